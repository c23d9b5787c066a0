// The output name of numbered frames (bounce sequence -o): a printf-style pattern with exactly one
// integer conversion for the frame number, e.g. "out/walk/frame_%04d.png". It is checked once,
// before anything renders, and then formatted without printf, so no user text reaches a format
// function.
#pragma once

#include <cstdint>
#include <string>

namespace bounce::app {

class FramePattern {
 public:
  // Accepts %d, %i or %u with an optional '0' or '-' flag and a width (%04d, %5d, %-3d); %% is a
  // literal percent. The conversion must be in the file name, not the directory, and the name
  // must end in .png, .exr or .pfm after it. Throws Error naming the pattern and the problem.
  explicit FramePattern(const std::string& pattern);

  // The file name of frame `index` (>= 0).
  std::string name(int64_t index) const;
  const std::string& pattern() const { return pattern_; }
  // The directory the frames go to, with %% already turned into %; empty: the working directory.
  const std::string& directory() const { return directory_; }

 private:
  std::string pattern_;
  std::string prefix_, suffix_;  // literal text before and after the conversion
  std::string directory_;
  int width_ = 0;
  bool zero_pad_ = false;
  bool left_align_ = false;
};

}  // namespace bounce::app
