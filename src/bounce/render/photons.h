// Photons as a structure of arrays: what photon tracing deposits and the density estimators read.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/core/math.h"
#include "bounce/core/octahedral.h"
#include "bounce/core/parallel.h"
#include "bounce/render/photon_view.h"

namespace bounce {

struct PhotonBuffer {
  std::vector<vec3> position;
  std::vector<vec3> flux;          // W, per channel
  std::vector<uint32_t> incident;  // octahedral-packed direction of travel towards the surface
  std::vector<uint32_t> normal;    // octahedral-packed surface normal, on the side it arrived from
  // Free distance along each tangent ray (kClearanceRays per photon, photon by photon) and the
  // smallest of them; empty when not computed.
  std::vector<float> clearance;
  std::vector<float> min_clearance;
  // incident and normal decoded once per pass for the gathers (unpack_directions()).
  std::vector<vec3> incident_dir;
  std::vector<vec3> normal_dir;

  size_t size() const { return position.size(); }
  bool has_clearance() const { return !clearance.empty(); }
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

  PhotonView view() { return view_of<false>(*this); }
  ConstPhotonView view() const { return view_of<true>(*this); }

 private:
  template <bool kConst, typename Buffer>
  static PhotonViewT<kConst> view_of(Buffer& b) {
    const auto data = [](auto& v) { return v.empty() ? nullptr : v.data(); };
    return {data(b.position),     data(b.flux),       data(b.incident),
            data(b.normal),       data(b.clearance),  data(b.min_clearance),
            data(b.incident_dir), data(b.normal_dir), uint32_t(b.size())};
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
