// Direct light's area-light row loop (direct.cpp, area_light_lane.h): the branch-free sample
// equals the light sample and its shading as the per-pixel kernel had them, and the row loop's
// frames equal the per-pixel kernel's (direct_light_pixel with one ray traced at a time).
#include <gtest/gtest.h>

#include <memory>

#include "bounce/core/rng.h"
#include "bounce/render/area_light_lane.h"
#include "bounce/render/direct.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/light_picker.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"
#include "bounce/trace/tracer.h"

namespace bounce {
namespace {

vec3 unit(Pcg32& rng) {
  const vec3 v(2.0f * rng.next_float() - 1.0f, 2.0f * rng.next_float() - 1.0f,
               2.0f * rng.next_float() - 1.0f);
  return glm::normalize(v + vec3(1e-3f));
}

void expect_vec_near(vec3 a, vec3 b, float relative) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], relative * (1e-6f + std::fabs(b[c])));
}

TEST(AreaLightLane, EqualsTheLightSampleAndItsShading) {
  Pcg32 rng(5);
  int lit = 0, dark = 0;
  for (int t = 0; t < 4000; ++t) {
    SurfaceHit s;
    s.position = 3.0f * unit(rng);
    s.geometric_normal = unit(rng);
    // Shading normals near the face's, some tilted past the light's side of it.
    s.normal = glm::normalize(s.geometric_normal + 0.6f * unit(rng));
    s.albedo = vec3(rng.next_float(), rng.next_float(), rng.next_float());
    s.f0 = t % 2 ? vec3(0.04f + 0.9f * rng.next_float()) : vec3(0.0f);  // glossy half the time
    s.roughness = rng.next_float();
    const vec3 eye = s.position + (1.0f + 4.0f * rng.next_float()) * unit(rng);
    const AreaLightPoint q{2.0f * unit(rng), unit(rng)};
    const vec3 light_radiance(3.0f, 2.0f, 1.0f);
    const float area = 0.5f, scale = 0.25f;

    const vec3 wo = glm::normalize(eye - s.position);
    const vec3 p = offset_origin(s.position, s.geometric_normal);
    Ray expected_ray{};
    vec3 expected(0.0f);
    auto keep = [&](const Ray& r, vec3 radiance) {
      expected_ray = r;
      expected = radiance;
    };
    shade_light_sample(s, wo, p, area_light_sample(q, light_radiance, area, p), scale, keep);

    const LaneSample lane =
        area_light_lane(lane_surface(s, eye), q.position, q.normal, light_radiance, area, scale);
    expect_vec_near(lane.radiance, expected, 1e-4f);
    if (max_component(expected) > 0.0f) {
      ++lit;
      const Ray ray = shadow_ray(lane_surface(s, eye).origin, lane.wi, lane.distance);
      expect_vec_near(ray.origin, expected_ray.origin, 1e-6f);
      expect_vec_near(ray.direction, expected_ray.direction, 1e-5f);
      EXPECT_NEAR(ray.tmax, expected_ray.tmax, 1e-5f * expected_ray.tmax);
    } else {
      ++dark;
    }
  }
  // Both outcomes are exercised: light arriving, and light from behind either face.
  EXPECT_GT(lit, 500);
  EXPECT_GT(dark, 500);
}

// The Cornell box, its tall box glossy so the GGX lobe is in the rows too.
struct CornellDirect {
  static constexpr int kSize = 48;
  Scene scene = glossy_cornell();
  SceneData data = SceneData::from(scene);
  std::unique_ptr<Tracer> tracer = make_embree_tracer(scene);
  LightPicker picker = LightPicker::build(scene);
  GBuffer g;

  static Scene glossy_cornell() {
    Scene s = make_cornell();
    for (MaterialRecord& m : s.materials)
      if (max_component(m.emission) <= 0.0f && m.albedo.x > 0.5f && m.albedo.y > 0.5f) {
        m.f0 = vec3(0.5f);
        m.roughness = 0.3f;
        break;
      }
    s.finalize();
    return s;
  }
  CornellDirect() {
    g.resize(kSize, kSize);
    build_gbuffer(data.view(), *tracer, CameraRays::from(scene.camera, kSize, kSize), vec2(0.5f),
                  g);
  }
  // compute_direct: the row loop for this scene's area light.
  Image rows(const DirectSettings& settings) const {
    Image out(kSize, kSize);
    compute_direct(data.view(), picker.view(), *tracer, g, scene.camera.position, settings, out);
    return out;
  }
  // The per-pixel kernel, each shadow ray traced on its own.
  Image per_pixel(const DirectSettings& settings) const {
    Image out(kSize, kSize);
    const ConstGBufferView view = g.view();
    for (uint32_t i = 0; i < uint32_t(view.size()); ++i) {
      vec3 sum = view.emission[i];
      direct_light_pixel(data.view(), picker.view(), view, i, scene.camera.position, settings,
                         [&](const Ray& ray, vec3 radiance) {
                           if (!tracer->occluded(ray)) sum += radiance;
                         });
      out.pixels()[i] = sum;
    }
    return out;
  }
};

TEST(AreaLightRows, EqualThePerPixelKernel) {
  const CornellDirect c;
  ASSERT_EQ(c.data.view().light_count, 0u);
  ASSERT_GT(c.data.view().area_light_count, 0u);
  for (const bool one_ray : {false, true})
    for (const int samples : {1, 3}) {
      DirectSettings settings;
      settings.light_samples = samples;
      settings.one_shadow_ray = one_ray;
      settings.frame = 7;
      const Image rows = c.rows(settings), expected = c.per_pixel(settings);
      double lit = 0.0;
      for (size_t i = 0; i < rows.pixel_count(); ++i) {
        expect_vec_near(rows.pixels()[i], expected.pixels()[i], 1e-4f);
        lit += double(max_component(expected.pixels()[i]));
      }
      EXPECT_GT(lit, 1.0) << "the box is lit";
    }
}

}  // namespace
}  // namespace bounce
