// The temporal pass's reprojection kernels on random frames: the bilinear footprint at the
// image's borders, and the CPU's eight-pixel reprojection (denoise_reproject_cpu.h) against the
// per-pixel kernel every backend shares (denoise_temporal.h's reproject_moved), the light's
// history and the modulation's alike.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include "bounce/core/rng.h"
#include "bounce/render/denoise_reproject_cpu.h"

namespace bounce::denoise {
namespace {

// A last frame of prev_w x prev_h pixels and this frame of w x h, filled at random: three
// objects, depths near 2, normals that mostly agree, motion from sub-pixel to far outside.
struct RandomFrames {
  int w, h, prev_w, prev_h;
  std::vector<vec2> motion;
  std::vector<float> depth;
  std::vector<vec3> normal;
  std::vector<uint32_t> mesh, primitive;
  // Depth and the eight history planes; the packed planes (normal, length, modulation).
  std::vector<float> prev_plane[9];
  std::vector<uint32_t> prev_object, prev_words[PackedPlanes::kCount];
  TemporalPass p;

  RandomFrames(int w_, int h_, int pw, int ph, uint64_t seed)
      : w(w_), h(h_), prev_w(pw), prev_h(ph) {
    Pcg32 rng(seed);
    auto u = [&] { return rng.next_float(); };
    const size_t n = size_t(w) * size_t(h), prev_n = size_t(pw) * size_t(ph);
    motion.resize(n);
    depth.resize(n);
    normal.resize(n);
    mesh.resize(n);
    primitive.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const float far = u() < 0.05f ? 40.0f : 3.0f;  // some pixels come from outside the image
      motion[i] = vec2(far * (2.0f * u() - 1.0f), far * (2.0f * u() - 1.0f));
      depth[i] = 2.0f + 0.2f * u();
      normal[i] = glm::normalize(vec3(0.3f * u(), 1.0f, 0.3f * u()));
      mesh[i] = uint32_t(u() * 3.0f);
      primitive[i] = u() < 0.05f ? kNoPrimitive : mesh[i] * 7u;
    }
    for (auto& plane : prev_plane) plane.resize(prev_n);
    prev_object.resize(prev_n);
    PackedPlanes packed;
    for (int k = 0; k < PackedPlanes::kCount; ++k) {
      prev_words[k].resize(prev_n);
      packed.w[k] = prev_words[k].data();
    }
    for (size_t i = 0; i < prev_n; ++i) {
      prev_plane[0][i] = 2.0f + 0.2f * u();
      // (Signed components, which the halves' decoding must keep.)
      const vec3 nn =
          glm::normalize(vec3(0.6f * (2.0f * u() - 1.0f), 1.0f, 0.6f * (2.0f * u() - 1.0f)));
      for (int c = 1; c < 9; ++c) prev_plane[c][i] = 10.0f * u();
      const float length = 40.0f * u();
      const vec3 factor(u(), u(), u()), emission(10.0f * u(), 10.0f * u(), 10.0f * u());
      packed.set(i, nn, length, factor, emission);
      prev_object[i] = uint32_t(u() * 3.0f);
    }
    p.g.motion = motion.data();
    p.g.depth = depth.data();
    p.g.normal = normal.data();
    p.g.mesh = mesh.data();
    p.g.primitive = primitive.data();
    // (The reprojection reads depth and objects of the surfaces, the normals from the packed
    // planes.)
    p.prev_surface =
        ConstSurfacePlanes{prev_plane[0].data(), nullptr, nullptr, nullptr, prev_object.data()};
    p.prev_packed = packed;
    for (int c = 0; c < 8; ++c) p.prev.c[c] = prev_plane[1 + c].data();
    p.width = w;
    p.height = h;
    p.prev_width = pw;
    p.prev_height = ph;
    p.s.history = true;
    p.s.reproject = true;
    p.s.depth_tolerance = 0.05f;
    p.s.normal_tolerance = 0.9f;
    p.s.cap_indirect = 4.0f;  // indirect light keeps a history (keeps_indirect)
  }
};

TEST(Reprojection, FootprintWeighsOnlyPixelsInsideTheImage) {
  RandomFrames f(4, 3, 4, 3, 1);
  // Pixel (0, 0) moved from half a pixel left and up of the image: the footprint's only pixel
  // inside is (0, 0), with a quarter of the weight.
  f.motion[0] = vec2(0.5f, 0.5f);
  BilinearTaps t = bilinear_taps(f.p, 0, 0, 0);
  EXPECT_EQ(t.q, 0);
  EXPECT_FLOAT_EQ(t.w[0], 0.25f);
  EXPECT_EQ(t.w[1] + t.w[2] + t.w[3], 0.0f);
  // Pixel (3, 2) from half a pixel right and down of the image: (3, 2) again, the block's last.
  f.motion[11] = vec2(-0.5f, -0.5f);
  t = bilinear_taps(f.p, 3, 2, 11);
  EXPECT_EQ(t.q, 1 * 4 + 2);  // the block (2..3, 1..2)
  EXPECT_FLOAT_EQ(t.w[3], 0.25f);
  EXPECT_EQ(t.w[0] + t.w[1] + t.w[2], 0.0f);
  // Inside: the four weights are the bilinear ones and sum to 1.
  f.motion[5] = vec2(0.25f, 0.75f);  // pixel (1, 1) from (0.75, 0.25) + 0.5
  t = bilinear_taps(f.p, 1, 1, 5);
  EXPECT_EQ(t.q, 0);
  EXPECT_FLOAT_EQ(t.w[0], 0.25f * 0.75f);
  EXPECT_FLOAT_EQ(t.w[1], 0.75f * 0.75f);
  EXPECT_FLOAT_EQ(t.w[2], 0.25f * 0.25f);
  EXPECT_FLOAT_EQ(t.w[3], 0.75f * 0.25f);
  // Far outside: nothing.
  f.motion[5] = vec2(1e30f, -1e30f);
  t = bilinear_taps(f.p, 1, 1, 5);
  EXPECT_EQ(t.w[0] + t.w[1] + t.w[2] + t.w[3], 0.0f);
}

TEST(Reprojection, OnePixelWideOrHighImagesReadOnlyTheirPixels) {
  for (const auto& [pw, ph] : {std::pair{1, 5}, std::pair{5, 1}, std::pair{1, 1}}) {
    RandomFrames f(3, 3, pw, ph, 2);
    for (int y = 0; y < 3; ++y) {
      for (int x = 0; x < 3; ++x) {
        const size_t i = size_t(y) * 3 + size_t(x);
        const BilinearTaps t = bilinear_taps(f.p, x, y, i);
        for (int k = 0; k < 4; ++k) {
          const int q = t.q + (k & 1) * t.dq_x + (k >> 1) * t.dq_y;
          EXPECT_GE(q, 0);
          EXPECT_LT(q, pw * ph);
        }
        // The footprint's weight inside the image is at most 1, and never negative.
        const float sum = t.w[0] + t.w[1] + t.w[2] + t.w[3];
        EXPECT_GE(sum, 0.0f);
        EXPECT_LE(sum, 1.0f + 1e-6f);
      }
    }
  }
}

TEST(Reprojection, EightPixelsAtOnceEqualThePerPixelKernel) {
  if (!BOUNCE_REPROJECT_EIGHT) GTEST_SKIP() << "built without AVX2";
  // The same size, a change of size (the viewer's resolution scaler), and a 2-pixel-wide last
  // frame; widths that leave a tail the per-pixel kernel takes.
  // With indirect light's history kept, and without (a cap of 0: its planes are not read and
  // both kernels leave zeros).
  for (const auto& [w, h, pw, ph, cap] :
       {std::tuple{37, 9, 37, 9, 4.0f}, std::tuple{64, 7, 40, 5, 4.0f},
        std::tuple{16, 4, 2, 2, 4.0f}, std::tuple{24, 3, 50, 8, 4.0f},
        std::tuple{37, 9, 37, 9, 0.0f}}) {
    RandomFrames f(w, h, pw, ph, uint64_t(w * 100 + pw));
    f.p.s.cap_indirect = cap;
    ASSERT_TRUE(reproject_eight_fits(f.p));
    std::vector<float> planes(kReprojectedPlanes * size_t(w)), tap_planes(7 * size_t(w));
    std::vector<int> tap_q(static_cast<size_t>(w));
    ReprojectedRow row;
    for (int c = 0; c < kReprojectedPlanes; ++c) row.v[c] = planes.data() + size_t(c) * size_t(w);
    const TapRow taps = TapRow::over(tap_q.data(), tap_planes.data(), size_t(w));
    int kept = 0, dropped = 0, indirect_read = 0;
    for (int y = 0; y < h; ++y) {
      const size_t first = size_t(y) * size_t(w);
      for (int x = 0; x < w; ++x) taps.store(f.p, x, y, first + size_t(x));
#if BOUNCE_REPROJECT_EIGHT
      for (int x = 0; x + 8 <= w; x += 8) reproject_eight(f.p, taps, x, y, row);
#endif
      for (int x = 0; x + 8 <= w; ++x) {
        const Reprojected want = reproject_moved(f.p, x, y, first + size_t(x));
        const Reprojected got = load_reprojected(row.v, x);
        ASSERT_EQ(got.kept, want.kept) << x << ", " << y;
        (want.kept ? kept : dropped) += 1;
        // (The same operations in the same order; a compiler that does not fuse the per-pixel
        // kernel's multiply-adds rounds differently in the last place.)
        for (int c = 0; c < 4; ++c) {
          EXPECT_NEAR(got.h.direct[c], want.h.direct[c],
                      1e-5f * (1.0f + std::fabs(want.h.direct[c])));
          EXPECT_NEAR(got.h.indirect[c], want.h.indirect[c],
                      1e-5f * (1.0f + std::fabs(want.h.indirect[c])));
          if (cap == 0.0f) {
            EXPECT_EQ(got.h.indirect[c], 0.0f);
          } else if (want.kept) {
            indirect_read += want.h.indirect[c] != 0.0f;
          }
        }
        EXPECT_NEAR(got.length, want.length, 1e-5f * (1.0f + want.length));
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(got.factor[c], want.factor[c], 1e-5f * (1.0f + std::fabs(want.factor[c])));
          EXPECT_NEAR(got.emission[c], want.emission[c],
                      1e-5f * (1.0f + std::fabs(want.emission[c])));
        }
      }
    }
    // The frames exercise both outcomes, and the kept history's indirect light where it is kept.
    EXPECT_GT(kept, 0);
    EXPECT_GT(dropped, 0);
    if (cap > 0.0f) {
      EXPECT_GT(indirect_read, 0);
    }
  }
}

}  // namespace
}  // namespace bounce::denoise

namespace bounce::denoise {
namespace {

// The CPU's packing of a row after the blend (pack_row, F16C where the CPU has it) writes the
// words PackedPlanes::set does, outliers included (huge, tiny, negative, infinite values), at
// widths that leave a tail.
TEST(Reprojection, ARowPacksAsEachPixelDoes) {
  for (const int w : {8, 13, 37}) {
    const int h = 2;
    const size_t n = size_t(w) * size_t(h);
    Pcg32 rng{uint64_t(w)};
    std::vector<float> plane[10];
    for (auto& v : plane) {
      v.resize(n);
      for (float& f : v) {
        const float u = rng.next_float();
        f = u < 0.1f    ? 1e6f
            : u < 0.2f  ? 1e-6f
            : u < 0.3f  ? -3.0f * rng.next_float()
            : u < 0.35f ? std::numeric_limits<float>::infinity()
                        : 70000.0f * rng.next_float() * rng.next_float() * rng.next_float();
      }
    }
    std::vector<uint32_t> got[PackedPlanes::kCount], want[PackedPlanes::kCount];
    TemporalPass p;
    PackedPlanes want_planes;
    for (int k = 0; k < PackedPlanes::kCount; ++k) {
      got[k].assign(n, 0u);
      want[k].assign(n, 0u);
      p.packed.w[k] = got[k].data();
      want_planes.w[k] = want[k].data();
    }
    p.surface.nx = plane[0].data();
    p.surface.ny = plane[1].data();
    p.surface.nz = plane[2].data();
    p.length = plane[3].data();
    p.rest.factor = {plane[4].data(), plane[5].data(), plane[6].data()};
    p.rest.emission = {plane[7].data(), plane[8].data(), plane[9].data()};
    p.width = w;
    p.height = h;
    for (int y = 0; y < h; ++y) pack_row(p, y);
    for (size_t i = 0; i < n; ++i)
      want_planes.set(i, vec3(plane[0][i], plane[1][i], plane[2][i]), plane[3][i],
                      p.rest.factor.get(i), p.rest.emission.get(i));
    for (int k = 0; k < PackedPlanes::kCount; ++k)
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(got[k][i], want[k][i]) << w << " " << k << " " << i;
  }
}

}  // namespace
}  // namespace bounce::denoise
