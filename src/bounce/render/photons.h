// Photons as a structure of arrays: what photon tracing deposits and the density estimators read.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "bounce/core/math.h"
#include "bounce/core/octahedral.h"
#include "bounce/core/parallel.h"

namespace bounce {

// Rays cast by each photon along its tangent plane to find nearby occluders (see
// photon_clearance.h); a gather point is accepted only within this visibility polygon.
inline constexpr int kClearanceRays = 8;

struct PhotonBuffer {
  std::vector<vec3> position;
  std::vector<vec3> flux;          // W, per channel
  std::vector<uint32_t> incident;  // octahedral-packed direction of travel towards the surface
  std::vector<uint32_t> normal;    // octahedral-packed surface normal, on the side it arrived from
  // Free distance along each tangent ray (kClearanceRays per photon) and the smallest of them;
  // empty when not computed.
  std::vector<std::array<float, kClearanceRays>> clearance;
  std::vector<float> min_clearance;
  // incident and normal decoded once per pass for the gathers (unpack_directions()).
  std::vector<vec3> incident_dir;
  std::vector<vec3> normal_dir;

  size_t size() const { return position.size(); }
  void clear() {
    position.clear();
    flux.clear();
    incident.clear();
    normal.clear();
    clearance.clear();
    min_clearance.clear();
    incident_dir.clear();
    normal_dir.clear();
  }
  void unpack_directions();
  void resize(size_t n) {
    position.resize(n);
    flux.resize(n);
    incident.resize(n);
    normal.resize(n);
  }
};

inline void PhotonBuffer::unpack_directions() {
  incident_dir.resize(size());
  normal_dir.resize(size());
  parallel_for(
      size(),
      [&](size_t i) {
        incident_dir[i] = oct_unpack(incident[i]);
        normal_dir[i] = oct_unpack(normal[i]);
      },
      1024);
}

}  // namespace bounce
