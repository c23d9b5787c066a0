#include "bounce/render/primary_raster.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "bounce/core/lane.h"
#include "bounce/core/parallel.h"

namespace bounce {

namespace {

// Rows per band of the raster: each band's triangles are listed once, and a thread keeps the
// band's depths (4 bytes a pixel) in its cache while it draws them.
constexpr int kBandRows = 16;
// How far beyond the image (in half-widths and half-heights) triangles are drawn before they
// are clipped: keeps pixel coordinates small enough for float edge functions.
constexpr float kGuardBand = 8.0f;
// A pixel counts as covered where its sample lies within this many pixels outside an edge: more
// than the rounding of a projected vertex (about 1e-3 pixel at the guard band's edge), so two
// triangles sharing an edge overlap there instead of leaving a crack.
constexpr float kCoverMargin = 1.0f / 64.0f;
// Triangles are drawn in chunks of this many on each core.
constexpr uint32_t kChunk = 1024;

// A vertex in the camera's frame: x and y in units of the image plane's half-width and half-height
// at depth w (so x / w, y / w lie in [-1, 1] across the image), w the depth along the view axis.
struct ClipVertex {
  float x, y, w;
};

ClipVertex lerp(const ClipVertex& a, const ClipVertex& b, float s) {
  return {a.x + (b.x - a.x) * s, a.y + (b.y - a.y) * s, a.w + (b.w - a.w) * s};
}

// A convex polygon while it is clipped: a triangle gains at most one vertex per plane.
struct Polygon {
  std::array<ClipVertex, 12> v;
  int n = 0;
};

// Keeps the part of `in` where plane(v) >= 0 (Sutherland and Hodgman), into `out`.
template <typename Plane>
void clip_polygon(const Polygon& in, const Plane& plane, Polygon& out) {
  out.n = 0;
  for (int i = 0; i < in.n; ++i) {
    const ClipVertex& a = in.v[size_t(i)];
    const ClipVertex& b = in.v[size_t((i + 1) % in.n)];
    const float da = plane(a), db = plane(b);
    if (da >= 0.0f) out.v[size_t(out.n++)] = a;
    if ((da >= 0.0f) != (db >= 0.0f)) out.v[size_t(out.n++)] = lerp(a, b, da / (da - db));
  }
}

float cross2(vec2 a, vec2 b) {
  return a.x * b.y - a.y * b.x;
}

// Sets up the triangle of pixel-space points p (sample positions at integer coordinates) and
// their 1 / w; false where it covers no pixel of the w x h image or has no area.
bool set_up(const vec2 (&p)[3], const float (&inv_w)[3], int width, int height, uint32_t mesh,
            uint32_t triangle, RasterTriangle& r) {
  const float area2 = cross2(p[1] - p[0], p[2] - p[0]);
  if (!(area2 != 0.0f) || !std::isfinite(area2)) return false;
  const float lo_x = std::min({p[0].x, p[1].x, p[2].x}), hi_x = std::max({p[0].x, p[1].x, p[2].x});
  const float lo_y = std::min({p[0].y, p[1].y, p[2].y}), hi_y = std::max({p[0].y, p[1].y, p[2].y});
  r.x0 = int(std::max(std::floor(lo_x - kCoverMargin), 0.0f));
  r.y0 = int(std::max(std::floor(lo_y - kCoverMargin), 0.0f));
  r.x1 = int(std::min(std::ceil(hi_x + kCoverMargin), float(width - 1)));
  r.y1 = int(std::min(std::ceil(hi_y + kCoverMargin), float(height - 1)));
  if (r.x0 > r.x1 || r.y0 > r.y1) return false;
  const float s = area2 > 0.0f ? 1.0f : -1.0f;
  const vec2 o(float(r.x0), float(r.y0));
  const float span_x = float(r.x1 - r.x0 + 1), span_y = float(r.y1 - r.y0 + 1);
  for (int k = 0; k < 3; ++k) {
    const vec2 a = p[k] - o, b = p[(k + 1) % 3] - o;
    // s * cross(b - a, q - a) >= 0 inside: a x + b y + c.
    r.a[k] = -s * (b.y - a.y);
    r.b[k] = s * (b.x - a.x);
    r.c[k] = -(r.a[k] * a.x + r.b[k] * a.y);
    // The margin as a distance, plus the rounding of the sum over the box.
    r.margin[k] =
        kCoverMargin * std::sqrt(r.a[k] * r.a[k] + r.b[k] * r.b[k]) +
        1e-6f * (std::fabs(r.a[k]) * span_x + std::fabs(r.b[k]) * span_y + std::fabs(r.c[k]));
  }
  const vec2 q0 = p[0] - o, d1 = p[1] - p[0], d2 = p[2] - p[0];
  const float z1 = inv_w[1] - inv_w[0], z2 = inv_w[2] - inv_w[0];
  r.za = (z1 * d2.y - z2 * d1.y) / area2;
  r.zb = (z2 * d1.x - z1 * d2.x) / area2;
  r.zc = inv_w[0] - r.za * q0.x - r.zb * q0.y;
  r.mesh = mesh;
  r.triangle = triangle;
  return true;
}

// Draws the rows of triangle `r` within [band_y0, band_y1) into the band's depths (1 / w, 0
// where nothing is) and candidates, rows of `width` from band_y0: the nearest wins.
void draw(const RasterTriangle& r, uint32_t index, int band_y0, int band_y1, int width,
          float* depth, uint32_t* candidate) {
  const int y_from = std::max(r.y0, band_y0), y_to = std::min(r.y1, band_y1 - 1);
  for (int y = y_from; y <= y_to; ++y) {
    const float ry = float(y - r.y0);
    // The row's span: where every edge function is at least -margin (widened by a pixel for
    // the rounding of the division; the loop below tests each pixel).
    float lo = 0.0f, hi = float(r.x1 - r.x0);
    for (int k = 0; k < 3; ++k) {
      const float rest = r.b[k] * ry + r.c[k] + r.margin[k];
      if (r.a[k] > 0.0f)
        lo = std::max(lo, -rest / r.a[k] - 1.0f);
      else if (r.a[k] < 0.0f)
        hi = std::min(hi, -rest / r.a[k] + 1.0f);
      else if (rest < 0.0f)
        hi = -1.0f;
    }
    if (!(lo <= hi)) continue;
    const int x_from = r.x0 + int(std::ceil(lo)), x_to = r.x0 + int(std::floor(hi));
    float* row_depth = depth + size_t(y - band_y0) * size_t(width);
    uint32_t* row_candidate = candidate + size_t(y) * size_t(width);
    const RasterTriangle t = r;
    BOUNCE_IVDEP
    for (int x = x_from; x <= x_to; ++x) {
      const float rx = float(x - t.x0);
      const bool inside = (t.a[0] * rx + t.b[0] * ry + t.c[0] >= -t.margin[0]) &
                          (t.a[1] * rx + t.b[1] * ry + t.c[1] >= -t.margin[1]) &
                          (t.a[2] * rx + t.b[2] * ry + t.c[2] >= -t.margin[2]);
      const float z = t.za * rx + t.zb * ry + t.zc;
      const bool nearer = inside & (z > row_depth[x]);
      row_depth[x] = nearer ? z : row_depth[x];
      row_candidate[x] = nearer ? index : row_candidate[x];
    }
  }
}

}  // namespace

bool PrimaryRaster::build(const SceneView& scene, const CameraRays& camera, vec2 subpixel,
                          int width, int height) {
  const vec3 right = camera.right / glm::dot(camera.right, camera.right);
  const vec3 up = camera.up / glm::dot(camera.up, camera.up);
  const float diagonal = glm::length(scene.bounds.hi - scene.bounds.lo);
  // Depths below this are cut away; geometry nearer than that within the view would be missed,
  // and build refuses such a view (the G-buffer then traces every pixel).
  const float near = 1e-5f * std::max(std::isfinite(diagonal) ? diagonal : 1.0f, 1.0f);
  // The image's frustum planes widened by two pixels, for the cull.
  const float wide_x = 1.0f + 4.0f / float(width), wide_y = 1.0f + 4.0f / float(height);

  std::vector<uint32_t> first(scene.mesh_count + 1, 0);
  for (uint32_t m = 0; m < scene.mesh_count; ++m)
    first[m + 1] = first[m] + scene.meshes[m].triangle_count;
  const uint32_t total = first[scene.mesh_count];
  const uint32_t chunks = (total + kChunk - 1) / kChunk;
  std::vector<std::vector<RasterTriangle>> pieces(chunks);
  std::atomic<bool> too_close{false};
  tbb::parallel_for(uint32_t(0), chunks, [&](uint32_t chunk) {
    std::vector<RasterTriangle>& out = pieces[chunk];
    const uint32_t end = std::min(total, (chunk + 1) * kChunk);
    uint32_t m =
        uint32_t(std::upper_bound(first.begin(), first.end(), chunk * kChunk) - first.begin()) - 1;
    for (uint32_t g = chunk * kChunk; g < end; ++g) {
      while (g >= first[m + 1]) ++m;
      const MeshView& mesh = scene.meshes[m];
      const uint32_t t = g - first[m];
      const uvec3 tri = mesh.triangles[t];
      Polygon poly;
      poly.n = 3;
      uint32_t outside_all = 0x1F, outside_any = 0;
      for (int k = 0; k < 3; ++k) {
        const vec3 d = mesh.positions[tri[k]] - camera.origin;
        const ClipVertex v{glm::dot(d, right), glm::dot(d, up), glm::dot(d, camera.forward)};
        poly.v[size_t(k)] = v;
        // Outside the near plane; the (widened) image's sides; the guard band.
        const uint32_t code = (v.w < near ? 1u : 0u) | (v.x > wide_x * v.w ? 2u : 0u) |
                              (-v.x > wide_x * v.w ? 4u : 0u) | (v.y > wide_y * v.w ? 8u : 0u) |
                              (-v.y > wide_y * v.w ? 16u : 0u);
        const bool guard = std::fabs(v.x) > kGuardBand * v.w || std::fabs(v.y) > kGuardBand * v.w;
        outside_all &= code;
        outside_any |= code | (guard ? 32u : 0u);
      }
      if (outside_all & ~1u) continue;  // wholly outside one of the image's sides
      if (outside_any & 1u) {
        // The part nearer than the near plane (in front of the eye) must lie outside the view.
        Polygon a, b;
        clip_polygon(
            poly, [&](const ClipVertex& v) { return near - v.w; }, a);
        clip_polygon(
            a, [](const ClipVertex& v) { return v.w; }, b);
        clip_polygon(
            b, [&](const ClipVertex& v) { return wide_x * v.w - v.x; }, a);
        clip_polygon(
            a, [&](const ClipVertex& v) { return wide_x * v.w + v.x; }, b);
        clip_polygon(
            b, [&](const ClipVertex& v) { return wide_y * v.w - v.y; }, a);
        clip_polygon(
            a, [&](const ClipVertex& v) { return wide_y * v.w + v.y; }, b);
        if (b.n > 0) too_close = true;
        if (outside_all & 1u) continue;  // wholly nearer than the near plane
      }
      if (outside_any & (1u | 32u)) {
        Polygon a, b;
        clip_polygon(
            poly, [&](const ClipVertex& v) { return v.w - near; }, a);
        clip_polygon(
            a, [](const ClipVertex& v) { return kGuardBand * v.w - v.x; }, b);
        clip_polygon(
            b, [](const ClipVertex& v) { return kGuardBand * v.w + v.x; }, a);
        clip_polygon(
            a, [](const ClipVertex& v) { return kGuardBand * v.w - v.y; }, b);
        clip_polygon(
            b, [](const ClipVertex& v) { return kGuardBand * v.w + v.y; }, poly);
      }
      // Pixel coordinates with the samples at integers; a fan over the clipped polygon.
      vec2 p[12];
      float inv_w[12];
      for (int k = 0; k < poly.n; ++k) {
        const ClipVertex& v = poly.v[size_t(k)];
        inv_w[k] = 1.0f / v.w;
        p[k] = vec2((v.x * inv_w[k] + 1.0f) * 0.5f * float(width) - subpixel.x,
                    (1.0f - v.y * inv_w[k]) * 0.5f * float(height) - subpixel.y);
      }
      for (int k = 1; k + 1 < poly.n; ++k) {
        const vec2 q[3] = {p[0], p[k], p[k + 1]};
        const float z[3] = {inv_w[0], inv_w[k], inv_w[k + 1]};
        RasterTriangle r;
        if (set_up(q, z, width, height, m, t, r)) out.push_back(r);
      }
    }
  });
  if (too_close) return false;
  triangles_.clear();
  for (const auto& piece : pieces) triangles_.insert(triangles_.end(), piece.begin(), piece.end());

  // Each band's triangles, in the order above (ties in depth go to the first: deterministic).
  const int bands = (height + kBandRows - 1) / kBandRows;
  band_start_.assign(size_t(bands) + 1, 0);
  for (const RasterTriangle& r : triangles_)
    for (int band = r.y0 / kBandRows; band <= r.y1 / kBandRows; ++band)
      ++band_start_[size_t(band) + 1];
  for (int band = 0; band < bands; ++band)
    band_start_[size_t(band) + 1] += band_start_[size_t(band)];
  band_list_.resize(band_start_[size_t(bands)]);
  std::vector<uint32_t> fill(band_start_.begin(), band_start_.end() - 1);
  for (uint32_t i = 0; i < uint32_t(triangles_.size()); ++i)
    for (int band = triangles_[i].y0 / kBandRows; band <= triangles_[i].y1 / kBandRows; ++band)
      band_list_[fill[size_t(band)]++] = i;

  candidate_.assign(size_t(width) * size_t(height), kNone);
  parallel_for(
      size_t(bands),
      [&](size_t band) {
        thread_local std::vector<float> depth;
        depth.assign(size_t(kBandRows) * size_t(width), 0.0f);
        const int y0 = int(band) * kBandRows, y1 = std::min(y0 + kBandRows, height);
        for (uint32_t k = band_start_[band]; k < band_start_[band + 1]; ++k)
          draw(triangles_[band_list_[k]], band_list_[k], y0, y1, width, depth.data(),
               candidate_.data());
      },
      1);
  return true;
}

}  // namespace bounce
