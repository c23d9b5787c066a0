// Edits made to a loaded scene (by the viewer's panel, by benchmarks), each returning the
// SceneChange to hand to Renderer::scene_changed.
#pragma once

#include <cstddef>

#include "bounce/core/math.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_change.h"

namespace bounce {

// Moves the vertices of area light `index`'s triangles by `offset` (a vertex its mesh shares with
// other triangles moves with them), in the animation's rest copy too so that the next pose keeps
// the edit, and re-derives the scene (area lights, bounds).
SceneChange move_area_light(Scene& scene, size_t index, vec3 offset);

// Moves every vertex of mesh `index` by `offset`, the same way.
SceneChange move_mesh(Scene& scene, uint32_t index, vec3 offset);

}  // namespace bounce
