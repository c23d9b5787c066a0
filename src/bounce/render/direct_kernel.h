// The direct-light kernel: the light every light source sends towards the eye from one G-buffer
// pixel. The body samples the lights and evaluates the BRDF; each sample hands its shadow ray
// and the radiance it carries to a caller-given `shadow(ray, radiance)`, so the CPU launcher
// (direct.cpp) can trace them in batches and a GPU launcher can trace each at once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

#include "bounce/core/color.h"
#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/qmc.h"
#include "bounce/core/rng.h"
#include "bounce/render/brdf.h"
#include "bounce/render/bsdf_sampling.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/render/light_lane.h"
#include "bounce/render/light_picker.h"
#include "bounce/render/light_resampling.h"
#include "bounce/render/light_sampling.h"
#include "bounce/scene/environment.h"
#include "bounce/scene/scene_view.h"

namespace bounce {

struct DirectSettings {
  int light_samples = 16;  // per area or sphere light, per pixel
  uint32_t frame = 0;      // rotates the sample pattern from frame to frame
  uint32_t seed = 0;
  // Scenes with more lights than this (lights and area lights together) take light_samples
  // resampled light samples per pixel instead of samples of every light (direct_pixel_resampled).
  uint32_t max_looped_lights = kResampleAboveLights;
  int candidates = kLightCandidates;  // resampling: candidates drawn by power per light sample
  // One shadow ray per pixel, for one of its light samples chosen by unshadowed contribution
  // (ShadowSelection), instead of one ray per light sample.
  bool one_shadow_ray = false;
  // Punctual lights (Scene::lights indices) shaded apart: each with a shadow ray of its own at
  // every pixel, handed to the launcher's `apart` rather than to `shadow` or the selection. The
  // renderer sets apart the lights that moved this frame (a carried flashlight): their light is
  // exact in one frame, and the denoiser's history, which would lag behind it, never holds it.
  static constexpr int kMaxApart = 2;
  uint32_t apart[kMaxApart] = {};
  int apart_count = 0;

  BOUNCE_HD bool is_apart(uint32_t light) const {
    bool found = false;
    for (int k = 0; k < apart_count; ++k) found |= apart[k] == light;
    return found;
  }
};

// Whether a scene with `lights` (LightPicker's entries) takes direct_pixel_resampled rather than
// the loop over every light (direct_pixel).
BOUNCE_HD inline bool resamples_lights(const LightPickerView& lights,
                                       const DirectSettings& settings) {
  return lights.count > settings.max_looped_lights;
}

// A pixel's coordinates on the screen (the G-buffer's), for the screen lattice (qmc.h).
struct PixelXY {
  uint32_t x, y;
};
BOUNCE_HD inline PixelXY pixel_xy(const ConstGBufferView& g, uint32_t i) {
  return {i % uint32_t(g.width), i / uint32_t(g.width)};
}

// A per-pixel, per-light rotation of the sample pattern (Cranley-Patterson), as two floats: the
// pixel's point of the screen lattice, rotated by one random offset per light and frame. Each
// pixel's offset is uniform over frames (so its estimate is unbiased), and neighbouring pixels'
// offsets spread evenly over the square, so the denoiser's spatial filter averages stratified
// samples (Georgiev and Fajardo 2016, blue-noise dithered sampling, the same idea).
// The random part, one per light and frame, as 32-bit fixed point (pattern_rotation), and the
// offset at a pixel from it (pattern_offset_at): a row loop makes the first once per light.
struct PatternRotation {
  uint32_t x, y;
};
BOUNCE_HD inline PatternRotation pattern_rotation(uint32_t light, uint32_t frame, uint32_t seed) {
  const uint32_t h = hash_u32(light * 0x9E3779B9u ^ hash_u32(frame + seed * 0x85EBCA6Bu));
  return {h, hash_u32(h ^ 0x68E31DA4u)};
}
BOUNCE_HD inline vec2 pattern_offset_at(PixelXY pixel, PatternRotation r) {
  return {bits_to_unit_float(screen_lattice_x(pixel.x, pixel.y) + r.x),
          bits_to_unit_float(screen_lattice_y(pixel.x, pixel.y) + r.y)};
}
BOUNCE_HD inline vec2 pattern_offset(PixelXY pixel, uint32_t light, uint32_t frame, uint32_t seed) {
  return pattern_offset_at(pixel, pattern_rotation(light, frame, seed));
}

// Sample k of a light's n, its pattern rotated by `offset` (pattern_offset).
BOUNCE_HD inline vec2 pattern_sample(int k, int n, vec2 offset) {
  return rotate_unit(hammersley(k, n), offset);
}

// Hands one light sample (from p, towards ls.wi) to shadow(ray, radiance) with the BRDF, cosine
// and `scale` applied, unless it arrives from below the surface or carries nothing.
template <typename Shadow>
BOUNCE_HD void shade_light_sample(const SurfaceHit& s, vec3 wo, vec3 p, const LightSample& ls,
                                  float scale, Shadow& shadow) {
  if (!ls.valid()) return;
  const float cos_theta = glm::dot(s.normal, ls.wi);
  // Light from below the face itself cannot arrive, whatever the shading normal says.
  if (cos_theta <= 0.0f || glm::dot(s.geometric_normal, ls.wi) <= 0.0f) return;
  const vec3 radiance = eval_brdf(s, wo, ls.wi) * ls.weight * (cos_theta * scale);
  if (max_component(radiance) > 0.0f) shadow(shadow_ray(p, ls), radiance);
}

// The environment light at pixel i: n samples, each one direction drawn by the map's luminance
// and one drawn by the BSDF, weighted by the power heuristic (Veach 1997). The sky fills every
// direction, so on a glossy surface a luminance-drawn direction rarely meets the narrow lobe and
// light sampling alone leaves fireflies; the BSDF's directions find the lobe's reflection.
template <typename Shadow>
BOUNCE_HD void direct_environment(const SceneView& scene, const LightRecord& light,
                                  uint32_t light_id, const SurfaceHit& s, vec3 wo, vec3 p,
                                  uint32_t i, PixelXY xy, const DirectSettings& settings,
                                  Shadow& shadow) {
  const int n = settings.light_samples;
  const float inv_n = 1.0f / float(n);
  const vec2 offset = pattern_offset(xy, light_id, settings.frame, settings.seed);
  const vec2 offset_bsdf =
      pattern_offset(xy, light_id ^ 0x5BD1E995u, settings.frame, settings.seed);
  for (int k = 0; k < n; ++k) {
    const LightSample ls = sample_environment_light(scene, light, pattern_sample(k, n, offset));
    if (ls.valid())
      shade_light_sample(s, wo, p, ls, inv_n * power_heuristic(ls.pdf, bsdf_pdf(s, wo, ls.wi)),
                         shadow);
    const vec2 ub = pattern_sample(k, n, offset_bsdf);
    const float u_lobe = bits_to_unit_float(hash_u32(i ^ hash_u32(uint32_t(k) ^ light_id)) ^
                                            hash_u32(settings.frame + settings.seed));
    const BsdfSample b = sample_bsdf(s, wo, u_lobe, ub);
    if (!b.valid()) continue;
    LightSample bs;
    bs.wi = b.wi;
    bs.distance = std::numeric_limits<float>::infinity();
    bs.pdf = b.pdf;
    bs.weight = environment_radiance(light, scene.environment_map, b.wi) / b.pdf;
    const float light_pdf = environment_pdf(light, scene.environment_map, b.wi);
    shade_light_sample(s, wo, p, bs, inv_n * power_heuristic(b.pdf, light_pdf), shadow);
  }
}

// The id that rotates area light a's sample pattern (pattern_offset): the scene's lights are
// 1 .. light_count, its area lights follow.
BOUNCE_HD inline uint32_t area_light_id(const SceneView& scene, uint32_t a) {
  return scene.light_count + a + 1;
}

// Hands a lane's sample to shadow(ray, radiance) unless nothing arrives.
template <typename Shadow>
BOUNCE_HD void offer_lane_sample(const LaneSurface& lane, const LaneSample& r, Shadow& shadow) {
  if (max_component(r.radiance) > 0.0f)
    shadow(shadow_ray(lane.origin, r.wi, r.distance), r.radiance);
}

// One sample of area light `light` at pattern point u, handed to shadow(ray, radiance) unless
// nothing arrives (light_lane.h, the same arithmetic that direct.cpp's row loop runs).
template <typename Shadow>
BOUNCE_HD void area_light_offer(const SceneView& scene, const AreaLightView& light,
                                const LaneSurface& lane, vec2 u, float scale, Shadow& shadow) {
  const AreaLightPoint q = sample_area_light_point(scene, light, u);
  offer_lane_sample(
      lane, area_light_lane(lane, q.position, q.normal, light.radiance, light.area, scale), shadow);
}

// Direct light at pixel i of g as seen from `eye`: calls shadow(ray, radiance) for each light
// sample whose radiance arrives if the ray is clear. The pixel's own emission (g.emission[i])
// needs no ray: the launcher adds it.
template <typename Shadow>
BOUNCE_HD void direct_pixel(const SceneView& scene, const ConstGBufferView& g, uint32_t i, vec3 eye,
                            const DirectSettings& settings, Shadow&& shadow) {
  if (!g.hit(i)) return;
  const SurfaceHit s = g.surface(i);
  const vec3 wo = glm::normalize(eye - s.position);
  // Lights are sampled from the shadow rays' own origin, so the rays end exactly at the sample.
  const vec3 p = offset_origin(s.position, s.geometric_normal);
  const int n = settings.light_samples;
  const float inv_n = 1.0f / float(n);
  const LaneSurface lane = lane_surface(s, eye);
  const PixelXY xy = pixel_xy(g, i);

  uint32_t light_id = 0;
  for (uint32_t l = 0; l < scene.light_count; ++l) {
    const LightRecord& light = scene.lights[l];
    ++light_id;
    if (light.type == LightType::kEnvironment) {
      direct_environment(scene, light, light_id, s, wo, p, i, xy, settings, shadow);
      continue;
    }
    if (is_punctual(light.type)) {
      if (!settings.is_apart(l))
        offer_lane_sample(lane, punctual_light_lane(lane, punctual_lane(light), 1.0f), shadow);
      continue;
    }
    // Diffuse from cone samples; GGX specular from Karis' representative point, shadowed by
    // the fraction of those samples that reach the light.
    SurfaceHit diffuse_only = s;
    diffuse_only.f0 = vec3(0.0f);
    const vec3 specular = sphere_light_specular(light, s, p, wo) * inv_n;
    const vec2 offset = pattern_offset(xy, light_id, settings.frame, settings.seed);
    for (int k = 0; k < n; ++k) {
      const LightSample ls = sample_sphere_light(light, p, pattern_sample(k, n, offset));
      if (!ls.valid() || glm::dot(s.geometric_normal, ls.wi) <= 0.0f) continue;
      const float cos_theta = glm::max(glm::dot(s.normal, ls.wi), 0.0f);
      const vec3 radiance =
          eval_brdf(diffuse_only, wo, ls.wi) * ls.weight * (cos_theta * inv_n) + specular;
      if (max_component(radiance) > 0.0f) shadow(shadow_ray(p, ls), radiance);
    }
  }
  for (uint32_t a = 0; a < scene.area_light_count; ++a) {
    const vec2 offset = pattern_offset(xy, area_light_id(scene, a), settings.frame, settings.seed);
    for (int k = 0; k < n; ++k)
      area_light_offer(scene, scene.area_lights[a], lane, pattern_sample(k, n, offset), inv_n,
                       shadow);
  }
}

// Direct light at pixel i of g for scenes with many lights (a Quake level has hundreds):
// light_samples shadow rays whatever the light count, each for a light sample chosen by
// resampled importance sampling (Talbot et al. 2005; the candidate step of Bitterli et al.
// 2020, ReSTIR): `candidates` samples drawn by power (`picker`), one kept with probability
// proportional to its unshadowed contribution's luminance, weighted so the estimate stays
// unbiased: f(y) / p(y) * (1/M) sum of p(x_j) / q(x_j). Lights that are far, behind the surface
// or facing away are thus rarely traced. Calls shadow(ray, radiance) as direct_pixel does.
template <typename Shadow>
BOUNCE_HD void direct_pixel_resampled(const SceneView& scene, const LightPickerView& picker,
                                      const ConstGBufferView& g, uint32_t i, vec3 eye,
                                      const DirectSettings& settings, Shadow&& shadow) {
  if (!g.hit(i) || picker.empty()) return;
  const SurfaceHit s = g.surface(i);
  const vec3 wo = glm::normalize(eye - s.position);
  const vec3 p = offset_origin(s.position, s.geometric_normal);
  const int n = settings.light_samples, m = settings.candidates > 0 ? settings.candidates : 1;
  // Each candidate's light and point from the screen lattice, rotated per candidate and frame
  // (as pattern_offset): neighbouring pixels draw candidates spread over the lights' power and
  // over each light, as from a stratified set.
  const PixelXY xy = pixel_xy(g, i);
  const uint32_t lattice_x = screen_lattice_x(xy.x, xy.y), lattice_y = screen_lattice_y(xy.x, xy.y);
  const uint32_t frame_hash = hash_u32(settings.frame + settings.seed * 0x85EBCA6Bu);
  Pcg32 rng(hash_u32(i ^ frame_hash), 0x5bd1e995u);  // which candidate each keeps
  for (int k = 0; k < n; ++k) {
    LightReservoir reservoir;
    vec3 kept_radiance(0.0f);
    LightSample kept;
    for (int j = 0; j < m; ++j) {
      const uint32_t rotation = hash_u32(frame_hash ^ hash_u32(uint32_t(k * m + j) + 0x7F4A7C15u));
      const float u_pick = bits_to_unit_float(lattice_x + rotation);
      const vec2 u(bits_to_unit_float(lattice_y + hash_u32(rotation ^ 0x68E31DA4u)),
                   bits_to_unit_float(lattice_x + hash_u32(rotation ^ 0x1B873593u)));
      const float u_keep = rng.next_float();
      const uint32_t entry = picker.pick(u_pick);
      const float pmf = picker.pmf[entry];
      if (!(pmf > 0.0f)) continue;
      // The environment and the lights set apart are sampled apart (below): as candidates
      // their target is 0, so the resampled estimate covers the other lights alone and stays
      // unbiased for them. (The renderer's picker never draws the lights set apart.)
      if (int32_t(entry) == scene.environment ||
          (entry < picker.light_count && settings.is_apart(entry)))
        continue;
      const LightSample ls = sample_light_entry(scene, picker.light_count, entry, p, u).ls;
      if (!ls.valid()) continue;
      const float cos_theta = glm::dot(s.normal, ls.wi);
      if (cos_theta <= 0.0f || glm::dot(s.geometric_normal, ls.wi) <= 0.0f) continue;
      // This candidate's one-sample estimate f / q; its weight p / q with target p = luminance(f).
      const vec3 radiance = eval_brdf(s, wo, ls.wi) * ls.weight * (cos_theta / pmf);
      const float w = luminance(radiance);
      if (!(w > 0.0f)) continue;
      if (reservoir.offer(w, u_keep)) {
        kept = ls;
        kept_radiance = radiance;
      }
    }
    if (reservoir.empty()) continue;
    shadow(shadow_ray(p, kept),
           kept_radiance * (reservoir.total / (float(m) * reservoir.kept * float(n))));
  }
  if (scene.environment >= 0)
    direct_environment(scene, scene.lights[scene.environment], uint32_t(scene.environment) + 1, s,
                       wo, p, i, pixel_xy(g, i), settings, shadow);
}

// One shadow ray for all of a pixel's light samples, by resampling over the samples themselves
// (Talbot et al. 2005): every sample's unshadowed radiance is known before its ray is traced, so
// the pixel keeps one sample with probability proportional to that radiance's luminance and
// scales it by (sum of the luminances) / (its own). Unbiased; exact wherever all the samples'
// rays agree (all lit or all shadowed), noisy only where the lights' visibility differs; with a
// single sample it is that sample unchanged. A level lit by the sun, its lamps and a flashlight
// thus pays one ray per pixel, not one per light.
struct ShadowSelection {
  Ray ray;
  vec3 radiance{0.0f};
  LightReservoir reservoir;  // over the samples' luminances
  uint32_t seed = 0;         // the pixel's (for_pixel)
  uint32_t offers = 0;       // samples offered so far that carry light

  ShadowSelection() = default;  // a placeholder until for_pixel
  BOUNCE_HD explicit ShadowSelection(uint32_t pixel_seed) : seed(pixel_seed) {}
  // Pixel i's selection in the frame `settings` names.
  BOUNCE_HD static ShadowSelection for_pixel(uint32_t i, const DirectSettings& settings) {
    return ShadowSelection(hash_u32(i ^ hash_u32(settings.frame * 0x9E3779B9u + settings.seed)));
  }
  // The uniform number that decides a pixel's offer number `offer`: counter-based, so direct.cpp's
  // row loop draws it for a whole row at once and gets what this kernel draws offer by offer.
  BOUNCE_HD static float u(uint32_t pixel_seed, uint32_t offer) {
    return bits_to_unit_float(hash_u32(pixel_seed ^ hash_u32(offer * 0x9E3779B9u + 0x2545F491u)));
  }
  // Offers one sample (what direct_pixel hands its `shadow`).
  BOUNCE_HD void operator()(const Ray& r, vec3 sample_radiance) {
    const float w = luminance(sample_radiance);
    if (!(w > 0.0f)) return;
    if (reservoir.offer(w, u(seed, offers++))) {
      ray = r;
      radiance = sample_radiance;
    }
  }
  // The kept sample's radiance weighted by (sum of luminances) / (its own).
  BOUNCE_HD static vec3 weighted(vec3 kept_radiance, float kept_luminance, float sum) {
    return kept_luminance == sum ? kept_radiance : kept_radiance * (sum / kept_luminance);
  }
  // Hands the kept sample, weighted, to shadow(ray, radiance); nothing when no sample came.
  template <typename Shadow>
  BOUNCE_HD void finish(Shadow& shadow) const {
    if (!reservoir.empty()) shadow(ray, weighted(radiance, reservoir.kept, reservoir.total));
  }
};

// The lights set apart (DirectSettings::apart) at pixel i: each one's sample handed to
// apart(ray, radiance) unless nothing arrives.
template <typename Apart>
BOUNCE_HD void direct_pixel_apart(const SceneView& scene, const ConstGBufferView& g, uint32_t i,
                                  vec3 eye, const DirectSettings& settings, Apart&& apart) {
  if (settings.apart_count == 0 || !g.hit(i)) return;
  const LaneSurface lane = lane_surface(g.surface(i), eye);
  for (int k = 0; k < settings.apart_count; ++k)
    offer_lane_sample(
        lane, punctual_light_lane(lane, punctual_lane(scene.lights[settings.apart[k]]), 1.0f),
        apart);
}

// Direct light at pixel i, as the pipeline takes it: the loop over every light, or resampled
// light samples in scenes with many lights (resamples_lights), each sample handed to
// shadow(ray, radiance); with settings.one_shadow_ray, one sample for them all
// (ShadowSelection). The lights set apart go to apart(ray, radiance), each with its own ray.
// The one entry the CPU and GPU launchers call.
template <typename Shadow, typename Apart>
BOUNCE_HD void direct_light_pixel(const SceneView& scene, const LightPickerView& picker,
                                  const ConstGBufferView& g, uint32_t i, vec3 eye,
                                  const DirectSettings& settings, Shadow&& shadow, Apart&& apart) {
  auto samples = [&](auto&& to) {
    if (resamples_lights(picker, settings))
      direct_pixel_resampled(scene, picker, g, i, eye, settings, to);
    else
      direct_pixel(scene, g, i, eye, settings, to);
  };
  direct_pixel_apart(scene, g, i, eye, settings, apart);
  if (!settings.one_shadow_ray) {
    samples(shadow);
    return;
  }
  ShadowSelection selection = ShadowSelection::for_pixel(i, settings);
  samples(selection);
  selection.finish(shadow);
}

// The same where the lights set apart add to the pixel like the others (a launcher with one
// image).
template <typename Shadow>
BOUNCE_HD void direct_light_pixel(const SceneView& scene, const LightPickerView& picker,
                                  const ConstGBufferView& g, uint32_t i, vec3 eye,
                                  const DirectSettings& settings, Shadow&& shadow) {
  direct_light_pixel(scene, picker, g, i, eye, settings, shadow, shadow);
}

}  // namespace bounce
