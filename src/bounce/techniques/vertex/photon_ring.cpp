#include "bounce/techniques/vertex/photon_ring.h"

#include <algorithm>

namespace bounce {

void PhotonRing::reset(uint32_t frames) {
  slots_.assign(std::max(frames, 1u), MapPhotons{});
  used_.assign(slots_.size(), 0);
  filled_ = 0;
}

MapPhotons& PhotonRing::begin_frame(uint32_t frame) {
  if (slots_.empty()) reset(1);
  const uint32_t i = frame % frames();
  if (!used_[i]) {
    used_[i] = 1;
    ++filled_;
  }
  slots_[i].clear();
  return slots_[i];
}

void PhotonRing::gather(MapPhotons& out) const {
  out.clear();
  out.reserve(photon_count());
  for (const MapPhotons& s : slots_) out.append(s);
}

size_t PhotonRing::photon_count() const {
  size_t n = 0;
  for (const MapPhotons& s : slots_) n += s.size();
  return n;
}

MapPhotons& RingedPhotonTree::refill(uint32_t frame, bool compare) {
  compare_ = compare;
  if (compare) replaced_ = ring_.slot(frame % ring_.frames());
  MapPhotons& slot = ring_.begin_frame(frame);
  slot_ = &slot;
  return slot;
}

MapPhotons& RingedPhotonTree::revisit(uint32_t frame) {
  compare_ = false;
  MapPhotons& slot = ring_.held(frame);
  slot_ = &slot;
  return slot;
}

void RingedPhotonTree::update(uint32_t leaf_size, bool unchanged) {
  kept_ = unchanged || (compare_ && slot_ && *slot_ == replaced_);
  if (kept_) return;
  ring_.gather(map_);
  tree_.build(map_, leaf_size);
}

}  // namespace bounce
