// The same scene read from OBJ and from glTF renders the same image.
#include <gtest/gtest.h>

#include <filesystem>

#include "bounce/core/color.h"
#include "bounce/eval/render_image.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "render/render_test_util.h"
#include "scene/gltf_export.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

Image render_small(const Scene& scene) {
  render_test::Job job("direct", 64, 64);
  job.light_samples = 8;
  job.frames = 2;
  job.jitter = true;
  return render_test::render(scene, job).color;
}

TEST(ObjVsGltf, CornellBoxRendersTheSameFromBothFormats) {
  const fs::path dir = fs::temp_directory_path() / "bounce-obj-vs-gltf";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Scene obj =
      load_scene(std::string(BOUNCE_SOURCE_DIR) + "/scenes/cornell-box/cornell-box.obj");
  // The OBJ file has no camera; give it the built-in scene's, which the glTF file carries.
  Scene obj_with_camera = obj;
  obj_with_camera.camera = make_cornell().camera;
  const Image reference = render_small(obj_with_camera);
  ASSERT_GT(luminance(mean(reference)), 0.01f);

  for (const bool binary : {false, true}) {
    const fs::path path = dir / (binary ? "cornell.glb" : "cornell.gltf");
    write_scene_as_gltf(obj_with_camera, path.string(), binary);
    const Image gltf = render_small(load_scene(path.string()));
    // Relative root-mean-square difference of luminance: float round trips of the camera basis
    // may move a sample by a hair, nothing more.
    double diff2 = 0.0, ref2 = 0.0;
    for (size_t i = 0; i < reference.pixel_count(); ++i) {
      const double a = luminance(reference.pixels()[i]), b = luminance(gltf.pixels()[i]);
      diff2 += (a - b) * (a - b);
      ref2 += a * a;
    }
    EXPECT_LT(std::sqrt(diff2 / ref2), 1e-3) << path;
  }
}

}  // namespace
}  // namespace bounce
