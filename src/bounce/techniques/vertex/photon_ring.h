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
  // The slot frame `frame` fills, as it is (held since it was last filled).
  MapPhotons& held(uint32_t frame) { return slots_[frame % frames()]; }

 private:
  std::vector<MapPhotons> slots_;
  std::vector<uint8_t> used_;
  uint32_t filled_ = 0;
};

// A ring with the kd-tree over every photon it holds (photons() in tree order's source), kept
// while a refill brings back exactly the photons it replaced (keep_unchanged: frame-coherent
// paths retrace themselves wherever nothing moved).
class RingedPhotonTree {
 public:
  void reset(uint32_t frames) { ring_.reset(frames); }
  // This frame's slot, emptied for tracing; with `compare`, what it held is kept to compare.
  MapPhotons& refill(uint32_t frame, bool compare);
  // This frame's slot as it is, for a refill that may leave it so (a filled ring's).
  MapPhotons& revisit(uint32_t frame);
  // Once the slot is traced: the tree stands if the slot holds what it held (`unchanged`: the
  // caller knows it does, having left the slot as it was), else is rebuilt.
  void update(uint32_t leaf_size, bool unchanged = false);

  const PhotonRing& ring() const { return ring_; }
  const PhotonKdTree& tree() const { return tree_; }
  const MapPhotons& photons() const { return map_; }  // the ring's photons, slot by slot
  bool kept() const { return kept_; }

 private:
  PhotonRing ring_;
  MapPhotons map_;
  PhotonKdTree tree_;
  MapPhotons replaced_;  // what the refilled slot held (when compared)
  const MapPhotons* slot_ = nullptr;
  bool compare_ = false;
  bool kept_ = false;
};

}  // namespace bounce
