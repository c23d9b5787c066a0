// Direct light's row loop (direct.cpp, light_lane.h): the branch-free samples of area and
// punctual lights equal the light sample and its shading as the per-pixel kernel had them, and
// the row loop's frames equal the per-pixel kernel's (direct_light_pixel with one ray traced at
// a time).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "bounce/core/rng.h"
#include "bounce/render/direct.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/light_lane.h"
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

// A random surface, glossy on odd t, seen from a random eye.
SurfaceHit random_surface(Pcg32& rng, int t) {
  SurfaceHit s;
  s.position = 3.0f * unit(rng);
  s.geometric_normal = unit(rng);
  // Shading normals near the face's, some tilted past the light's side of it.
  s.normal = glm::normalize(s.geometric_normal + 0.6f * unit(rng));
  s.albedo = vec3(rng.next_float(), rng.next_float(), rng.next_float());
  s.f0 = t % 2 ? vec3(0.04f + 0.9f * rng.next_float()) : vec3(0.0f);
  s.roughness = rng.next_float();
  return s;
}

// What the per-pixel kernel hands its shadow for one light sample (nothing: a zero radiance),
// against a lane's sample and the ray made from it. Returns whether light arrives.
bool expect_lane_equals(const SurfaceHit& s, vec3 eye, const LightSample& ls, float scale,
                        const LaneSample& lane) {
  const vec3 wo = glm::normalize(eye - s.position);
  const vec3 p = offset_origin(s.position, s.geometric_normal);
  Ray expected_ray{};
  vec3 expected(0.0f);
  auto keep = [&](const Ray& r, vec3 radiance) {
    expected_ray = r;
    expected = radiance;
  };
  shade_light_sample(s, wo, p, ls, scale, keep);
  expect_vec_near(lane.radiance, expected, 1e-4f);
  if (!(max_component(expected) > 0.0f)) return false;
  const Ray ray = shadow_ray(lane_surface(s, eye).origin, lane.wi, lane.distance);
  expect_vec_near(ray.origin, expected_ray.origin, 1e-6f);
  expect_vec_near(ray.direction, expected_ray.direction, 1e-5f);
  if (std::isinf(expected_ray.tmax))
    EXPECT_TRUE(std::isinf(ray.tmax));
  else
    EXPECT_NEAR(ray.tmax, expected_ray.tmax, 1e-5f * expected_ray.tmax);
  return true;
}

TEST(AreaLightLane, EqualsTheLightSampleAndItsShading) {
  Pcg32 rng(5);
  int lit = 0, dark = 0;
  for (int t = 0; t < 4000; ++t) {
    const SurfaceHit s = random_surface(rng, t);
    const vec3 eye = s.position + (1.0f + 4.0f * rng.next_float()) * unit(rng);
    const AreaLightPoint q{2.0f * unit(rng), unit(rng)};
    const vec3 light_radiance(3.0f, 2.0f, 1.0f);
    const float area = 0.5f, scale = 0.25f;
    const vec3 p = offset_origin(s.position, s.geometric_normal);
    const LaneSample lane =
        area_light_lane(lane_surface(s, eye), q.position, q.normal, light_radiance, area, scale);
    if (expect_lane_equals(s, eye, area_light_sample(q, light_radiance, area, p), scale, lane))
      ++lit;
    else
      ++dark;
  }
  // Both outcomes are exercised: light arriving, and light from behind either face.
  EXPECT_GT(lit, 500);
  EXPECT_GT(dark, 500);
}

TEST(PunctualLightLane, EqualsTheLightSampleAndItsShading) {
  Pcg32 rng(11);
  int lit[3] = {}, dark[3] = {}, penumbra = 0;
  for (int t = 0; t < 6000; ++t) {
    const SurfaceHit s = random_surface(rng, t / 3);
    const vec3 eye = s.position + (1.0f + 4.0f * rng.next_float()) * unit(rng);
    const vec3 power(2.0f, 1.5f, 0.5f);
    const vec3 at = 2.0f * unit(rng);
    // Spots aimed near the surface, so some of it falls inside, across and outside the cone.
    const Light light =
        t % 3 == 0   ? Light::point(at, power)
        : t % 3 == 1 ? Light::spot(at, s.position - at + 0.8f * unit(rng), power, 15.0f, 35.0f)
                     : Light::directional(unit(rng), power);
    const float scale = t % 2 ? 1.0f : 0.5f;
    const LaneSample lane = punctual_light_lane(lane_surface(s, eye), punctual_lane(light), scale);
    const vec3 p = offset_origin(s.position, s.geometric_normal);
    const LightSample ls = sample_punctual_light(light, p);
    if (light.type == LightType::kSpot) {
      const float falloff = spot_falloff(light, -ls.wi);
      penumbra += falloff > 0.0f && falloff < 1.0f;
    }
    (expect_lane_equals(s, eye, ls, scale, lane) ? lit : dark)[t % 3]++;
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(lit[k], 300) << "light type " << k;
    EXPECT_GT(dark[k], 300) << "light type " << k;
  }
  EXPECT_GT(penumbra, 100) << "spots' smoothstep band";
}

// sphere_outside_spot, by brute force: no point of a sphere it rules out is lit (spot_falloff_lane
// is 0 at points on its boundary and within), and it rules out most of the spheres whose points
// all lie outside the cone (a test that always said no would fail), for narrow and wide cones.
TEST(SpotCone, SpheresRuledOutAreUnlitAndMostUnlitSpheresAreRuledOut) {
  Pcg32 rng(23);
  int ruled_out = 0, unlit = 0, unlit_ruled_out = 0;
  for (int t = 0; t < 4000; ++t) {
    const float outer = 5.0f + 80.0f * rng.next_float();
    const Light light = Light::spot(2.0f * unit(rng), unit(rng), vec3(1.0f), 0.5f * outer, outer);
    const PunctualLane l = punctual_lane(light);
    const vec3 centre = l.position + (0.2f + 4.0f * rng.next_float()) * unit(rng);
    const float radius = 0.5f * rng.next_float() * rng.next_float();
    const bool out = sphere_outside_spot(l, centre, radius);
    bool any_lit = false;
    for (int k = 0; k < 200; ++k) {
      // Points on the boundary (the nearest to the cone are there) and within.
      const vec3 q = centre + (k % 2 ? radius : radius * rng.next_float()) * unit(rng);
      any_lit |= spot_falloff_lane(l, glm::normalize(q - l.position)) > 0.0f;
    }
    if (out) {
      ++ruled_out;
      EXPECT_FALSE(any_lit) << "trial " << t;
    }
    if (!any_lit) {
      ++unlit;
      unlit_ruled_out += out;
    }
  }
  EXPECT_GT(ruled_out, 1000);
  EXPECT_GT(unlit_ruled_out, unlit * 9 / 10);
  // Not a spot, or a cone wider than a hemisphere: never ruled out.
  const vec3 far(100.0f, 0.0f, 0.0f);
  EXPECT_FALSE(sphere_outside_spot(punctual_lane(Light::point(vec3(0.0f), vec3(1.0f))), far, 1.0f));
  EXPECT_FALSE(sphere_outside_spot(
      punctual_lane(Light::spot(vec3(0.0f), vec3(0, 0, 1), vec3(1.0f), 60.0f, 100.0f)), far, 1.0f));
  EXPECT_TRUE(sphere_outside_spot(
      punctual_lane(Light::spot(vec3(0.0f), vec3(0, 0, 1), vec3(1.0f), 20.0f, 30.0f)), far, 1.0f));
}

// The Cornell box, its tall box glossy so the GGX lobe is in the rows too; with `punctual`, also
// lit by a point light, a spot from the camera whose cone edge crosses the back wall, the sun
// through the open front, and glowing strips of 13 and 21 triangles of unequal areas on the left
// wall (area lights whose triangle tables the row loop scans, and searches in several steps).
struct CornellDirect {
  static constexpr int kSize = 48;
  Scene scene;
  SceneData data = SceneData::from(scene);
  std::unique_ptr<Tracer> tracer = make_embree_tracer(scene);
  LightPicker picker = LightPicker::build(scene);
  GBuffer g;

  static Scene glossy_cornell(bool punctual) {
    Scene s = make_cornell();
    if (punctual) {
      s.lights.push_back(Light::point(vec3(0.15f, 0.45f, 0.25f), vec3(0.05f)));
      s.lights.push_back(Light::spot(vec3(0.278f, 0.273f, -0.6f), vec3(0.1f, -0.05f, 1.0f),
                                     vec3(0.3f, 0.2f, 0.1f), 8.0f, 16.0f));
      s.lights.push_back(Light::directional(vec3(-0.3f, -0.6f, 1.0f), vec3(0.8f, 0.8f, 1.0f)));
      Material glow;
      glow.name = "glow";
      glow.albedo = vec3(0.0f);
      glow.emission = vec3(2.0f, 3.0f, 1.0f);
      s.materials.push_back(glow);
      // Fans just inside the wall at x = 0.556 (the left one on screen), one behind the other:
      // vertices along two lines.
      for (const uint32_t triangles : {13u, 21u}) {
        Mesh strip;
        strip.name = "strip" + std::to_string(triangles);
        const bool first = triangles == 13;
        float z = first ? 0.05f : 0.345f;
        for (uint32_t t = 0; t <= triangles; ++t) {
          strip.positions.push_back(vec3(0.54f, 0.1f + 0.02f * float(t % 3), z));
          strip.positions.push_back(vec3(0.54f, 0.4f, z));
          z += first ? 0.01f + 0.006f * float((t * 7) % 5) : 0.004f + 0.003f * float((t * 7) % 5);
        }
        for (uint32_t t = 0; t < triangles; ++t) {
          // Wound so the face normal points to -x, into the room.
          strip.triangles.push_back(uvec3(2 * t, 2 * t + 2, 2 * t + 1));
          strip.materials.push_back(uint32_t(s.materials.size() - 1));
        }
        s.meshes.push_back(strip);
      }
    }
    for (MaterialRecord& m : s.materials)
      if (max_component(m.emission) <= 0.0f && m.albedo.x > 0.5f && m.albedo.y > 0.5f) {
        m.f0 = vec3(0.5f);
        m.roughness = 0.3f;
        break;
      }
    s.finalize();
    return s;
  }
  explicit CornellDirect(bool punctual = false) : scene(glossy_cornell(punctual)) {
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
  // The same with the lights settings.apart names: their light into `apart`.
  Image rows(const DirectSettings& settings, Image& apart) const {
    Image out(kSize, kSize);
    apart = Image(kSize, kSize);
    compute_direct(data.view(), picker.view(), *tracer, g, scene.camera.position, settings, out,
                   &apart);
    return out;
  }
  // The per-pixel kernel, each shadow ray traced on its own; the lights set apart into `apart`
  // when given.
  Image per_pixel(const DirectSettings& settings, Image* apart = nullptr) const {
    Image out(kSize, kSize);
    if (apart) *apart = Image(kSize, kSize);
    const ConstGBufferView view = g.view();
    for (uint32_t i = 0; i < uint32_t(view.size()); ++i) {
      vec3 sum = view.emission[i], apart_sum(0.0f);
      auto add_to = [&](vec3& to) {
        return [&](const Ray& ray, vec3 radiance) {
          if (!tracer->occluded(ray)) to += radiance;
        };
      };
      direct_light_pixel(data.view(), picker.view(), view, i, scene.camera.position, settings,
                         add_to(sum), add_to(apart ? apart_sum : sum));
      out.pixels()[i] = sum;
      if (apart) apart->pixels()[i] = apart_sum;
    }
    return out;
  }
};

// The row loop's frames against the per-pixel kernel's, for 1 and 3 area-light samples, with and
// without one shadow ray per pixel.
void expect_rows_equal_per_pixel(const CornellDirect& c) {
  for (const bool one_ray : {false, true})
    for (const int samples : {1, 3}) {
      DirectSettings settings;
      settings.light_samples = samples;
      settings.one_shadow_ray = one_ray;
      settings.frame = 7;
      ASSERT_TRUE(direct_takes_rows(c.data.view(), c.picker.view(), settings));
      const Image rows = c.rows(settings), expected = c.per_pixel(settings);
      double lit = 0.0;
      for (size_t i = 0; i < rows.pixel_count(); ++i) {
        expect_vec_near(rows.pixels()[i], expected.pixels()[i], 1e-4f);
        lit += double(max_component(expected.pixels()[i]));
      }
      EXPECT_GT(lit, 1.0) << "the box is lit";
    }
}

TEST(AreaLightRows, EqualThePerPixelKernel) {
  const CornellDirect c;
  ASSERT_EQ(c.data.view().light_count, 0u);
  ASSERT_GT(c.data.view().area_light_count, 0u);
  expect_rows_equal_per_pixel(c);
}

TEST(LightRows, PointSpotSunAndAreaLightsEqualThePerPixelKernel) {
  const CornellDirect c(/*punctual=*/true);
  ASSERT_EQ(c.data.view().light_count, 3u);
  ASSERT_EQ(c.data.view().area_light_count, 3u);
  EXPECT_EQ(c.data.view().area_lights[1].triangle_count, 13u);
  EXPECT_EQ(c.data.view().area_lights[2].triangle_count, 21u);
  expect_rows_equal_per_pixel(c);
  // Each punctual light adds light somewhere: the frame without them is darker.
  const CornellDirect area_only;
  DirectSettings settings;
  settings.light_samples = 1;
  const Image with = c.rows(settings), without = area_only.rows(settings);
  double added = 0.0;
  for (size_t i = 0; i < with.pixel_count(); ++i)
    added += double(luminance(with.pixels()[i]) - luminance(without.pixels()[i]));
  EXPECT_GT(added, 1.0);
}

// Lights set apart (DirectSettings::apart: the renderer's moved lights) take a shadow ray of
// their own at every pixel, into an image of their own: with a ray per sample the two images sum
// to the frame without them, and with one ray per pixel their image is the same; the row loop and
// the per-pixel kernel agree; resampled light samples (many-light scenes) leave them out.
TEST(LightRows, LightsSetApartTakeRaysOfTheirOwn) {
  const CornellDirect c(/*punctual=*/true);
  DirectSettings settings;
  settings.light_samples = 3;
  settings.frame = 5;
  DirectSettings apart_settings = settings;
  apart_settings.apart_count = 2;
  apart_settings.apart[0] = 1;  // the spot
  apart_settings.apart[1] = 0;  // the point light
  ASSERT_TRUE(c.scene.lights[1].type == LightType::kSpot);
  const Image whole = c.rows(settings);
  Image apart, apart_one_ray, apart_per_pixel;
  const Image rest = c.rows(apart_settings, apart);
  double apart_light = 0.0;
  for (size_t i = 0; i < whole.pixel_count(); ++i) {
    expect_vec_near(rest.pixels()[i] + apart.pixels()[i], whole.pixels()[i], 1e-4f);
    apart_light += double(luminance(apart.pixels()[i]));
  }
  EXPECT_GT(apart_light, 0.5) << "the spot and the point light light the box";
  const Image rest_per_pixel = c.per_pixel(apart_settings, &apart_per_pixel);
  apart_settings.one_shadow_ray = true;
  const Image rest_one_ray = c.rows(apart_settings, apart_one_ray);
  const Image rest_one_ray_per_pixel = c.per_pixel(apart_settings);
  for (size_t i = 0; i < whole.pixel_count(); ++i) {
    expect_vec_near(rest_per_pixel.pixels()[i], rest.pixels()[i], 1e-4f);
    expect_vec_near(apart_per_pixel.pixels()[i], apart.pixels()[i], 1e-4f);
    EXPECT_EQ(apart_one_ray.pixels()[i], apart.pixels()[i]);
    // (per_pixel without an image for them adds them to the frame.)
    expect_vec_near(rest_one_ray_per_pixel.pixels()[i],
                    rest_one_ray.pixels()[i] + apart.pixels()[i], 1e-4f);
  }
  // Resampled: the frames' mean without the lights set apart plus their image is the mean with
  // every light resampled.
  settings.max_looped_lights = apart_settings.max_looped_lights = 1;
  apart_settings.one_shadow_ray = false;
  double with_all = 0.0, without_apart = 0.0;
  for (uint32_t frame = 0; frame < 64; ++frame) {
    settings.frame = apart_settings.frame = frame;
    Image resampled_apart;
    const Image all = c.per_pixel(settings), part = c.per_pixel(apart_settings, &resampled_apart);
    for (size_t i = 0; i < all.pixel_count(); ++i) {
      with_all += double(luminance(all.pixels()[i]));
      without_apart += double(luminance(part.pixels()[i]));
      if (frame == 0) expect_vec_near(resampled_apart.pixels()[i], apart.pixels()[i], 1e-4f);
    }
  }
  without_apart += 64.0 * apart_light;
  EXPECT_NEAR(without_apart / with_all, 1.0, 0.03);
}

TEST(LightRows, ScenesTheRowsDoNotTake) {
  DirectSettings settings;
  Scene sphere = make_cornell();
  sphere.lights.push_back(Light::sphere(vec3(0.3f, 0.4f, 0.3f), 0.05f, vec3(1.0f)));
  sphere.finalize();
  const SceneData data = SceneData::from(sphere);
  const LightPicker picker = LightPicker::build(sphere);
  EXPECT_FALSE(direct_takes_rows(data.view(), picker.view(), settings)) << "a sphere light";
  settings.max_looped_lights = 1;
  const CornellDirect c(true);
  EXPECT_FALSE(direct_takes_rows(c.data.view(), c.picker.view(), settings)) << "resampled";
}

}  // namespace
}  // namespace bounce
