#include "bounce/render/direct.h"

#include <tbb/enumerable_thread_specific.h>

#include <vector>

#include "bounce/core/parallel.h"
#include "bounce/core/qmc.h"
#include "bounce/core/rng.h"
#include "bounce/render/brdf.h"
#include "bounce/render/light_sampling.h"

namespace bounce {

vec2 pattern_offset(uint32_t pixel, uint32_t light, uint32_t frame, uint32_t seed) {
  const uint32_t h =
      hash_u32(pixel ^ hash_u32(light * 0x9E3779B9u ^ hash_u32(frame + seed * 0x85EBCA6Bu)));
  return {bits_to_unit_float(h), bits_to_unit_float(hash_u32(h ^ 0x68E31DA4u))};
}

namespace {

// Shadow rays wait here with the radiance they carry until a batch is traced at once.
struct ShadowBatch {
  static constexpr size_t kCapacity = 1024;
  std::vector<Ray> rays;
  std::vector<vec3> radiance;
  std::vector<uint32_t> pixel;
  std::vector<uint8_t> blocked;
  uint64_t traced = 0;

  ShadowBatch() {
    rays.reserve(kCapacity);
    radiance.reserve(kCapacity);
    pixel.reserve(kCapacity);
    blocked.resize(kCapacity);
  }
};

struct DirectPass {
  const Scene& scene;
  const Tracer& tracer;
  const GBuffer& g;
  vec3 eye;
  DirectSettings settings;
  Image& out;

  void flush(ShadowBatch& b) const {
    tracer.occluded(b.rays, std::span<uint8_t>(b.blocked.data(), b.rays.size()));
    b.traced += b.rays.size();
    for (size_t k = 0; k < b.rays.size(); ++k)
      if (!b.blocked[k]) out.pixels()[b.pixel[k]] += b.radiance[k];
    b.rays.clear();
    b.radiance.clear();
    b.pixel.clear();
  }

  void push(ShadowBatch& b, uint32_t i, vec3 origin, const LightSample& ls, vec3 radiance) const {
    // Stop just short of the sampled point so the light's own surface does not block it.
    b.rays.push_back({origin, 0.0f, ls.wi, ls.distance * (1.0f - 1e-4f)});
    b.radiance.push_back(radiance);
    b.pixel.push_back(i);
    if (b.rays.size() == ShadowBatch::kCapacity) flush(b);
  }

  void shade_pixel(ShadowBatch& b, uint32_t i) const {
    out.pixels()[i] = g.emission[i];
    if (!g.hit(i)) return;
    const SurfacePoint s{g.normal[i], g.albedo[i], g.roughness[i], g.f0[i]};
    const vec3 wo = glm::normalize(eye - g.position[i]);
    // Lights are sampled from the shadow rays' own origin, so the rays end exactly at the sample.
    const vec3 p = offset_origin(g.position[i], g.geometric_normal[i]);
    const int n = settings.light_samples;
    const float inv_n = 1.0f / float(n);
    auto add = [&](const LightSample& ls, float scale) {
      if (!ls.valid()) return;
      const float cos_theta = glm::dot(s.normal, ls.wi);
      // Light from below the face itself cannot arrive, whatever the shading normal says.
      if (cos_theta <= 0.0f || glm::dot(g.geometric_normal[i], ls.wi) <= 0.0f) return;
      const vec3 radiance = eval_brdf(s, wo, ls.wi) * ls.weight * (cos_theta * scale);
      if (max_component(radiance) > 0.0f) push(b, i, p, ls, radiance);
    };

    uint32_t light_id = 0;
    for (const Light& light : scene.lights) {
      ++light_id;
      if (light.type != LightType::kSphere) {
        add(sample_punctual_light(light, p), 1.0f);
        continue;
      }
      // Diffuse from cone samples; GGX specular from Karis' representative point, shadowed by
      // the fraction of those samples that reach the light.
      const SurfacePoint diffuse_only{s.normal, s.albedo, s.roughness, vec3(0.0f)};
      const vec3 specular = sphere_light_specular(light, s, p, wo) * inv_n;
      const vec2 offset = pattern_offset(i, light_id, settings.frame, settings.seed);
      for (int k = 0; k < n; ++k) {
        const LightSample ls = sample_sphere_light(light, p, rotate_unit(hammersley(k, n), offset));
        if (!ls.valid() || glm::dot(g.geometric_normal[i], ls.wi) <= 0.0f) continue;
        const float cos_theta = glm::max(glm::dot(s.normal, ls.wi), 0.0f);
        const vec3 radiance =
            eval_brdf(diffuse_only, wo, ls.wi) * ls.weight * (cos_theta * inv_n) + specular;
        if (max_component(radiance) > 0.0f) push(b, i, p, ls, radiance);
      }
    }
    for (const AreaLight& light : scene.area_lights) {
      ++light_id;
      const vec2 offset = pattern_offset(i, light_id, settings.frame, settings.seed);
      for (int k = 0; k < n; ++k)
        add(sample_area_light(scene, light, p, rotate_unit(hammersley(k, n), offset)), inv_n);
    }
  }
};

}  // namespace

uint64_t compute_direct(const Scene& scene, const Tracer& tracer, const GBuffer& g, vec3 eye,
                        const DirectSettings& settings, Image& out) {
  DirectPass pass{scene, tracer, g, eye, settings, out};
  tbb::enumerable_thread_specific<ShadowBatch> batches;
  parallel_for_tiles(g.width, g.height, 8, [&](int x0, int y0, int x1, int y1) {
    ShadowBatch& batch = batches.local();
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) pass.shade_pixel(batch, uint32_t(y) * g.width + x);
    pass.flush(batch);  // a tile's pixels are final before the tile ends
  });
  uint64_t total = 0;
  for (const ShadowBatch& b : batches) total += b.traced;
  return total;
}

}  // namespace bounce
