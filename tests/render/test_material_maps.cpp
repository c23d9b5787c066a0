// Normal maps and alpha cut-outs where light meets them: a normal-mapped plane shades as the
// plane with the mapped normal, and an alpha-masked quad blocks rays (shadow, primary, photon:
// all go through the Tracer or its trace view) on its opaque part only, in Embree and our BVH.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "bounce/render/surface.h"
#include "bounce/trace/tracer.h"
#include "render/render_test_util.h"
#include "scene/hand_built_scenes.h"

namespace bounce {
namespace {

constexpr int kSize = 31;

using scene_test::quad_mesh;

// A 4 x 4 m white floor in y = 0 facing up, uv = ((x + 2) / 4, (z + 2) / 4), seen from above by
// a narrow camera and lit by a point light off to the side.
Scene floor_scene() {
  Scene s;
  s.source = "floor";
  Material white;
  white.albedo = vec3(1.0f);
  s.materials.push_back(white);
  Mesh floor = quad_mesh("floor", vec3(-2, 0, -2), vec3(0, 0, 4), vec3(4, 0, 0), 0);
  for (const vec3& p : floor.positions) floor.uvs.push_back({(p.x + 2) / 4, (p.z + 2) / 4});
  s.meshes.push_back(floor);
  s.lights.push_back(Light::point(vec3(1.0f, 1.0f, 0.5f), vec3(2.0f)));
  s.camera.position = vec3(0.0f, 3.0f, 0.0f);
  s.camera.look_at = vec3(0.0f);
  s.camera.up = vec3(0.0f, 0.0f, 1.0f);
  s.camera.vfov_deg = 10.0f;
  s.has_camera = true;
  return s;
}

Image direct_image(Scene scene) {
  scene.finalize();
  render_test::Job job("direct", kSize, kSize);
  return render_test::render(scene, job).color;
}

float max_difference(const Image& a, const Image& b) {
  float d = 0.0f;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      d = std::max(d, max_component(glm::abs(a.at(x, y) - b.at(x, y))));
  return d;
}

// The tangent-space normal t (unit) stored as a 1 x 1 normal map, float texels (no 8-bit
// rounding); on this floor tangent = +x, bitangent = -z (up the image: towards -v), normal = +y.
TEST(MaterialMaps, NormalMappedPlaneShadesAsTheTiltedPlane) {
  const vec3 tangent_space[] = {glm::normalize(vec3(0.6f, 0.0f, 0.8f)),
                                glm::normalize(vec3(0.0f, 0.6f, 0.8f)),
                                glm::normalize(vec3(-0.3f, 0.4f, 0.8f))};
  const Image flat = direct_image(floor_scene());
  for (const vec3& t : tangent_space) {
    const vec3 world =
        glm::normalize(t.x * vec3(1, 0, 0) + t.y * vec3(0, 0, -1) + t.z * vec3(0, 1, 0));
    Scene mapped = floor_scene();
    Texture map;
    map.width = map.height = 1;
    map.texels = {t * 0.5f + 0.5f};
    mapped.textures.push_back(map);
    mapped.materials[0].normal_texture = 0;
    Scene tilted = floor_scene();
    tilted.meshes[0].normals.assign(4, world);

    const Image a = direct_image(mapped), b = direct_image(tilted);
    const vec3 centre = a.at(kSize / 2, kSize / 2);
    EXPECT_LT(max_difference(a, b), 1e-4f * centre.y) << t.x << " " << t.y;
    EXPECT_GT(std::abs(centre.y - flat.at(kSize / 2, kSize / 2).y), 0.05f * centre.y);
    // Analytic at the centre: albedo / pi * I * cos / d^2 about the floor's middle.
    const vec3 to_light = vec3(1.0f, 1.0f, 0.5f);
    const float d2 = glm::dot(to_light, to_light);
    const float expected =
        kInvPi * 2.0f * std::max(0.0f, glm::dot(world, to_light)) / std::sqrt(d2) / d2;
    EXPECT_NEAR(centre.y, expected, 0.02f * expected) << t.x << " " << t.y;
  }
}

// A 2 x 2 m quad at height 0.5 over the floor, u along x: its left half (x < 0) opaque, its right
// half a hole in a MASK material. The alpha texels are 1, 1, 0, 0, so that bilinear filtering
// (with repeat wrapping) crosses the cutoff at u = 0.5 and near the edges only.
Scene masked_quad_scene() {
  Scene s = floor_scene();
  const uint32_t leaf = scene_test::add_half_cut_out_material(s);
  Mesh quad = quad_mesh("leaf", vec3(-1, 0.5f, -1), vec3(0, 0, 2), vec3(2, 0, 0), leaf);
  for (const vec3& p : quad.positions) quad.uvs.push_back({(p.x + 1) / 2, (p.z + 1) / 2});
  s.meshes.push_back(quad);
  s.lights.clear();
  s.lights.push_back(Light::point(vec3(0.0f, 2.0f, 0.0f), vec3(2.0f)));
  s.finalize();
  return s;
}

Ray segment(vec3 from, vec3 to) {
  Ray r;
  r.origin = from;
  r.direction = glm::normalize(to - from);
  r.tmin = 1e-4f;
  r.tmax = glm::length(to - from) * (1.0f - 1e-4f);
  return r;
}

TEST(MaterialMaps, AlphaMaskedQuadShadowsWithItsOpaquePartOnly) {
  const Scene scene = masked_quad_scene();
  const vec3 light(0.0f, 2.0f, 0.0f);
  // Floor points whose shadow rays cross the quad's opaque half, its hole, or miss it.
  const std::vector<vec3> shadowed = {{-0.5f, 0, 0}, {-1.2f, 0, 0.3f}, {-0.1f, 0, -0.8f}};
  const std::vector<vec3> lit = {{0.5f, 0, 0}, {1.2f, 0, 0.3f}, {0.1f, 0, -0.8f}, {-1.9f, 0, 0}};
  std::vector<Ray> rays;
  for (const vec3& p : shadowed) rays.push_back(segment(p, light));
  for (const vec3& p : lit) rays.push_back(segment(p, light));

  std::unique_ptr<Tracer> tracers[] = {make_embree_tracer(scene), make_bvh_tracer(scene)};
  for (int k = 0; k < 2; ++k) {
    const Tracer& tracer = *tracers[k];
    const TraceView view = tracer.view();
    std::vector<uint8_t> blocked(rays.size());
    tracer.occluded(rays, blocked);
    for (size_t i = 0; i < rays.size(); ++i) {
      const bool expected = i < shadowed.size();
      EXPECT_EQ(tracer.occluded(rays[i]), expected) << k << " ray " << i;
      EXPECT_EQ(view.occluded(rays[i]), expected) << k << " ray " << i;
      EXPECT_EQ(blocked[i] != 0, expected) << k << " ray " << i;
    }
    // Rays from above (primary and photon rays alike) stop on the opaque half and pass the hole.
    for (const float x : {-0.5f, 0.5f}) {
      Ray down;
      down.origin = vec3(x, 3.0f, 0.2f);
      down.direction = vec3(0.0f, -1.0f, 0.0f);
      const float expected_t = x < 0.0f ? 2.5f : 3.0f;
      const Hit one = tracer.intersect(down), from_view = view.intersect(down);
      std::vector<Hit> streamed(1);
      tracer.intersect(std::span<const Ray>(&down, 1), streamed, true);
      for (const Hit& hit : {one, from_view, streamed[0]}) {
        ASSERT_TRUE(hit.valid()) << k << " x " << x;
        EXPECT_NEAR(hit.t, expected_t, 1e-4f) << k << " x " << x;
        EXPECT_EQ(hit.mesh, x < 0.0f ? 1u : 0u) << k << " x " << x;
      }
    }
  }
}

// The shadow in a rendered frame: the floor under the hole is lit as if the quad were not there,
// under the opaque half it is dark (light at the zenith, camera beside it looking down).
TEST(MaterialMaps, AlphaMaskedShadowInTheDirectImage) {
  Scene masked = masked_quad_scene();
  Scene open = masked;
  open.meshes.pop_back();
  for (Scene* s : {&masked, &open}) {
    s->camera.position = vec3(0.0f, 0.4f, 0.0f);  // under the quad: it sees only the floor
    s->camera.look_at = vec3(0.0f);
    s->camera.vfov_deg = 90.0f;
    s->finalize();
  }
  render_test::Job job("direct", kSize, kSize);
  const Image with_quad = render_test::render(masked, job).color;
  const Image without = render_test::render(open, job).color;
  int lit = 0, dark = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float a = with_quad.at(x, y).y, b = without.at(x, y).y;
      if (std::abs(a - b) <= 1e-5f * b) ++lit;
      if (a == 0.0f && b > 0.0f) ++dark;
    }
  // The quad's two halves each shade about half the floor in view.
  EXPECT_GT(lit, kSize * kSize / 3);
  EXPECT_GT(dark, kSize * kSize / 3);
}

}  // namespace
}  // namespace bounce
