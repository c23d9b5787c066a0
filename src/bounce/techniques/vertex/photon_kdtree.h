// The real-time photon map's index (seed 004 §5.3.2-5.3.3; notes/seed-004.md §2.8): a kd-tree
// whose median photon sits in the middle of each index range (no heap layout), split on the
// widest axis of the range's box, with unsorted leaf buckets of at most `leaf_size` photons. The
// photons are copied into tree order, so a query walks contiguous arrays.
//
// The k-nearest search (knn_search) is a kernel body: an explicit stack instead of recursion and
// a fixed-capacity max-heap instead of the seed's vector, so it never allocates. A filter runs on
// each photon *before* it enters the heap (the seed found filtering afterwards unstable): the
// sphere slice and the side test of vertex_estimate.h.
#pragma once

#include <cstdint>
#include <type_traits>
#include <vector>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

// The most photons one estimate may hold (the seed's max_search_count is 50).
inline constexpr int kMaxSearchCount = 512;

// A photon as the map holds it.
struct MapPhotons {
  std::vector<vec3> position;
  std::vector<vec3> flux;    // W
  std::vector<vec3> normal;  // the surface's normal on the side the photon arrived from

  size_t size() const { return position.size(); }
  bool operator==(const MapPhotons&) const = default;
  // Adds `more`'s photons after these.
  void append(const MapPhotons& more) {
    position.insert(position.end(), more.position.begin(), more.position.end());
    flux.insert(flux.end(), more.flux.begin(), more.flux.end());
    normal.insert(normal.end(), more.normal.begin(), more.normal.end());
  }
  void reserve(size_t n) {
    position.reserve(n);
    flux.reserve(n);
    normal.reserve(n);
  }
  void clear() {
    position.clear();
    flux.clear();
    normal.clear();
  }
};

struct PhotonKdTreeView {
  const vec3* position = nullptr;  // tree order
  const vec3* flux = nullptr;
  const vec3* normal = nullptr;
  const uint8_t* axis = nullptr;  // split axis of the node whose median is at this index
  uint32_t count = 0;
  uint32_t leaf_size = 1;
  // The box around every photon, when `bounded`: a search clips it per level to each node's
  // range, for filters that can rule a whole box out (KnnBoxTest).
  vec3 lo{0.0f}, hi{0.0f};
  bool bounded = false;
};
static_assert(std::is_trivially_copyable_v<PhotonKdTreeView>);

// The same predicate in build and search (the seed's two differed by one: notes §2.8).
BOUNCE_HD inline bool kd_is_leaf(uint32_t from, uint32_t to, uint32_t leaf_size) {
  return to - from <= leaf_size;
}
BOUNCE_HD inline uint32_t kd_middle(uint32_t from, uint32_t to) {
  return from + (to - from) / 2;
}

// A photon's position beside its index, as the build sorts them: the median search compares and
// moves these, reading contiguous memory, instead of indices that send every comparison to a
// photon's position elsewhere.
struct KdBuildItem {
  vec3 position;
  uint32_t index;
};

class PhotonKdTree {
 public:
  // Builds over `photons` (copied into tree order); leaf_size >= 1.
  void build(const MapPhotons& photons, uint32_t leaf_size);
  PhotonKdTreeView view() const {
    return {photons_.position.data(),
            photons_.flux.data(),
            photons_.normal.data(),
            axis_.data(),
            uint32_t(photons_.size()),
            leaf_size_,
            lo_,
            hi_,
            true};
  }
  const MapPhotons& photons() const { return photons_; }
  size_t size() const { return photons_.size(); }

 private:
  MapPhotons photons_;
  std::vector<uint8_t> axis_;
  std::vector<KdBuildItem> items_;
  uint32_t leaf_size_ = 1;
  vec3 lo_{0.0f}, hi_{0.0f};
};

// The k nearest photons found so far: a max-heap on squared distance, fixed capacity.
struct KnnHeap {
  float dist2[kMaxSearchCount];
  uint32_t index[kMaxSearchCount];
  int size = 0;
  int capacity = 0;  // k

  BOUNCE_HD bool full() const { return size == capacity; }
  BOUNCE_HD float top() const { return dist2[0]; }
  // Adds a photon at squared distance d2 (the caller checked d2 is below the current radius).
  BOUNCE_HD void push(float d2, uint32_t i) {
    if (size < capacity) {
      int c = size++;
      while (c > 0) {
        const int parent = (c - 1) / 2;
        if (dist2[parent] >= d2) break;
        dist2[c] = dist2[parent];
        index[c] = index[parent];
        c = parent;
      }
      dist2[c] = d2;
      index[c] = i;
      return;
    }
    // Full: the new photon replaces the farthest, then sinks.
    int c = 0;
    for (;;) {
      const int l = 2 * c + 1, r = l + 1;
      int largest = c;
      float largest_d2 = d2;
      if (l < size && dist2[l] > largest_d2) largest = l, largest_d2 = dist2[l];
      if (r < size && dist2[r] > largest_d2) largest = r, largest_d2 = dist2[r];
      if (largest == c) break;
      dist2[c] = dist2[largest];
      index[c] = index[largest];
      c = largest;
    }
    dist2[c] = d2;
    index[c] = i;
  }
};

// The search radius, squared, while the heap holds `heap`: the farthest photon once full (the
// seed's shrinking radius), the maximum before.
BOUNCE_HD inline float knn_radius2(const KnnHeap& heap, float max_radius2) {
  return heap.full() ? heap.top() : max_radius2;
}

// Offers photon i of tree t at squared distance d2 to the heap as index base + i, if it is closer
// than the radius and the filter accepts it: accept(t, i), or accept(base + i).
template <typename Filter>
BOUNCE_HD inline void knn_offer(const PhotonKdTreeView& t, uint32_t base, vec3 x, uint32_t i,
                                float max_radius2, const Filter& accept, KnnHeap& heap) {
  const vec3 d = t.position[i] - x;
  const float d2 = glm::dot(d, d);
  if (d2 >= knn_radius2(heap, max_radius2)) return;
  // A filter may read the photon from its own tree (no search of the map for it) or take the
  // map's index.
  if constexpr (std::is_invocable_v<const Filter&, const PhotonKdTreeView&, uint32_t>) {
    if (!accept(t, i)) return;
  } else {
    if (!accept(base + i)) return;
  }
  heap.push(d2, base + i);
}

// Whether Filter can rule out a whole box of photons: filter.may_accept_box(lo, hi) is false
// only when it would reject every photon inside.
template <typename F, typename = void>
struct KnnBoxTest : std::false_type {};
template <typename F>
struct KnnBoxTest<F, std::void_t<decltype(std::declval<const F&>().may_accept_box(vec3(), vec3()))>>
    : std::true_type {};

// Goes on with a search whose heap holds what earlier trees gave: the k nearest of all of them
// stay (their indices offset by each tree's `base`), and the radius found so far prunes this tree.
template <typename Filter>
BOUNCE_HD inline void knn_search_more(const PhotonKdTreeView& t, uint32_t base, vec3 x,
                                      float max_radius2, const Filter& accept, KnnHeap& heap) {
  if (t.count == 0 || heap.capacity <= 0) return;
  // With a filter that tests boxes, each range carries its box (the photons' box clipped at the
  // medians above it: nth_element leaves none of a range beyond its split values).
  constexpr bool kBoxes = KnnBoxTest<Filter>::value;
  const bool boxes = kBoxes && t.bounded;
  struct Range {
    uint32_t from, to;
    float plane_d2;  // squared distance from x to the splitting plane that separates it
    vec3 lo, hi;
  };
  Range stack[64];
  int top = 0;
  stack[top++] = {0, t.count, 0.0f, t.lo, t.hi};
  while (top > 0) {
    const Range r = stack[--top];
    if (r.plane_d2 >= knn_radius2(heap, max_radius2)) continue;
    if constexpr (kBoxes) {
      if (boxes && !accept.may_accept_box(r.lo, r.hi)) continue;
    }
    if (kd_is_leaf(r.from, r.to, t.leaf_size)) {
      for (uint32_t i = r.from; i < r.to; ++i) knn_offer(t, base, x, i, max_radius2, accept, heap);
      continue;
    }
    const uint32_t mid = kd_middle(r.from, r.to);
    knn_offer(t, base, x, mid, max_radius2, accept, heap);
    const int axis = t.axis[mid];
    const float split = t.position[mid][axis];
    const float delta = x[axis] - split;
    Range left{r.from, mid, 0.0f, r.lo, r.hi}, right{mid + 1, r.to, 0.0f, r.lo, r.hi};
    left.hi[axis] = split;
    right.lo[axis] = split;
    Range near = delta < 0.0f ? left : right;
    Range far = delta < 0.0f ? right : left;
    far.plane_d2 = delta * delta;
    // The far side first onto the stack, so the near side is searched first.
    if (far.to > far.from) stack[top++] = far;
    if (near.to > near.from) stack[top++] = near;
  }
}

// The k = heap.capacity nearest photons to x within max_radius that `accept(index)` accepts, into
// `heap` (emptied first).
template <typename Filter>
BOUNCE_HD inline void knn_search(const PhotonKdTreeView& t, vec3 x, float max_radius,
                                 const Filter& accept, KnnHeap& heap) {
  heap.size = 0;
  knn_search_more(t, 0, x, max_radius * max_radius, accept, heap);
}

// Every photon of t offered as base + i: the brute-force form of knn_search_more.
template <typename Filter>
BOUNCE_HD inline void knn_brute_force_more(const PhotonKdTreeView& t, uint32_t base, vec3 x,
                                           float max_radius2, const Filter& accept, KnnHeap& heap) {
  if (heap.capacity <= 0) return;
  for (uint32_t i = 0; i < t.count; ++i) knn_offer(t, base, x, i, max_radius2, accept, heap);
}

// The same answer by looking at every photon: the seed's Exact_photon_map, the check of the tree.
template <typename Filter>
BOUNCE_HD inline void knn_brute_force(const PhotonKdTreeView& t, vec3 x, float max_radius,
                                      const Filter& accept, KnnHeap& heap) {
  heap.size = 0;
  knn_brute_force_more(t, 0, x, max_radius * max_radius, accept, heap);
}

// The photon map as two trees searched as one: the photons of lights that stay put (rebuilt only
// when those photons change) and those of lights that move (the flashlight: rebuilt each frame).
// Index i names the first tree's photon i below first.count, else the second's i - first.count.
struct PhotonMapView {
  PhotonKdTreeView first, second;

  PhotonMapView() = default;
  BOUNCE_HD PhotonMapView(const PhotonKdTreeView& a, const PhotonKdTreeView& b = {})
      : first(a), second(b) {}
  BOUNCE_HD uint32_t count() const { return first.count + second.count; }
  BOUNCE_HD vec3 position(uint32_t i) const {
    return i < first.count ? first.position[i] : second.position[i - first.count];
  }
  BOUNCE_HD vec3 flux(uint32_t i) const {
    return i < first.count ? first.flux[i] : second.flux[i - first.count];
  }
  BOUNCE_HD vec3 normal(uint32_t i) const {
    return i < first.count ? first.normal[i] : second.normal[i - first.count];
  }
};

// The k nearest accepted photons of both trees (exact: by brute force), into `heap`.
template <typename Filter>
BOUNCE_HD inline void knn_search(const PhotonMapView& map, vec3 x, float max_radius, bool exact,
                                 const Filter& accept, KnnHeap& heap) {
  heap.size = 0;
  const float max_radius2 = max_radius * max_radius;
  if (exact) {
    knn_brute_force_more(map.first, 0, x, max_radius2, accept, heap);
    knn_brute_force_more(map.second, map.first.count, x, max_radius2, accept, heap);
  } else {
    knn_search_more(map.first, 0, x, max_radius2, accept, heap);
    knn_search_more(map.second, map.first.count, x, max_radius2, accept, heap);
  }
}

}  // namespace bounce
