// Every glTF and OBJ file of Debian's assimp-testmodels through `bounce info`: a real corpus of
// models, 37 of them deliberately broken. Each file's outcome is recorded here (it loads, or it
// fails with the reason named), so a loader change that crashes, hangs, or turns a clear message
// into a vague one shows up as a difference from the record. docs/reliability.md lists the classes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "app/cli_test_util.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;
using cli_test::Result;
using cli_test::run;

const fs::path kCorpus = "/usr/share/assimp/models";

// Files that load (bounce info exits 0 and counts triangles), relative to kCorpus.
const std::vector<std::string> kLoads = {
    "OBJ/WusonOBJ.obj",
    "OBJ/box.obj",
    "OBJ/box_mat_with_spaces.obj",
    "OBJ/box_without_lineending.obj",
    "OBJ/concave_polygon.obj",
    "OBJ/cube_mtllib_after_g.obj",
    "OBJ/cube_usemtl.obj",
    "OBJ/cube_with_vertexcolors.obj",
    "OBJ/cube_with_vertexcolors_uni.obj",
    "OBJ/multiple_spaces.obj",
    "OBJ/regr01.obj",
    "OBJ/regr_3429812.obj",
    "OBJ/space_in_material_name.obj",
    "OBJ/spider.obj",
    "OBJ/testmixed.obj",
    "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
    "glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb",
    "glTF2/BoxTexcoords-glTF/boxTexcoords.gltf",
    "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
    "glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf",
    "glTF2/BoxTextured-glTF-pbrSpecularGlossiness/BoxTextured.gltf",
    "glTF2/BoxTextured-glTF/BoxTextured.gltf",
    "glTF2/ClearCoat-glTF/ClearCoatTest.gltf",
    "glTF2/cameras/Cameras.gltf",
    "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_04.gltf",
    "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_05.gltf",
    "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf",
    "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_11.gltf",
    "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_12.gltf",
    "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_13.gltf",
    "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_14.gltf",
    "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_15.gltf",
    "glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf",
    "glTF2/issue_3269/texcoord_crash.gltf",
    "glTF2/simple_skin/simple_skin.gltf",
    "glTF2/textureTransform/TextureTransformTest.gltf",
    "glTF2/wrongTypes/badExtension.gltf",
    "glTF2/wrongTypes/badNumber.gltf",
    "glTF2/wrongTypes/badObject.gltf",
    "glTF2/wrongTypes/badString.gltf",
    "glTF2/wrongTypes/badUint.gltf",
};

// Files that fail, with a piece of the message that names the reason.
const std::map<std::string, std::string> kFails = {
    {"OBJ/box_UTF16BE.obj", "the file is UTF-16 text"},
    {"OBJ/box_longline.obj", "a face has 936 vertices; at most 255 are supported"},
    {"OBJ/empty_mat.obj", "empty_mat.mtl:3: 'newmtl' needs a name"},
    {"OBJ/number_formats.obj", "'3.1+e2' is not a finite number"},
    {"OBJ/point_cloud.obj", "the scene has no triangles"},
    {"OBJ/testline.obj", "the scene has no triangles"},
    {"OBJ/testpoints.obj", "the scene has no triangles"},
    {"glTF/BoxTextured-glTF-Binary/BoxTextured.glb", "this is a binary glTF 1.0 file"},
    {"glTF/BoxTextured-glTF-Embedded/BoxTextured.gltf", "this is a glTF 1.0 file"},
    {"glTF/BoxTextured-glTF-MaterialsCommon/BoxTextured.gltf", "this is a glTF 1.0 file"},
    {"glTF/BoxTextured-glTF/BoxTextured.gltf", "this is a glTF 1.0 file"},
    // A glTF 1.0 file without the "asset" object that would say so.
    {"glTF/CesiumMilkTruck/CesiumMilkTruck.gltf", "\"asset\" object not found"},
    {"glTF/IncorrectVertexArrays/Cube_v1.gltf", "this is a glTF 1.0 file"},
    {"glTF/TwoBoxes/TwoBoxes.gltf", "this is a glTF 1.0 file"},
    {"glTF2/BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf",
     "requires glTF extension(s) KHR_technique_webgl"},
    {"glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "has a non-finite position"},
    {"glTF2/IncorrectVertexArrays/Cube.gltf", "35 vertex indices do not make whole triangles"},
    {"glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf", "index 65535 (at 0) is out of range"},
    {"glTF2/IndexOutOfRange/IndexOutOfRange.gltf", "index 255 (at 0) is out of range"},
    {"glTF2/MissingBin/BoxTextured.gltf", "File not found : BoxTextured0.bin"},
    {"glTF2/RecursiveNodes/RecursiveNodes.gltf", "node 0 is reached twice"},
    {"glTF2/SchemaFailures/sceneWrongType.gltf", "File not found : BoxTextured0.bin"},
    {"glTF2/TestNoRootNode/NoScene.gltf", "the default scene 0 does not exist"},
    {"glTF2/TestNoRootNode/SceneWithoutNodes.gltf", "the scene has no triangles"},
    {"glTF2/draco/2CylinderEngine.gltf", "requires glTF extension(s) KHR_draco_mesh_compression"},
    {"glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf",
     "skipping primitives of mode 0 (points and lines"},
    {"glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf",
     "skipping primitives of mode 1 (points and lines"},
    {"glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_02.gltf",
     "skipping primitives of mode 2 (points and lines"},
    {"glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_03.gltf",
     "skipping primitives of mode 3 (points and lines"},
    {"glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_07.gltf",
     "skipping primitives of mode 0 (points and lines"},
    {"glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_08.gltf",
     "skipping primitives of mode 1 (points and lines"},
    {"glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_09.gltf",
     "skipping primitives of mode 2 (points and lines"},
    {"glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_10.gltf",
     "skipping primitives of mode 3 (points and lines"},
    // "primitives" is an object where glTF requires an array: named, then nothing is left.
    {"glTF2/wrongTypes/badArray.gltf", "/meshes/0/primitives should be an array"},
    {"invalid/empty.obj", "the scene has no triangles"},
    {"invalid/malformed.obj", "uses index 0 (OBJ indices start at 1)"},
    {"invalid/malformed2.obj", "a face needs at least 3 vertices, found 0"},
};

// The corpus's glTF and OBJ files as installed, relative to kCorpus, sorted.
std::vector<std::string> installed_models() {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(kCorpus)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb" || ext == ".obj"))
      files.push_back(fs::relative(entry.path(), kCorpus).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// `bounce info` on one file. A crash shows as status -1 (killed by a signal); a hang fails the test
// through ctest's time limit.
Result info(const std::string& relative) {
  return run("info '" + (kCorpus / relative).string() + "'", true);
}

class AssimpCorpus : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::is_directory(kCorpus))
      GTEST_SKIP() << kCorpus << " is missing: install assimp-testmodels (scripts/setup.sh)";
  }
};

TEST_F(AssimpCorpus, EveryModelIsClassified) {
  const std::vector<std::string> files = installed_models();
  EXPECT_EQ(files.size(), kLoads.size() + kFails.size());
  for (const std::string& f : files)
    EXPECT_TRUE(std::count(kLoads.begin(), kLoads.end(), f) == 1 || kFails.count(f) == 1)
        << f << " is in the corpus but not in this test's record";
}

TEST_F(AssimpCorpus, ModelsThatLoadLoad) {
  for (const std::string& f : kLoads) {
    const Result r = info(f);
    EXPECT_EQ(r.status, 0) << f << ":\n" << r.output;
    EXPECT_TRUE(cli_test::contains(r.output, "triangles")) << f << ":\n" << r.output;
  }
}

TEST_F(AssimpCorpus, BrokenModelsFailWithTheirReasonNamed) {
  for (const auto& [f, reason] : kFails) {
    const Result r = info(f);
    EXPECT_EQ(r.status, 1) << f << ":\n" << r.output;
    // The error names the file (or, for a material library, the file it names) and the reason.
    EXPECT_TRUE(cli_test::contains(r.output, "bounce: error: ")) << f << ":\n" << r.output;
    EXPECT_TRUE(cli_test::contains(r.output, fs::path(f).stem().string())) << f << ":\n"
                                                                           << r.output;
    EXPECT_TRUE(cli_test::contains(r.output, reason)) << f << ": expected '" << reason << "':\n"
                                                      << r.output;
  }
}

}  // namespace
}  // namespace bounce
