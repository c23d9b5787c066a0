// The CPU launcher of the vertex technique's photon paths (vertex_photon_path.h): which emitter
// each path leaves and along which point of its set, then the paths in parallel, their photons in
// path order (deterministic whatever the thread count).
//
// Paths are shared out over the emitters by power (at least one each); emitter l gets c_l paths
// per frame and a set of c_l * F points (F = accumulation_frames), of which frame slot f uses
// points f, f + F, f + 2F, ...: the ring's F slots together hold the whole low-discrepancy set,
// and the slot that replaces one F frames later follows the same paths (frame coherence).
#pragma once

#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "bounce/render/photon_emission.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_view.h"
#include "bounce/techniques/vertex/photon_kdtree.h"
#include "bounce/techniques/vertex/vertex_photon_path.h"
#include "bounce/trace/tracer.h"

namespace bounce {

struct VertexPhotonSettings {
  uint32_t photons = 200;      // photons_from_light: paths per frame (shared by the emitters)
  uint32_t frames = 10;        // accumulation_frames
  uint32_t slot = 0;           // this frame's ring slot
  bool saff_kuijlaars = true;  // light_distribution_type 0, else random directions
  bool stratified = true;      // diffuse_light_distribution 0, else random
  uint32_t splits = 36;        // diffuse_reflections
  int recursion_depth = 1;
  bool roulette = true;
  bool store_direct = false;
  int snowball = 1;
  float snowball_radius = 0.0f;
  uint32_t seed = 0;
  bool every_triangle = false;  // BSP_tree off
  // 0: the frame-coherent sets; k > 0: the sets turned and shifted by a hash of k (a fresh,
  // independent photon set, for frames at rest).
  uint32_t variant = 0;
  // Per emitter (LightPicker entry): 1 for a light that moves, whose photons trace() keeps apart
  // (the flashlight). Empty, or missing entries: the light stays put.
  std::vector<uint8_t> moving;
  // Trace only the emitters `moving` flags, leaving `out` as it is: the caller holds the other
  // emitters' photons of this slot from the last time it was traced, which retracing would give
  // again (frame-coherent paths with nothing they depend on changed). Ignored, and every path
  // traced, when the paths per emitter differ from the last trace's (a light's power changed).
  bool reuse_still = false;
};

struct VertexPhotonStats {
  uint64_t paths = 0;   // traced
  uint64_t stored = 0;  // by the traced paths
  uint64_t rays = 0;
  bool reused = false;  // settings.reuse_still took effect: `out` was left as it was
  // The paths per emitter differ from the last trace's: every path of the slot is new.
  bool emission_changed = false;
};

class VertexPhotonTracer {
 public:
  // This frame's photons into `out`; with `moving_out`, those of the emitters settings.moving
  // flags go there instead (each in path order, as out alone would hold them).
  VertexPhotonStats trace(const Scene& scene, const SceneView& view, const Tracer& tracer,
                          const VertexPhotonSettings& settings, MapPhotons& out,
                          MapPhotons* moving_out = nullptr);
  // Paths each emitter (LightPicker entry) leaves per frame for `photons` in all.
  static std::vector<uint32_t> paths_per_emitter(const std::vector<float>& pmf, uint32_t photons);

 private:
  const std::vector<vec3>& point_set(int kind, uint32_t n, float z_lo, bool saff_kuijlaars,
                                     uint32_t seed);
  std::map<std::tuple<int, uint32_t, float, bool, uint32_t>, std::vector<vec3>> sets_;
  std::vector<vec3> bounce_dirs_;
  std::tuple<uint32_t, bool, uint32_t> bounce_key_{0, false, 0};
  std::vector<VertexPathStart> starts_;
  std::vector<uint32_t> path_ids_;
  std::vector<MapPhotons> chunks_, moving_chunks_;
  std::vector<uint32_t> last_counts_;  // paths per emitter of the last trace
};

}  // namespace bounce
