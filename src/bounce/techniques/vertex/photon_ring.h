// The real-time photon map's storage (seed 004 §5.3.1; notes/seed-004.md §2.7): one slot of
// photons per frame for the last `accumulation_frames` frames, a ring. Each frame refills the
// oldest slot; photons age out after that many frames, with no invalidation scheme.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/techniques/vertex/photon_kdtree.h"

namespace bounce {

class PhotonRing {
 public:
  // Empties the ring and sets its size (>= 1).
  void reset(uint32_t frames);
  // The slot frame `frame` fills (frame % frames), emptied; counts it as filled.
  MapPhotons& begin_frame(uint32_t frame);
  // Every held photon, slot by slot in ring order, into `out` (the map the kd-tree is built on).
  void gather(MapPhotons& out) const;

  uint32_t frames() const { return uint32_t(slots_.size()); }
  // Slots holding a frame's photons (the map holds that many frames' emission).
  uint32_t filled() const { return filled_; }
  size_t photon_count() const;
  const MapPhotons& slot(uint32_t i) const { return slots_[i]; }

 private:
  std::vector<MapPhotons> slots_;
  std::vector<uint8_t> used_;
  uint32_t filled_ = 0;
};

}  // namespace bounce
