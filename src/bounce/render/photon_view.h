// PhotonView: a photon buffer's arrays as pointers, for per-photon and per-pixel kernels
// (PhotonBuffer::view()).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

// Rays cast by each photon along its tangent plane to find nearby occluders (see
// photon_clearance.h); a gather point is accepted only within this visibility polygon.
inline constexpr int kClearanceRays = 8;

// Field by field as PhotonBuffer (photons.h), which documents them. Arrays that are not computed
// (clearances, decoded directions) are null.
template <bool kConst>
struct PhotonViewT {
  template <typename T>
  using Ptr = maybe_const_t<T, kConst>*;

  Ptr<vec3> position = nullptr;
  Ptr<vec3> flux = nullptr;
  Ptr<uint32_t> incident = nullptr;
  Ptr<uint32_t> normal = nullptr;
  Ptr<float> clearance = nullptr;  // kClearanceRays per photon
  Ptr<float> min_clearance = nullptr;
  Ptr<vec3> incident_dir = nullptr;
  Ptr<vec3> normal_dir = nullptr;
  uint32_t count = 0;

  // A writable view reads as a read-only one.
  template <bool kTo>
  requires(kTo && !kConst) BOUNCE_HD operator PhotonViewT<kTo>() const {
    return {position,      flux,         incident,   normal, clearance,
            min_clearance, incident_dir, normal_dir, count};
  }

  BOUNCE_HD size_t size() const { return count; }
  BOUNCE_HD Ptr<float> clearance_of(size_t i) const { return clearance + i * kClearanceRays; }
};
using PhotonView = PhotonViewT<false>;
using ConstPhotonView = PhotonViewT<true>;
static_assert(std::is_trivially_copyable_v<PhotonView>);

}  // namespace bounce
