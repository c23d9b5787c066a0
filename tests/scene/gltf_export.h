// Test helper: writes a bounce::Scene as glTF 2.0, so that tests can check that a scene read
// from glTF matches the same scene read from another format (and can make glTF fixtures).
#pragma once

#include <string>

#include "bounce/scene/scene.h"

namespace bounce {

// Writes `scene` to `path` as .gltf (JSON with the buffer embedded as a data URI) or, when
// `binary`, as .glb. Each mesh becomes a node and a mesh with one primitive per material, its
// vertices already in world space (normals and uvs kept; uvs are already in glTF's top-left
// convention). Materials become metallic-roughness materials with metallic 0: albedo is the base
// colour, f0 goes to KHR_materials_specular (f0 = 0.04 * specularColorFactor * specularFactor),
// emission above 1 is split into emissiveFactor and KHR_materials_emissive_strength. Point, spot
// and directional lights go to KHR_lights_punctual with colour x intensity equal to ours (no
// photometric conversion, as in the loader); a sphere light becomes a point light of the same
// far-field intensity (radiance * pi * r^2). The camera, if any, becomes a perspective camera
// node. Textures are not written (materials keep their factor colour only).
// Throws bounce::Error if the file cannot be written.
void write_scene_as_gltf(const Scene& scene, const std::string& path, bool binary);

}  // namespace bounce
