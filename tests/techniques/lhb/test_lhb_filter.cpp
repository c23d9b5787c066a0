// The lhb filter's row loop for a one-pixel window against the windowed discontinuity filter it
// stands in for, on pixels with and without surfaces.
#include <gtest/gtest.h>

#include <vector>

#include "bounce/core/rng.h"
#include "bounce/render/gbuffer.h"
#include "bounce/techniques/lhb/lhb_kernels.h"

namespace bounce {
namespace {

TEST(LhbFilter, OnePixelWindowRowsEqualTheWindowedFilter) {
  const int w = 37, h = 5;  // a width that is not a multiple of the vector length
  GBuffer g;
  g.resize(w, h);
  Pcg32 rng(9);
  std::vector<vec3> incoming(size_t(w * h));
  for (size_t i = 0; i < incoming.size(); ++i) {
    const bool hit = rng.next_float() < 0.8f;
    g.primitive[i] = hit ? uint32_t(i) : kNoPrimitive;
    g.albedo[i] = vec3(rng.next_float(), rng.next_float(), rng.next_float());
    g.normal[i] = vec3(0.0f, 1.0f, 0.0f);
    g.position[i] = vec3(float(i), 0.0f, 0.0f);
    g.depth[i] = 1.0f;
    incoming[i] = 3.0f * vec3(rng.next_float(), rng.next_float(), rng.next_float());
  }
  const ConstGBufferView view = g.view();
  std::vector<vec3> rows(incoming.size(), vec3(-1.0f));
  for (int y = 0; y < h; ++y) {
    const size_t row = size_t(y) * size_t(w);
    lhb_albedo_times_incoming(view.albedo + row, view.primitive + row, incoming.data() + row,
                              rows.data() + row, w);
  }
  int misses = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = view.index(x, y);
      const vec3 want = lhb_discontinuity_pixel(view, incoming.data(), x, y, 1, 0.9f, 0.05f);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(rows[i][c], want[c]) << x << ", " << y;
      misses += !view.hit(i);
    }
  EXPECT_GT(misses, 0);
}

}  // namespace
}  // namespace bounce
