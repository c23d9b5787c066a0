// Loading scenes. A scene "spec" is a built-in name (cornell, cubes:N[:seed], leak) or a file:
// .obj (with .mtl), .gltf / .glb, or a *.bounce.json scene file.
#pragma once

#include <cstdint>
#include <string>

#include "bounce/scene/scene.h"

namespace bounce {

// Loads and finalizes a scene; throws Error with the file (or spec) and the problem. A file
// scene with no light at all gets the default sky (add_default_environment), so it renders
// visibly.
Scene load_scene(const std::string& spec);

// The default sky of a scene without lights: white radiance 1 from the upper hemisphere, so
// that an unshadowed diffuse surface facing up shows its albedo at the default exposure (0 EV
// maps radiance 1 to white), and a darker grey from below, so shapes read.
inline constexpr float kDefaultSkyRadiance = 1.0f;
inline constexpr float kDefaultGroundRadiance = 0.25f;
// Gives a finalized scene that has no lights and no emissive surfaces the default sky, an
// environment light with a two-row map (kDefaultSkyRadiance above the horizon,
// kDefaultGroundRadiance below), with a warning saying so; returns whether it did.
bool add_default_environment(Scene& scene);

// Individual loaders; each returns a scene that is not yet finalized.
Scene load_obj(const std::string& path);
Scene load_obj_text(const std::string& obj_text, const std::string& mtl_text,
                    const std::string& name);
Scene load_gltf(const std::string& path);
Scene load_scene_file(const std::string& path);

// Built-in scenes (finalized).
Scene make_cornell();
Scene make_cubes(uint32_t cube_count, uint32_t seed = 1);
Scene make_leak();

// True when `spec` names a built-in scene (cornell, leak, cubes, cubes:...) rather than a file;
// the name may still be malformed ("cubes:abc"), which make_builtin_scene reports.
bool is_builtin_scene(const std::string& spec);
// The built-in scene named by `spec` (finalized); throws Error for a malformed or unknown name.
Scene make_builtin_scene(const std::string& spec);
// Loads a model file (.obj, .gltf, .glb) chosen by its extension; not finalized.
Scene load_model_file(const std::string& path);

}  // namespace bounce
