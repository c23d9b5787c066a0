// What changed in a scene between two frames: the frame pipeline refits the tracer for moved
// meshes and tells the technique to restart (or reproject) its accumulated state.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace bounce {

struct SceneChange {
  std::vector<uint32_t> moved_meshes;  // meshes whose vertices changed (sorted, unique)
  bool lights = false;                 // a light moved or its colour or power changed
  bool materials = false;              // a material changed (emission included)

  bool geometry() const { return !moved_meshes.empty(); }
  bool any() const { return geometry() || lights || materials; }

  // Adds another change to this one.
  void merge(const SceneChange& other) {
    moved_meshes.insert(moved_meshes.end(), other.moved_meshes.begin(), other.moved_meshes.end());
    std::sort(moved_meshes.begin(), moved_meshes.end());
    moved_meshes.erase(std::unique(moved_meshes.begin(), moved_meshes.end()), moved_meshes.end());
    lights |= other.lights;
    materials |= other.materials;
  }
};

}  // namespace bounce
