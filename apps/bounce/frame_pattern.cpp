#include "frame_pattern.h"

#include <cctype>
#include <cstring>
#include <filesystem>

#include "bounce/core/error.h"

namespace bounce::app {

namespace {

constexpr int kMaxWidth = 32;  // wider than any frame number; stops absurd names
constexpr const char* kHint = "the frame number takes %d, %Nd or %0Nd; %% is a literal percent";

bool is_flag(char c) {
  return std::strchr("-+ #0'", c) != nullptr;
}
bool is_length(char c) {
  return std::strchr("hlLqjzt", c) != nullptr;
}
bool is_digit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

}  // namespace

FramePattern::FramePattern(const std::string& pattern) : pattern_(pattern) {
  const auto bad = [&](const std::string& problem) { fail("-o '{}': {}", pattern, problem); };
  if (pattern.empty()) bad("the pattern is empty");
  std::string literal;  // the text read so far, %% turned into %
  int conversions = 0;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      literal += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      literal += '%';
      ++i;
      continue;
    }
    // A conversion as printf reads one: flags, width, precision, length, then a letter. Only
    // the integer forms of the frame number pass; the rest is read so the message can quote it.
    size_t j = i + 1;
    std::string flags;
    while (j < pattern.size() && is_flag(pattern[j])) flags += pattern[j++];
    std::string width;
    while (j < pattern.size() && is_digit(pattern[j])) width += pattern[j++];
    bool precision = false;
    if (j < pattern.size() && pattern[j] == '.') {
      precision = true;
      ++j;
      while (j < pattern.size() && is_digit(pattern[j])) ++j;
    }
    bool length = false;
    while (j < pattern.size() && is_length(pattern[j])) {
      length = true;
      ++j;
    }
    if (j >= pattern.size())
      bad(fmt::format("it ends in an incomplete conversion '{}' ({})", pattern.substr(i), kHint));
    const std::string spec = pattern.substr(i, j - i + 1);
    const bool integer = std::strchr("diu", pattern[j]) != nullptr;
    if (!integer || precision || length || flags.find_first_not_of("-0") != std::string::npos)
      bad(fmt::format("unsupported conversion '{}' ({})", spec, kHint));
    i = j;
    if (++conversions > 1) continue;  // counted, and reported below
    if (width.size() > 2 || std::stoi("0" + width) > kMaxWidth)
      bad(fmt::format("the width of '{}' is over {}", spec, kMaxWidth));
    width_ = std::stoi("0" + width);
    left_align_ = flags.find('-') != std::string::npos;
    zero_pad_ = !left_align_ && flags.find('0') != std::string::npos;
    prefix_ = literal;
    literal.clear();
  }
  if (conversions == 0)
    bad("there is no conversion for the frame number (e.g. frame_%04d.png; " + std::string(kHint) +
        ")");
  if (conversions > 1)
    bad(fmt::format("there are {} conversions; exactly one, for the frame number, is allowed ({})",
                    conversions, kHint));
  suffix_ = literal;
  if (suffix_.find('/') != std::string::npos)
    bad("the frame number must be in the file name, not in a directory name");
  const size_t dot = suffix_.rfind('.');
  if (dot == std::string::npos)
    bad("the name has no extension after the frame number (expected .png, .exr or .pfm)");
  std::string ext = suffix_.substr(dot);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png" && ext != ".exr" && ext != ".pfm")
    bad(fmt::format("unsupported extension '{}' (expected .png, .exr or .pfm)",
                    suffix_.substr(dot)));
  directory_ = std::filesystem::path(prefix_ + suffix_).parent_path().string();
}

std::string FramePattern::name(int64_t index) const {
  std::string number = std::to_string(index);
  const size_t width = size_t(width_);
  if (number.size() < width) {
    const std::string pad(width - number.size(), zero_pad_ ? '0' : ' ');
    number = left_align_ ? number + pad : pad + number;
  }
  return prefix_ + number + suffix_;
}

}  // namespace bounce::app
