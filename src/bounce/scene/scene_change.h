// What changed between two frames. The Renderer owns the one notion of it: scene edits and
// animation arrive through Renderer::scene_changed, and the Renderer itself adds what it sees
// (a new camera or image size, changed technique parameters or frame settings, a new technique).
// Techniques receive it in prepare() and indirect() and restart, reuse or reproject their state.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace bounce {

struct SceneChange {
  std::vector<uint32_t> moved_meshes;  // meshes whose vertices changed (sorted, unique)
  bool lights = false;                 // a light moved or its colour or power changed
  bool materials = false;              // a material changed (emission included)
  bool camera = false;                 // the camera (or the image size) changed
  bool parameters = false;             // technique parameters or frame settings changed
  // Everything is new: the first frame, a new technique or a new scene. Nothing carries over.
  bool everything = false;

  static SceneChange all() {
    SceneChange c;
    c.everything = true;
    return c;
  }

  bool geometry() const { return !moved_meshes.empty() || everything; }
  // Whether light transport in world space (photons, per-vertex light, hit buffers) is still
  // valid: only the camera moved, or nothing did.
  bool world_changed() const { return geometry() || lights || materials || parameters; }
  bool any() const { return world_changed() || camera; }
  bool camera_only() const { return camera && !world_changed(); }

  // Adds another change to this one.
  void merge(const SceneChange& other) {
    moved_meshes.insert(moved_meshes.end(), other.moved_meshes.begin(), other.moved_meshes.end());
    std::sort(moved_meshes.begin(), moved_meshes.end());
    moved_meshes.erase(std::unique(moved_meshes.begin(), moved_meshes.end()), moved_meshes.end());
    lights |= other.lights;
    materials |= other.materials;
    camera |= other.camera;
    parameters |= other.parameters;
    everything |= other.everything;
  }
};

}  // namespace bounce
