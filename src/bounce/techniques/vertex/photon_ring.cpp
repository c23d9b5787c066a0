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
  const size_t n = photon_count();
  out.position.reserve(n);
  out.flux.reserve(n);
  out.normal.reserve(n);
  for (const MapPhotons& s : slots_) {
    out.position.insert(out.position.end(), s.position.begin(), s.position.end());
    out.flux.insert(out.flux.end(), s.flux.begin(), s.flux.end());
    out.normal.insert(out.normal.end(), s.normal.begin(), s.normal.end());
  }
}

size_t PhotonRing::photon_count() const {
  size_t n = 0;
  for (const MapPhotons& s : slots_) n += s.size();
  return n;
}

}  // namespace bounce
