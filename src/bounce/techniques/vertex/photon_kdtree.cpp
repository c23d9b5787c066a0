#include "bounce/techniques/vertex/photon_kdtree.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>

#include "bounce/core/parallel.h"

namespace bounce {

namespace {

// Ranges above this size build their two halves in parallel.
constexpr uint32_t kParallelRange = 8192;

struct Builder {
  KdBuildItem* items;
  uint8_t* axis;
  uint32_t leaf_size;

  // The seed's build_tree: the median on the widest axis of the range's box goes to the middle;
  // each half recurses with the box clipped at the median.
  void build(uint32_t from, uint32_t to, vec3 lo, vec3 hi) const {
    if (kd_is_leaf(from, to, leaf_size)) return;
    const vec3 extent = hi - lo;
    const int a = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const uint32_t mid = kd_middle(from, to);
    std::nth_element(
        items + from, items + mid, items + to,
        [a](const KdBuildItem& p, const KdBuildItem& q) { return p.position[a] < q.position[a]; });
    axis[mid] = uint8_t(a);
    const float split = items[mid].position[a];
    vec3 left_hi = hi, right_lo = lo;
    left_hi[a] = split;
    right_lo[a] = split;
    if (to - from > kParallelRange) {
      tbb::parallel_invoke([&] { build(from, mid, lo, left_hi); },
                           [&] { build(mid + 1, to, right_lo, hi); });
    } else {
      build(from, mid, lo, left_hi);
      build(mid + 1, to, right_lo, hi);
    }
  }
};

}  // namespace

void PhotonKdTree::build(const MapPhotons& photons, uint32_t leaf_size) {
  leaf_size_ = std::max(leaf_size, 1u);
  const uint32_t n = uint32_t(photons.size());
  items_.resize(n);
  parallel_for(
      n,
      [&](size_t i) {
        items_[i] = {photons.position[i], uint32_t(i)};
      },
      4096);
  axis_.assign(n, 0);
  vec3 lo(0.0f), hi(0.0f);
  if (n > 0) {
    lo = hi = photons.position[0];
    for (const vec3& p : photons.position) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  Builder{items_.data(), axis_.data(), leaf_size_}.build(0, n, lo, hi);
  lo_ = lo;
  hi_ = hi;
  photons_.position.resize(n);
  photons_.flux.resize(n);
  photons_.normal.resize(n);
  parallel_for(
      n,
      [&](size_t i) {
        const uint32_t k = items_[i].index;
        photons_.position[i] = items_[i].position;
        photons_.flux[i] = photons.flux[k];
        photons_.normal[i] = photons.normal[k];
      },
      4096);
}

}  // namespace bounce
