// The photon passes tiled keeps while only the camera moves: a ring of the last `capacity`
// passes. Photons live in world space, so after a camera move the passes still held, gathered
// together from the new view, are as valid an estimate as they were from the old one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bounce/render/photons.h"

namespace bounce {

class PhotonHistory {
 public:
  // Drops every pass and holds at most `capacity` (at least 1) from now on. The buffers are kept
  // for reuse.
  void reset(size_t capacity);
  // The buffer for a new pass, traced with sample index `sample` (PhotonTraceSettings::pass); it
  // becomes the newest pass and, when the ring is full, the oldest one is dropped. Its contents
  // are the dropped pass's (or empty) until the caller fills it.
  PhotonBuffer& add(uint32_t sample);

  size_t size() const { return count_; }
  size_t capacity() const { return slots_.size(); }
  // Pass k, oldest first (k < size()), and the sample index it was traced with.
  const PhotonBuffer& pass(size_t k) const { return slots_[slot(k)]; }
  uint32_t sample(size_t k) const { return samples_[slot(k)]; }
  const PhotonBuffer& newest() const { return pass(count_ - 1); }  // size() > 0
  size_t photon_count() const;

  // Every pass's photons in one buffer, oldest pass first, each pass in its own order: the union
  // the gathers read after a camera move. Clearances are copied when every pass has them. With
  // `newest`, only the newest that many passes (a frame that traced several).
  void concatenate(PhotonBuffer& out) const { concatenate(out, count_); }
  void concatenate(PhotonBuffer& out, size_t newest) const;

 private:
  size_t slot(size_t k) const { return (first_ + k) % slots_.size(); }

  std::vector<PhotonBuffer> slots_;
  std::vector<uint32_t> samples_;
  size_t first_ = 0;  // slot of the oldest pass
  size_t count_ = 0;
};

}  // namespace bounce
