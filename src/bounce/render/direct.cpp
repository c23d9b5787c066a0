#include "bounce/render/direct.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <memory>
#include <span>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/scene/bounds.h"

namespace bounce {

// Shadow rays wait here with the radiance they carry until a batch is traced at once: the
// Tracer's stream call is what makes this stage fast on the CPU.
struct ShadowBatch {
  static constexpr size_t kCapacity = 1024;
  // Fixed arrays and a count: a vector's push_back checked its capacity three times per ray.
  std::unique_ptr<Ray[]> rays{new Ray[kCapacity]};
  std::unique_ptr<vec3[]> radiance{new vec3[kCapacity]};
  std::unique_ptr<vec3* []> target { new vec3*[kCapacity] };  // the pixel its light adds to
  std::unique_ptr<uint8_t[]> blocked{new uint8_t[kCapacity]};
  size_t size = 0;
  uint64_t traced = 0;

  // Queues a ray whose light adds to `to` if clear; a full batch is traced at once.
  void add(const Ray& ray, vec3 ray_radiance, vec3* to, const Tracer& tracer) {
    rays[size] = ray;
    radiance[size] = ray_radiance;
    target[size] = to;
    if (++size == kCapacity) flush(tracer);
  }

  void flush(const Tracer& tracer) {
    tracer.occluded(std::span<const Ray>(rays.get(), size),
                    std::span<uint8_t>(blocked.get(), size));
    traced += size;
    for (size_t k = 0; k < size; ++k)
      if (!blocked[k]) *target[k] += radiance[k];
    size = 0;
  }
};

namespace {

constexpr int kRowWidth = 32;  // the row loop's tiles are this wide and tall

// A vec3 for each pixel of a row as three planes: the row loops then load and store whole
// vectors (from an array of vec3, GCC gathers every component with shuffles).
struct Row3 {
  float x[kRowWidth], y[kRowWidth], z[kRowWidth];

  BOUNCE_LANE_INLINE vec3 operator[](int j) const { return {x[j], y[j], z[j]}; }
  BOUNCE_LANE_INLINE void set(int j, vec3 v) {
    x[j] = v.x;
    y[j] = v.y;
    z[j] = v.z;
  }
};

// The same for a vec2.
struct Row2 {
  float x[kRowWidth], y[kRowWidth];

  BOUNCE_LANE_INLINE vec2 operator[](int j) const { return {x[j], y[j]}; }
  BOUNCE_LANE_INLINE void set(int j, vec2 v) {
    x[j] = v.x;
    y[j] = v.y;
  }
};

// The lane surfaces (lane_surface) of a row's pixels as planes, read from the G-buffer once for
// all the row's lights.
struct RowSurfaces {
  Row3 origin, normal, geometric_normal, albedo, f0, wo;
  float roughness[kRowWidth];
  uint32_t hit[kRowWidth];  // whether the G-buffer has a surface there
  // A sphere around the origins of the pixels that have a surface (radius < 0: none has).
  vec3 centre;
  float radius;

  // Returns whether any of them reflects specularly (f0 > 0: lane_shade's kGlossy).
  bool load(const ConstGBufferView& g, size_t i0, int n, vec3 eye) {
    uint32_t glossy = 0;
    BOUNCE_IVDEP
    for (int j = 0; j < n; ++j) {
      const size_t i = i0 + size_t(j);
      const LaneSurface s = lane_surface(g, i, eye);
      origin.set(j, s.origin);
      normal.set(j, s.normal);
      geometric_normal.set(j, s.geometric_normal);
      albedo.set(j, s.albedo);
      f0.set(j, s.f0);
      wo.set(j, s.wo);
      roughness[j] = s.roughness;
      hit[j] = uint32_t(g.primitive[i] != kNoPrimitive);
      glossy |= uint32_t(max_component(s.f0) > 0.0f);
    }
    Bounds bounds;
    for (int j = 0; j < n; ++j)
      if (hit[j]) bounds.extend(origin[j]);
    centre = bounds.centre();
    radius = bounds.empty() ? -1.0f : 0.5f * bounds.diagonal();
    return glossy != 0;
  }

  // Whether spot light l sends none of these pixels light (sphere_outside_spot): then its
  // samples carry nothing, and skipping them leaves every selection and batch as it was.
  bool outside(const PunctualLane& l) const {
    return radius < 0.0f || sphere_outside_spot(l, centre, radius);
  }

  BOUNCE_LANE_INLINE LaneSurface operator[](int j) const {
    LaneSurface s;
    s.origin = origin[j];
    s.normal = normal[j];
    s.geometric_normal = geometric_normal[j];
    s.albedo = albedo[j];
    s.f0 = f0[j];
    s.roughness = roughness[j];
    s.wo = wo[j];
    return s;
  }
};

// A row of up to kWidth pixels of one tile, for the row loop (compute_direct).
struct LightRow {
  static constexpr int kWidth = kRowWidth;
  // The pattern's rotation at each pixel for the current area light, and each pixel's sample of
  // the pattern, as planes (x, y): the loop that makes the samples then vectorises.
  Row2 offset, u;
  uint32_t base[kWidth];
  Row3 q, q_normal;
  Row3 wi, radiance;
  float distance[kWidth];
};

// The row's shadow selections (ShadowSelection's state as planes), so that each light's samples
// are offered to the row's pixels in one loop the compiler vectorises.
struct RowSelection {
  static constexpr int kWidth = LightRow::kWidth;
  uint32_t seed[kWidth], offers[kWidth];
  float kept[kWidth], total[kWidth], distance[kWidth];
  Row3 wi, radiance;

  void start(uint32_t i0, int width, const DirectSettings& settings) {
    for (int j = 0; j < width; ++j) {
      seed[j] = ShadowSelection::for_pixel(i0 + uint32_t(j), settings).seed;
      offers[j] = 0;
      kept[j] = total[j] = distance[j] = 0.0f;
      wi.set(j, vec3(0.0f));
      radiance.set(j, vec3(0.0f));
    }
  }

  // Offers the row's samples of one light (ShadowSelection::operator() per pixel, as selects).
  void offer(const LightRow& row, int width) {
    BOUNCE_IVDEP
    for (int j = 0; j < width; ++j) {
      const vec3 r = row.radiance[j];
      const float w = luminance(r);
      const bool carries = w > 0.0f;
      const float sum = total[j] + pick(carries, w, 0.0f);
      const bool take =
          carries & reservoir_takes(ShadowSelection::u(seed[j], offers[j]), sum, w, kept[j]);
      offers[j] += uint32_t(carries);
      total[j] = sum;
      kept[j] = pick(take, w, kept[j]);
      distance[j] = pick(take, row.distance[j], distance[j]);
      wi.set(j, pick(take, row.wi[j], wi[j]));
      radiance.set(j, pick(take, r, radiance[j]));
    }
  }
};

// An area light's triangles as kCornerFloats planes of triangle_count floats each: the corners
// p0, p1 and p2, then the unit normal, component by component. area_light_point_at reaches them
// through the light's triangle references and the scene's meshes, a chain of dependent loads for
// each pixel; the row loop below gathers each pixel's corners from these planes, as vector code.
constexpr uint32_t kCornerFloats = 12;
std::vector<float> area_light_corners(const SceneView& scene, const AreaLightView& light) {
  const size_t count = light.triangle_count;
  std::vector<float> planes(count * kCornerFloats);
  const auto put = [&](size_t t, uint32_t first, vec3 v) {
    planes[first * count + t] = v.x;
    planes[(first + 1) * count + t] = v.y;
    planes[(first + 2) * count + t] = v.z;
  };
  for (size_t t = 0; t < count; ++t) {
    const TriangleRef ref = light.triangles[t];
    const MeshView& mesh = scene.meshes[ref.mesh];
    const uvec3 tri = mesh.triangles[ref.triangle];
    put(t, 0, mesh.positions[tri.x]);
    put(t, 3, mesh.positions[tri.y]);
    put(t, 6, mesh.positions[tri.z]);
    put(t, 9, light.normals[t]);
  }
  return planes;
}

// The searches of a light's cdf (count entries) for the row's u.x, into row.base (the entries)
// and `stretched` (u.x stretched within them): in lockstep (sample_cdf's steps, one at a time for
// every pixel: no branch to mispredict, and the pixels' loads overlap).
// (Over int indices, which GCC can gather with: src/CMakeLists.txt.)
void search_cdf_row(const float* cdf, uint32_t count, int width, LightRow& row, float* stretched) {
  int base[LightRow::kWidth];
  const float* ux = row.u.x;
  for (int j = 0; j < width; ++j) base[j] = 0;
  for_cdf_halves(count, [&](uint32_t half) {
    BOUNCE_IVDEP
    for (int j = 0; j < width; ++j) base[j] = cdf_halve(cdf, base[j], int(half), ux[j]);
  });
  BOUNCE_IVDEP
  for (int j = 0; j < width; ++j) {
    const int entry = cdf_entry(cdf, base[j], int(count), ux[j]);
    row.base[j] = uint32_t(entry);
    stretched[j] = cdf_stretch(cdf, entry, ux[j]);
  }
}

// The same for a table of at most kScannedCdf entries, without gathers: u.x is compared with each
// value but the last in turn, one value for the whole row. The entry is the count of values at or
// below u.x (the cdf does not decrease, so that is the search's; u.x at or past them all takes the
// last entry, as cdf_entry does), its interval runs from the largest of them to the smallest
// above, or to the last value. The same entries and stretches as search_cdf_row. (Scanning a
// level's 36-entry table was slower than its search: docs/benchmarks.md.)
constexpr uint32_t kScannedCdf = 16;
void scan_cdf_row(const float* cdf, uint32_t count, int width, LightRow& row, float* stretched) {
  const uint32_t last = count - 1;
  const float* ux = row.u.x;
  float start[LightRow::kWidth], end[LightRow::kWidth];
  for (int j = 0; j < width; ++j) {
    row.base[j] = 0;
    start[j] = 0.0f;
    end[j] = cdf[last];
  }
  for (uint32_t t = 0; t < last; ++t) {
    const float c = cdf[t];
    BOUNCE_IVDEP
    for (int j = 0; j < width; ++j) {
      const bool below = c <= ux[j];
      row.base[j] += uint32_t(below);
      start[j] = pick(below, c, start[j]);
      end[j] = pick(below, end[j], glm::min(end[j], c));
    }
  }
  BOUNCE_IVDEP
  for (int j = 0; j < width; ++j) stretched[j] = cdf_stretch_within(start[j], end[j], ux[j]);
}

// Sample k of n of an area light's points for the row's n pixels, into row.q and row.q_normal:
// each pixel's entry in the light's triangle table (scanned or searched), then its point on that
// triangle (area_light_point_at's, from `corners`: area_light_corners').
void pick_area_light_row(const AreaLightView& light, const float* corners, int k, int n, int width,
                         LightRow& row) {
  const float* cdf = light.cdf;
  const uint32_t count = light.triangle_count;
  BOUNCE_IVDEP
  for (int j = 0; j < width; ++j) row.u.set(j, pattern_sample(k, n, row.offset[j]));
  float stretched[LightRow::kWidth];
  if (count <= kScannedCdf)
    scan_cdf_row(cdf, count, width, row, stretched);
  else
    search_cdf_row(cdf, count, width, row, stretched);
  const float* uy = row.u.y;
  BOUNCE_IVDEP
  for (int j = 0; j < width; ++j) {
    const int e = int(row.base[j]);
    const auto c = [&](int f) { return corners[f * int(count) + e]; };
    const vec2 v(stretched[j], uy[j]);
    row.q.set(j, point_on_triangle(vec3(c(0), c(1), c(2)), vec3(c(3), c(4), c(5)),
                                   vec3(c(6), c(7), c(8)), v));
    row.q_normal.set(j, vec3(c(9), c(10), c(11)));
  }
}

// The vector part of one light sample across the row's n pixels: sample(surface, j) (a lane of
// light_lane.h) at each, where the G-buffer has a surface.
template <typename Sample>
BOUNCE_LANE_INLINE void shade_row(const RowSurfaces& surfaces, int n, LightRow& row,
                                  const Sample& sample) {
  BOUNCE_IVDEP
  for (int j = 0; j < n; ++j) {
    const LaneSample r = sample(surfaces[j], j);
    row.wi.set(j, r.wi);
    row.distance[j] = r.distance;
    row.radiance.set(j, pick(surfaces.hit[j] != 0, r.radiance, vec3(0.0f)));
  }
}

// kGlossy: whether any pixel of the row has a specular lobe (lane_shade).
template <bool kGlossy>
void shade_area_row(const RowSurfaces& surfaces, int n, const AreaLightView& light, float scale,
                    LightRow& row) {
  const vec3 radiance = light.radiance;
  const float area = light.area;
  shade_row(surfaces, n, row, [&](const LaneSurface& s, int j) {
    return area_light_lane<kGlossy>(s, row.q[j], row.q_normal[j], radiance, area, scale);
  });
}

template <bool kGlossy>
void shade_punctual_row(const RowSurfaces& surfaces, int n, const PunctualLane& light,
                        LightRow& row) {
  shade_row(surfaces, n, row, [&](const LaneSurface& s, int) {
    return punctual_light_lane<kGlossy>(s, light, 1.0f);
  });
}

}  // namespace

bool direct_takes_rows(const SceneView& scene, const LightPickerView& lights,
                       const DirectSettings& settings) {
  if (scene.light_count + scene.area_light_count == 0 || resamples_lights(lights, settings))
    return false;
  for (uint32_t l = 0; l < scene.light_count; ++l)
    if (!is_punctual(scene.lights[l].type)) return false;
  return true;
}

DirectPass::DirectPass(const SceneView& scene, const LightPickerView& lights, const Tracer& tracer,
                       const GBuffer& g, vec3 eye, const DirectSettings& settings, Image& out,
                       Image* apart)
    : scene_(scene),
      lights_(lights),
      tracer_(tracer),
      view_(g.view()),
      eye_(eye),
      settings_(settings),
      pixels_(out.pixels().data()),
      apart_pixels_(apart ? apart->pixels().data() : nullptr),
      rows_(direct_takes_rows(scene, lights, settings)),
      batches_(std::make_unique<tbb::enumerable_thread_specific<ShadowBatch>>()) {
  if (settings.apart_count > 0 && !apart)
    fail("direct light: lights set apart need an image of their own");
  if (!rows_) return;
  for (uint32_t l = 0; l < scene.light_count; ++l)
    (settings.is_apart(l) ? apart_ : punctual_).push_back(punctual_lane(scene.lights[l]));
  corners_.resize(scene.area_light_count);
  for (uint32_t a = 0; a < scene.area_light_count; ++a)
    corners_[a] = area_light_corners(scene, scene.area_lights[a]);
  // With one sample per pixel (one light, one sample: the Cornell box in real time) the
  // selection keeps that sample unchanged (ShadowSelection's first offer), so it is skipped.
  select_ = settings.one_shadow_ray &&
            scene.light_count + scene.area_light_count * uint32_t(settings.light_samples) > 1;
}

DirectPass::~DirectPass() = default;

int DirectPass::tile() const {
  return rows_ ? LightRow::kWidth : 8;
}

void DirectPass::run(int x0, int y0, int x1, int y1) {
  const int t = tile();
  for (int ty = y0; ty < y1; ty += t)
    for (int tx = x0; tx < x1; tx += t) {
      if (rows_)
        row_tile(tx, ty, std::min(tx + t, x1), std::min(ty + t, y1));
      else
        pixel_tile(tx, ty, std::min(tx + t, x1), std::min(ty + t, y1));
    }
  // The block's pixels are final before it ends: the rays still waiting are traced now. (A
  // pixel's rays reach it in the order they were made, whatever the batches' bounds.)
  batches_->local().flush(tracer_);
}

// Per tile row and light sample: a light_lane.h lane runs across the row as vector code (for an
// area light after a loop picks each pixel's point on it: a search in the light's triangle
// table), then each sample goes to its pixel's selection or to the batch. Each pixel gets its
// samples in direct_pixel's order, so the frames are the per-pixel kernel's.
void DirectPass::row_tile(int x0, int y0, int x1, int y1) {
  const SceneView& scene = scene_;
  const ConstGBufferView& view = view_;
  const Tracer& tracer = tracer_;
  vec3* pixels = pixels_;
  vec3* apart_pixels = apart_pixels_;
  const int n = settings_.light_samples;
  const float inv_n = 1.0f / float(n);
  const bool select = select_;
  ShadowBatch& b = batches_->local();
  LightRow row;
  RowSurfaces surfaces;
  RowSelection selection;
  const int width = x1 - x0;
  bool glossy = false;  // whether any pixel of the row reflects specularly (RowSurfaces::load)
  for (int y = y0; y < y1; ++y) {
    const size_t i0 = view.index(x0, y);
    // The row's samples of one light, from `row`, each with its ray to the batch, adding to
    // `to`'s pixels.
    auto trace_row = [&](vec3* to) {
      for (int j = 0; j < width; ++j) {
        const vec3 radiance = row.radiance[j];
        if (max_component(radiance) > 0.0f)
          b.add(shadow_ray(surfaces.origin[j], row.wi[j], row.distance[j]), radiance,
                to + i0 + size_t(j), tracer);
      }
    };
    // The same to their selections or the batch.
    auto hand_off = [&] {
      if (select)
        selection.offer(row, width);
      else
        trace_row(pixels);
    };
    auto shade_punctual = [&](const PunctualLane& light) {
      if (glossy)
        shade_punctual_row<true>(surfaces, width, light, row);
      else
        shade_punctual_row<false>(surfaces, width, light, row);
    };
    for (int j = 0; j < width; ++j) pixels[i0 + size_t(j)] = view.emission[i0 + size_t(j)];
    if (apart_pixels)
      for (int j = 0; j < width; ++j) apart_pixels[i0 + size_t(j)] = vec3(0.0f);
    if (select) selection.start(uint32_t(i0), width, settings_);
    glossy = surfaces.load(view, i0, width, eye_);
    // The lights set apart: a ray of each one's own at every pixel it reaches.
    for (const PunctualLane& light : apart_) {
      if (surfaces.outside(light)) continue;
      shade_punctual(light);
      trace_row(apart_pixels);
    }
    for (const PunctualLane& light : punctual_) {
      if (surfaces.outside(light)) continue;
      shade_punctual(light);
      hand_off();
    }
    for (uint32_t a = 0; a < scene.area_light_count; ++a) {
      const AreaLightView& light = scene.area_lights[a];
      const PatternRotation rotation =
          pattern_rotation(area_light_id(scene, a), settings_.frame, settings_.seed);
      BOUNCE_IVDEP
      for (int j = 0; j < width; ++j)
        row.offset.set(j, pattern_offset_at({uint32_t(x0 + j), uint32_t(y)}, rotation));
      for (int k = 0; k < n; ++k) {
        pick_area_light_row(light, corners_[a].data(), k, n, width, row);
        if (glossy)
          shade_area_row<true>(surfaces, width, light, inv_n, row);
        else
          shade_area_row<false>(surfaces, width, light, inv_n, row);
        hand_off();
      }
    }
    // Each pixel's kept sample, from the origin every lane shaded it from.
    if (select)
      for (int j = 0; j < width; ++j)
        if (selection.kept[j] > 0.0f)
          b.add(shadow_ray(surfaces.origin[j], selection.wi[j], selection.distance[j]),
                ShadowSelection::weighted(selection.radiance[j], selection.kept[j],
                                          selection.total[j]),
                pixels + i0 + size_t(j), tracer);
  }
}

void DirectPass::pixel_tile(int x0, int y0, int x1, int y1) {
  ShadowBatch& b = batches_->local();
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const uint32_t i = uint32_t(view_.index(x, y));
      pixels_[i] = view_.emission[i];  // before the samples: a full batch adds to it at once
      if (apart_pixels_) apart_pixels_[i] = vec3(0.0f);
      auto shadow = [&](const Ray& ray, vec3 radiance) {
        b.add(ray, radiance, pixels_ + i, tracer_);
      };
      auto apart = [&](const Ray& ray, vec3 radiance) {
        b.add(ray, radiance, apart_pixels_ + i, tracer_);
      };
      direct_light_pixel(scene_, lights_, view_, i, eye_, settings_, shadow, apart);
    }
}

uint64_t DirectPass::shadow_rays() const {
  uint64_t total = 0;
  for (const ShadowBatch& b : *batches_) total += b.traced;
  return total;
}

uint64_t compute_direct(const SceneView& scene, const LightPickerView& lights, const Tracer& tracer,
                        const GBuffer& g, vec3 eye, const DirectSettings& settings, Image& out,
                        Image* apart) {
  DirectPass pass(scene, lights, tracer, g, eye, settings, out, apart);
  parallel_for_tiles(g.width, g.height, pass.tile(),
                     [&](int x0, int y0, int x1, int y1) { pass.run(x0, y0, x1, y1); });
  return pass.shadow_rays();
}

}  // namespace bounce
