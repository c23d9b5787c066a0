// The environment light as kernels read it: radiance arriving from infinitely far away along
// each direction, a uniform sky colour or an equirectangular (latitude-longitude) map, and its
// importance sampling. Plain functions over plain data (the light's LightRecord and the map's
// view), shared by direct light, the path tracer, the G-buffer's misses and photon emission.
//
// Map layout: row 0 is straight up (+y), the last row straight down; the centre column looks
// along -z and u grows towards +x (u = 0.75 is +x). `rotation` turns the map about +y
// (right-handed: a positive angle carries +x towards -z). Texels are looked up nearest, so the
// map is piecewise constant, exactly what the sampling distribution assumes.
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "bounce/core/cdf_sampling.h"
#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/sampling.h"
#include "bounce/scene/light.h"

namespace bounce {

// An equirectangular map and its sampling tables (EnvironmentMap owns them). The distribution
// is piecewise constant over texels with weight luminance * sin(theta) at the texel's row
// centre: a row's marginal cdf, then a cdf over the texels of each row (pbrt's
// Distribution2D, Pharr, Jakob and Humphreys, Physically Based Rendering, 3rd ed., 14.2.4).
struct EnvironmentMapView {
  const vec3* texels = nullptr;            // row-major from the top row, linear RGB
  const float* marginal_cdf = nullptr;     // height entries: cumulative row weight
  const float* conditional_cdf = nullptr;  // height rows of width entries
  int width = 0;
  int height = 0;

  BOUNCE_HD bool empty() const { return texels == nullptr || width <= 0 || height <= 0; }
};
static_assert(std::is_trivially_copyable_v<EnvironmentMapView>);

// A world direction turned into the map's frame (the inverse of the light's rotation), and back.
BOUNCE_HD inline vec3 environment_to_map(float rotation, vec3 d) {
  const float c = std::cos(rotation), s = std::sin(rotation);
  return {c * d.x - s * d.z, d.y, s * d.x + c * d.z};
}
BOUNCE_HD inline vec3 environment_from_map(float rotation, vec3 m) {
  const float c = std::cos(rotation), s = std::sin(rotation);
  return {c * m.x + s * m.z, m.y, -s * m.x + c * m.z};
}

// Map coordinates in [0, 1]^2 of a unit direction in the map's frame, and the direction of
// map coordinates.
BOUNCE_HD inline vec2 environment_uv(vec3 m) {
  const float theta = std::acos(glm::clamp(m.y, -1.0f, 1.0f));
  const float phi = std::atan2(m.x, -m.z);
  return {0.5f + phi * (0.5f / kPi), theta / kPi};
}
BOUNCE_HD inline vec3 environment_direction(vec2 uv) {
  const float theta = uv.y * kPi, phi = (uv.x - 0.5f) * kTwoPi;
  const float st = std::sin(theta);
  return {st * std::sin(phi), std::cos(theta), -st * std::cos(phi)};
}

// The texel (column, row) that map coordinates fall in.
BOUNCE_HD inline ivec2 environment_texel(const EnvironmentMapView& map, vec2 uv) {
  const int x = glm::clamp(int(uv.x * float(map.width)), 0, map.width - 1);
  const int y = glm::clamp(int(uv.y * float(map.height)), 0, map.height - 1);
  return {x, y};
}

// Radiance arriving along -d, i.e. seen looking along unit world direction d.
BOUNCE_HD inline vec3 environment_radiance(const LightRecord& light, const EnvironmentMapView& map,
                                           vec3 d) {
  if (map.empty()) return light.radiance;
  const ivec2 t = environment_texel(map, environment_uv(environment_to_map(light.rotation, d)));
  return light.radiance * map.texels[size_t(t.y) * size_t(map.width) + size_t(t.x)];
}

// The probability of texel (x, y) under the sampling tables (from their cdf differences, so it
// is exactly what sample_environment draws with).
BOUNCE_HD inline float environment_texel_probability(const EnvironmentMapView& map, int x, int y) {
  const float* row = map.conditional_cdf + size_t(y) * size_t(map.width);
  const float row_p = map.marginal_cdf[y] - (y > 0 ? map.marginal_cdf[y - 1] : 0.0f);
  const float texel_p = row[x] - (x > 0 ? row[x - 1] : 0.0f);
  return row_p * texel_p;
}

// Solid-angle pdf with which sample_environment returns unit world direction d.
BOUNCE_HD inline float environment_pdf(const LightRecord& light, const EnvironmentMapView& map,
                                       vec3 d) {
  if (map.empty()) return uniform_sphere_pdf();
  const vec2 uv = environment_uv(environment_to_map(light.rotation, d));
  const float sin_theta = std::sin(uv.y * kPi);
  if (!(sin_theta > 0.0f)) return 0.0f;
  const ivec2 t = environment_texel(map, uv);
  // The texel's probability spread over its (u, v) area, then over the solid angle:
  // d(omega) = 2 pi^2 sin(theta) du dv.
  const float pdf_uv =
      environment_texel_probability(map, t.x, t.y) * float(map.width) * float(map.height);
  return pdf_uv / (2.0f * kPi * kPi * sin_theta);
}

// A direction towards the environment drawn from u in [0, 1)^2 by the map's luminance (uniform
// over the sphere for a sky colour), with its radiance and solid-angle pdf.
struct EnvironmentSample {
  vec3 direction{0.0f};  // unit, world space, towards the sky
  vec3 radiance{0.0f};
  float pdf = 0.0f;
};
BOUNCE_HD inline EnvironmentSample sample_environment(const LightRecord& light,
                                                      const EnvironmentMapView& map, vec2 u) {
  EnvironmentSample s;
  if (map.empty()) {
    s.direction = sample_uniform_sphere(u);
    s.radiance = light.radiance;
    s.pdf = uniform_sphere_pdf();
    return s;
  }
  const CdfSample row = sample_cdf(map.marginal_cdf, size_t(map.height), u.y);
  const CdfSample column = sample_cdf(map.conditional_cdf + size_t(row.entry) * size_t(map.width),
                                      size_t(map.width), u.x);
  const vec2 uv((float(column.entry) + column.u) / float(map.width),
                (float(row.entry) + row.u) / float(map.height));
  const float sin_theta = std::sin(uv.y * kPi);
  if (!(sin_theta > 0.0f)) return s;
  const float pdf_uv = environment_texel_probability(map, int(column.entry), int(row.entry)) *
                       float(map.width) * float(map.height);
  s.pdf = pdf_uv / (2.0f * kPi * kPi * sin_theta);
  if (!(s.pdf > 0.0f)) return EnvironmentSample{};
  s.direction = environment_from_map(light.rotation, environment_direction(uv));
  s.radiance =
      light.radiance * map.texels[size_t(row.entry) * size_t(map.width) + size_t(column.entry)];
  return s;
}

}  // namespace bounce
