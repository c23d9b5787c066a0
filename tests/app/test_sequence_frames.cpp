// bounce sequence's frame pattern (-o) and frame range (--from, --to, --fps, --every), tested as
// plain code: names against printf's, counts against exact frame arithmetic.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "apps/bounce/frame_pattern.h"
#include "apps/bounce/frame_range.h"
#include "bounce/core/error.h"
#include "test_text.h"

namespace bounce::app {
namespace {

using test::contains;

// The message of the Error `f` throws ("" when it throws none).
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(FramePattern, NamesFramesAsPrintfWould) {
  // Each pattern with its printf-only form (%% already a percent sign), formatted by snprintf.
  const struct {
    const char* pattern;
    const char* printf_form;
  } cases[] = {
      {"out/frame_%04d.png", "out/frame_%04d.png"},
      {"%d.exr", "%d.exr"},
      {"a_%5d.pfm", "a_%5d.pfm"},
      {"a_%-5d.PNG", "a_%-5d.PNG"},
      {"f%i.png", "f%i.png"},
      {"f%u.png", "f%u.png"},
      {"f_%02d.png", "f_%02d.png"},
      {"f_%-04d.png", "f_%-4d.png"},
  };
  for (const auto& c : cases)
    for (const int k : {0, 7, 42, 12345, 2000000}) {
      char expected[256];
      std::snprintf(expected, sizeof expected, c.printf_form, k);
      EXPECT_EQ(FramePattern(c.pattern).name(k), expected) << c.pattern << " " << k;
    }
}

TEST(FramePattern, PercentPercentIsALiteralPercent) {
  const FramePattern p("100%%/take%%2_%03d.png");
  EXPECT_EQ(p.name(5), "100%/take%2_005.png");
  EXPECT_EQ(p.directory(), "100%");
}

TEST(FramePattern, DirectoryIsTheNamesParent) {
  EXPECT_EQ(FramePattern("out/walk/f_%d.png").directory(), "out/walk");
  EXPECT_EQ(FramePattern("/tmp/%d.png").directory(), "/tmp");
  EXPECT_EQ(FramePattern("%d.png").directory(), "");
}

TEST(FramePattern, RefusesWhatIsNotOneIntegerConversionInANameWithAnImageExtension) {
  const struct {
    const char* pattern;
    const char* problem;
  } cases[] = {
      {"", "empty"},
      {"out/frame.png", "no conversion"},
      {"out/frame_%%.png", "no conversion"},
      {"out/f_%d_%d.png", "2 conversions"},
      {"out/%d_%04d_%d.png", "3 conversions"},
      {"out/f_%s.png", "unsupported conversion '%s'"},
      {"out/f_%x.png", "unsupported conversion '%x'"},
      {"out/f_%04x.png", "unsupported conversion '%04x'"},
      {"out/f_%f.png", "unsupported conversion '%f'"},
      {"out/f_%ld.png", "unsupported conversion '%ld'"},
      {"out/f_%.3d.png", "unsupported conversion '%.3d'"},
      {"out/f_%+d.png", "unsupported conversion '%+d'"},
      {"out/f_%n.png", "unsupported conversion '%n'"},
      {"out/f_%", "incomplete conversion '%'"},
      {"out/f_%04", "incomplete conversion '%04'"},
      {"out/f_%99d.png", "width"},
      {"out/f_%100d.png", "width"},
      {"out/%04d/frame.png", "not in a directory"},
      {"out/f_%04d", "no extension"},
      {"out/f.%d", "no extension"},
      {"out/f_%04d.jpg", "unsupported extension '.jpg'"},
      {"out/f_%04d.png.tmp", "unsupported extension '.tmp'"},
  };
  for (const auto& c : cases) {
    const std::string message = error_of([&] { FramePattern p(c.pattern); });
    EXPECT_TRUE(contains(message, c.problem)) << c.pattern << ": " << message;
    EXPECT_TRUE(contains(message, fmt::format("'{}'", c.pattern))) << message;
  }
}

TEST(FrameRange, CountsFramesUpToAndIncludingTo) {
  EXPECT_EQ(make_frame_range(0.0, 0.2, 10.0, 1).count, 3);         // 2.0000000000000004 intervals
  EXPECT_EQ(make_frame_range(0.1, 0.3, 10.0, 1).count, 3);         // 1.9999999999999998 intervals
  EXPECT_EQ(make_frame_range(0.0, 0.20000001, 10.0, 1).count, 3);  // 2.0000001
  EXPECT_EQ(make_frame_range(0.0, 0.19999999, 10.0, 1).count, 3);  // 1.9999999
  EXPECT_EQ(make_frame_range(0.0, 0.25, 10.0, 1).count, 3);        // 2.5: no frame at 0.3
  EXPECT_EQ(make_frame_range(0.0, 0.15, 10.0, 1).count, 2);
  EXPECT_EQ(make_frame_range(0.0, 0.1999, 10.0, 1).count, 2);  // short of 2 by 1e-3 frames
  EXPECT_EQ(make_frame_range(1.0, 1.0, 30.0, 1).count, 1);
  EXPECT_EQ(make_frame_range(0.0, 4.0, 30.0, 1).count, 121);
}

TEST(FrameRange, CountMatchesExactArithmeticOverManyRanges) {
  // to = from + m / fps in floating point lands a rounding error either side of m intervals;
  // half an interval more must not add a frame.
  for (const double from : {0.0, 0.1, 1.0 / 3.0, 2.5, 17.3})
    for (const double fps : {7.0, 23.976, 24.0, 25.0, 29.97, 30.0, 60.0, 144.0})
      for (int m = 0; m <= 400; ++m) {
        EXPECT_EQ(make_frame_range(from, from + m / fps, fps, 1).count, m + 1)
            << from << " " << fps << " " << m;
        EXPECT_EQ(make_frame_range(from, from + (m + 0.5) / fps, fps, 1).count, m + 1)
            << from << " " << fps << " " << m;
      }
}

TEST(FrameRange, WarmupAndFrameNumbersFromZero) {
  // 0.5 s at 10 fps is frame 5 of a run from 0 s; 3 warm-up frames are frames 2, 3 and 4, at
  // the times that run renders them (k / fps, not from + k / fps).
  const FrameRange r = make_frame_range(0.5, 1.0, 10.0, 1, 3);
  EXPECT_EQ(r.origin, 5);
  EXPECT_EQ(r.warmup, 3);
  for (int64_t k = -3; k < r.count; ++k) {
    EXPECT_EQ(r.number(k), 5 + k);
    EXPECT_EQ(r.time(k), double(5 + k) / 10.0) << k;
  }
  // No frames before 0 s: the warm-up is cut to what a run from 0 s has.
  EXPECT_EQ(make_frame_range(0.2, 1.0, 10.0, 1, 30).warmup, 2);
  EXPECT_EQ(make_frame_range(0.0, 1.0, 10.0, 1, 30).warmup, 0);
  // Off the grid: times from `from`, numbers local, the warm-up within 0 s .. from.
  const FrameRange off = make_frame_range(0.25, 1.0, 10.0, 1, 5);
  EXPECT_EQ(off.origin, -1);
  EXPECT_EQ(off.warmup, 2);
  EXPECT_EQ(off.number(1), 1);
  EXPECT_DOUBLE_EQ(off.time(-2), 0.05);
  EXPECT_THROW(make_frame_range(0.0, 1.0, 10.0, 1, -1), Error);
}

TEST(FrameRange, TimesAndKeptFrames) {
  const FrameRange r = make_frame_range(0.5, 1.0, 10.0, 2);
  ASSERT_EQ(r.count, 6);
  for (int64_t k = 0; k < r.count; ++k) {
    EXPECT_DOUBLE_EQ(r.time(k), 0.5 + 0.1 * double(k));
    EXPECT_EQ(r.kept(k), k % 2 == 0);
  }
  EXPECT_EQ(r.kept_count(), 3);
  EXPECT_EQ(make_frame_range(0.0, 0.3, 10.0, 3).kept_count(), 2);  // frames 0 and 3
  EXPECT_EQ(make_frame_range(0.0, 0.2, 10.0, 5).kept_count(), 1);  // frame 0
}

TEST(FrameRange, RefusesBadValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const struct {
    double from, to, fps;
    int every;
    const char* problem;
  } cases[] = {
      {0, 1, 0, 1, "--fps must be"},
      {0, 1, -30, 1, "--fps must be"},
      {0, 1, nan, 1, "--fps must be"},
      {0, 1, inf, 1, "--fps must be"},
      {0, 1, 1000.5, 1, "--fps must be"},
      {0, 1, 30, 0, "--every must be at least 1, got 0"},
      {0, 1, 30, -2, "--every"},
      {-0.1, 1, 30, 1, "--from must be"},
      {nan, 1, 30, 1, "--from must be"},
      {inf, inf, 30, 1, "--from must be"},
      {0, nan, 30, 1, "--to must be"},
      {0, inf, 30, 1, "--to must be"},
      {2, 1, 30, 1, "--to 1 s is before --from 2 s"},
      {0, 10000, 30, 1, "300001 frames; at most 100000"},
  };
  for (const auto& c : cases) {
    const std::string message = error_of([&] { make_frame_range(c.from, c.to, c.fps, c.every); });
    EXPECT_TRUE(contains(message, c.problem))
        << c.from << " " << c.to << " " << c.fps << " " << c.every << ": " << message;
  }
  // The limit itself is allowed.
  EXPECT_EQ(make_frame_range(0.0, (kMaxSequenceFrames - 1) / 30.0, 30.0, 1).count,
            kMaxSequenceFrames);
  EXPECT_EQ(make_frame_range(0.0, 1.0, kMaxSequenceFps, 1).count, 1001);
}

}  // namespace
}  // namespace bounce::app
