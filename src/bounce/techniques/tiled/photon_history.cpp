#include "bounce/techniques/tiled/photon_history.h"

#include <algorithm>

#include "bounce/core/parallel.h"

namespace bounce {

void PhotonHistory::reset(size_t capacity) {
  capacity = std::max<size_t>(capacity, 1);
  slots_.resize(capacity);
  samples_.assign(capacity, 0);
  first_ = 0;
  count_ = 0;
}

PhotonBuffer& PhotonHistory::add(uint32_t sample) {
  if (slots_.empty()) reset(1);
  if (count_ == slots_.size()) {
    first_ = slot(1);
    --count_;
  }
  const size_t s = slot(count_);
  ++count_;
  samples_[s] = sample;
  return slots_[s];
}

size_t PhotonHistory::photon_count() const {
  size_t n = 0;
  for (size_t k = 0; k < count_; ++k) n += pass(k).size();
  return n;
}

void PhotonHistory::concatenate(PhotonBuffer& out, size_t newest) const {
  const size_t count = std::min(newest, count_), skip = count_ - count;
  bool clearance = count > 0;
  std::vector<size_t> first(count + 1, 0);
  for (size_t k = 0; k < count; ++k) {
    first[k + 1] = first[k] + pass(skip + k).size();
    clearance = clearance && pass(skip + k).has_clearance();
  }
  const size_t n = first[count];
  out.resize(n);
  out.incident_dir.resize(n);
  out.normal_dir.resize(n);
  out.clearance.resize(clearance ? n * kClearanceRays : 0);
  out.min_clearance.resize(clearance ? n : 0);
  // A task per pass: each copies its arrays to its own range.
  parallel_for(
      count,
      [&](size_t k) {
        const PhotonBuffer& p = pass(skip + k);
        const size_t at = first[k];
        std::copy(p.position.begin(), p.position.end(), out.position.begin() + at);
        std::copy(p.flux.begin(), p.flux.end(), out.flux.begin() + at);
        std::copy(p.incident.begin(), p.incident.end(), out.incident.begin() + at);
        std::copy(p.normal.begin(), p.normal.end(), out.normal.begin() + at);
        std::copy(p.incident_dir.begin(), p.incident_dir.end(), out.incident_dir.begin() + at);
        std::copy(p.normal_dir.begin(), p.normal_dir.end(), out.normal_dir.begin() + at);
        if (!clearance) return;
        std::copy(p.clearance.begin(), p.clearance.end(),
                  out.clearance.begin() + at * kClearanceRays);
        std::copy(p.min_clearance.begin(), p.min_clearance.end(), out.min_clearance.begin() + at);
      },
      1);
}

}  // namespace bounce
