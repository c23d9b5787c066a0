#include "bounce/scene/quake/patch.h"

#include "bounce/core/error.h"

namespace bounce::quake {

namespace {

PatchVertex control_point(const BspVertex& v) {
  return {vec3(v.position[0], v.position[1], v.position[2]),
          vec3(v.normal[0], v.normal[1], v.normal[2]), vec2(v.uv[0], v.uv[1])};
}

// Point (k, m) of the patch whose control points are c[row][column], k across and m down.
PatchVertex evaluate(const PatchVertex c[3][3], int k, int m, int level) {
  PatchVertex row[3];
  for (int j = 0; j < 3; ++j) {
    row[j].position = bezier_step(c[j][0].position, c[j][1].position, c[j][2].position, k, level);
    row[j].normal = bezier_step(c[j][0].normal, c[j][1].normal, c[j][2].normal, k, level);
    row[j].uv = bezier_step(c[j][0].uv, c[j][1].uv, c[j][2].uv, k, level);
  }
  PatchVertex p;
  p.position = bezier_step(row[0].position, row[1].position, row[2].position, m, level);
  p.uv = bezier_step(row[0].uv, row[1].uv, row[2].uv, m, level);
  const vec3 n = bezier_step(row[0].normal, row[1].normal, row[2].normal, m, level);
  const float length = glm::length(n);
  p.normal = length > 1e-12f ? n / length : vec3(0.0f);
  return p;
}

}  // namespace

void tessellate_patch(std::span<const BspVertex> controls, int width, int height, int level,
                      PatchMesh& out) {
  if (level < 1 || level > kMaxPatchLevel)
    fail("patch tessellation level {} is outside [1, {}]", level, kMaxPatchLevel);
  if (width < 3 || height < 3 || width % 2 == 0 || height % 2 == 0 ||
      controls.size() != size_t(width) * size_t(height))
    fail("a patch control grid of {} x {} with {} points is malformed", width, height,
         controls.size());
  const int across = (width - 1) / 2, down = (height - 1) / 2;
  // One grid of vertices for the whole face: neighbouring patches share their border vertices.
  const int columns = across * level + 1, rows = down * level + 1;
  const uint32_t base = uint32_t(out.vertices.size());
  out.vertices.reserve(out.vertices.size() + size_t(columns) * size_t(rows));
  for (int r = 0; r < rows; ++r) {
    const int py = std::min(r / level, down - 1), m = r - py * level;
    for (int c = 0; c < columns; ++c) {
      const int px = std::min(c / level, across - 1), k = c - px * level;
      PatchVertex ctrl[3][3];
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          ctrl[j][i] =
              control_point(controls[size_t(2 * py + j) * size_t(width) + size_t(2 * px + i)]);
      out.vertices.push_back(evaluate(ctrl, k, m, level));
    }
  }
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c + 1 < columns; ++c) {
      const uint32_t a = base + uint32_t(r * columns + c), b = a + 1;
      const uint32_t d = a + uint32_t(columns), e = d + 1;
      // The map's own triangles face the side their winding turns clockwise from (Quake's
      // convention); across the grid that is (a, b, d), (b, e, d) with rows running down.
      out.triangles.push_back({a, b, d});
      out.triangles.push_back({b, e, d});
    }
  }
}

}  // namespace bounce::quake
