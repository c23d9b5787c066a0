// Photon hits of technique `vertex` read each texture's mean colour (surface_at<true>), as the
// seed reflects photons with a texture's average; pixels read the texels.
#include <gtest/gtest.h>

#include "bounce/render/surface.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_data.h"
#include "checker_texture.h"
#include "hand_built_scenes.h"

namespace bounce {
namespace {

// A quad textured with a 2 x 2 checker of red, green, blue and yellow.
Scene checker_quad() {
  return scene_test::textured_unit_quad(checker_texture(), vec3(0.5f));
}

TEST(TextureMean, PhotonHitsReadTheTexturesMeanAndPixelsTheTexels) {
  const Scene scene = checker_quad();
  EXPECT_EQ(mean_texel(scene.textures[0]), vec3(0.5f, 0.5f, 0.25f));
  const SceneData data = SceneData::from(scene);
  const SceneView view = data.view();
  ASSERT_EQ(view.texture_count, 1u);
  EXPECT_EQ(view.textures[0].mean, vec3(0.5f, 0.5f, 0.25f));
  Hit hit;
  hit.t = 1.0f;
  hit.mesh = 0;
  hit.triangle = 0;
  const vec3 direction(0.0f, 0.0f, -1.0f);
  // Near the red texel's centre and near the green one's.
  for (const vec2 b : {vec2(0.1f, 0.1f), vec2(0.6f, 0.1f)}) {
    hit.barycentric = b;
    const SurfaceHit texels = surface_at(view, hit, direction);
    const SurfaceHit mean = surface_at<true>(view, hit, direction);
    EXPECT_EQ(mean.albedo, vec3(0.25f, 0.25f, 0.125f));
    EXPECT_GT(glm::length(texels.albedo - mean.albedo), 0.1f);
    EXPECT_EQ(mean.position, texels.position);
    EXPECT_EQ(mean.normal, texels.normal);
    EXPECT_EQ(mean.geometric_normal, texels.geometric_normal);
  }
}

}  // namespace
}  // namespace bounce
