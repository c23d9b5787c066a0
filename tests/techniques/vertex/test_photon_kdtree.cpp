// The kd-tree's k nearest photons equal brute force's (the seed's Exact_photon_map), with and
// without the sphere slice and the side test, over random photons and queries.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "bounce/core/rng.h"
#include "bounce/techniques/vertex/photon_kdtree.h"
#include "bounce/techniques/vertex/vertex_estimate.h"

namespace bounce {
namespace {

MapPhotons random_photons(size_t n, uint32_t seed) {
  Pcg32 rng(seed);
  MapPhotons p;
  for (size_t i = 0; i < n; ++i) {
    // Half on the plane y = 0, half in the volume: the slice has something to remove.
    const vec3 q(rng.next_float(), i % 2 ? rng.next_float() : 0.0f, rng.next_float());
    p.position.push_back(q);
    p.flux.push_back(vec3(rng.next_float()));
    p.normal.push_back(rng.next_float() < 0.8f ? vec3(0, 1, 0) : vec3(0, -1, 0));
  }
  return p;
}

std::vector<std::pair<float, uint32_t>> sorted(const KnnHeap& h) {
  std::vector<std::pair<float, uint32_t>> v;
  for (int i = 0; i < h.size; ++i) v.emplace_back(h.dist2[i], h.index[i]);
  std::sort(v.begin(), v.end());
  return v;
}

void expect_tree_equals_brute_force(bool slice, bool direction_test) {
  const MapPhotons photons = random_photons(20000, 7);
  for (const uint32_t leaf : {1u, 8u, 33u}) {
    PhotonKdTree tree;
    tree.build(photons, leaf);
    const PhotonKdTreeView view = tree.view();
    ASSERT_EQ(view.count, photons.size());
    Pcg32 rng(99);
    for (const int k : {1, 7, 50, 300}) {
      for (int q = 0; q < 200; ++q) {
        const vec3 x(rng.next_float(), q % 3 == 0 ? 0.0f : rng.next_float(), rng.next_float());
        const vec3 n(0, 1, 0);
        const float radius = 0.02f + 0.3f * rng.next_float();
        const EstimateFilter filter{x, n, slice, direction_test, 0.01f};
        KnnHeap fast, exact;
        fast.capacity = exact.capacity = k;
        knn_search(view, x, radius, filter, fast);
        knn_brute_force(view, x, radius, filter, exact);
        ASSERT_EQ(sorted(fast), sorted(exact)) << "k " << k << " leaf " << leaf << " query " << q;
        for (int i = 0; i < fast.size; ++i) {
          const uint32_t p = fast.index[i];
          EXPECT_LE(fast.dist2[i], radius * radius);
          if (slice) {
            EXPECT_LE(std::abs(view.position[p].y - x.y), 0.01f);
          }
          if (direction_test) {
            EXPECT_GT(view.normal[p].y, 0.0f);
          }
        }
      }
    }
  }
}

TEST(PhotonKdTree, NearestEqualBruteForce) {
  expect_tree_equals_brute_force(false, false);
}
TEST(PhotonKdTree, NearestEqualBruteForceWithSphereSlice) {
  expect_tree_equals_brute_force(true, false);
}
TEST(PhotonKdTree, NearestEqualBruteForceWithSliceAndSideTest) {
  expect_tree_equals_brute_force(true, true);
}

// The photons of the lights that stay put and of those that move live in two trees searched as
// one (PhotonMapView): the k nearest of both, with the slice and side test, are those of a single
// tree over all the photons, and so is the irradiance they give. A few photons in the second
// tree (the flashlight's share), half of them, or none.
TEST(PhotonKdTree, TwoTreesSearchAsOne) {
  const MapPhotons all = random_photons(12000, 11);
  for (const size_t every : {size_t(25), size_t(2), size_t(0)}) {
    SCOPED_TRACE(every);
    MapPhotons still, moving;
    for (size_t i = 0; i < all.size(); ++i) {
      MapPhotons& to = every > 0 && i % every == 0 ? moving : still;
      to.position.push_back(all.position[i]);
      to.flux.push_back(all.flux[i]);
      to.normal.push_back(all.normal[i]);
    }
    PhotonKdTree one, first, second;
    one.build(all, 8);
    first.build(still, 8);
    second.build(moving, 8);
    const PhotonMapView map(first.view(), second.view());
    ASSERT_EQ(map.count(), all.size());
    Pcg32 rng(5);
    for (const bool exact : {false, true})
      for (int q = 0; q < 300; ++q) {
        const vec3 x(rng.next_float(), q % 3 == 0 ? 0.0f : rng.next_float(), rng.next_float());
        const vec3 n(0, 1, 0);
        EstimateSettings s;
        s.k = q % 2 ? 50 : 7;
        s.max_radius = 0.05f + 0.3f * rng.next_float();
        s.sphere_slice = q % 4 < 2;
        s.slice_half = 0.01f;
        s.exact = exact;
        KnnHeap a, b;
        find_photons(map, x, n, s, a);
        find_photons(PhotonMapView(one.view()), x, n, s, b);
        // Indices differ (each tree has its own order): compare distances and positions.
        std::vector<std::pair<float, float>> pa, pb;
        for (int i = 0; i < a.size; ++i) pa.emplace_back(a.dist2[i], map.position(a.index[i]).x);
        for (int i = 0; i < b.size; ++i)
          pb.emplace_back(b.dist2[i], one.view().position[b.index[i]].x);
        std::sort(pa.begin(), pa.end());
        std::sort(pb.begin(), pb.end());
        ASSERT_EQ(pa, pb) << "query " << q << (exact ? " exact" : "");
        const vec3 ea = irradiance_from(map, a, s), eb = irradiance_from(one.view(), b, s);
        EXPECT_NEAR(ea.x, eb.x, 1e-5f * (1.0f + eb.x)) << "query " << q;
      }
  }
}

// A filter that tests boxes (the sphere slice) lets the search skip nodes off the tangent plane:
// the same k nearest, from fewer photons looked at (here 17% fewer). Without the box test every
// photon in the radius is offered to the slice one by one.
struct CountingFilter {
  EstimateFilter inner;
  mutable int offered = 0;
  bool operator()(const PhotonKdTreeView& t, uint32_t i) const {
    ++offered;
    return inner(t, i);
  }
};
struct CountingBoxFilter : CountingFilter {
  bool may_accept_box(vec3 lo, vec3 hi) const { return inner.may_accept_box(lo, hi); }
};

TEST(PhotonKdTree, TheSliceSkipsNodesOffThePlane) {
  // A floor with a tenth of the photons, and the rest in the room above it (as on a level: most
  // photons near a point lie on other surfaces).
  MapPhotons photons;
  Pcg32 place(3);
  for (int i = 0; i < 20000; ++i) {
    const bool floor = i % 10 == 0;
    photons.position.push_back(vec3(
        place.next_float(), floor ? 0.0f : 0.1f + 0.9f * place.next_float(), place.next_float()));
    photons.flux.push_back(vec3(1.0f));
    photons.normal.push_back(vec3(0, 1, 0));
  }
  PhotonKdTree tree;
  tree.build(photons, 8);
  Pcg32 rng(17);
  long plain_offers = 0, box_offers = 0;
  for (int q = 0; q < 200; ++q) {
    const vec3 x(rng.next_float(), 0.0f, rng.next_float());  // on the plane y = 0
    const EstimateFilter inner{x, vec3(0, 1, 0), true, false, 0.01f};
    CountingFilter plain{inner};
    CountingBoxFilter boxed{{inner}};
    KnnHeap a, b;
    a.capacity = b.capacity = 50;
    knn_search(tree.view(), x, 0.3f, plain, a);
    knn_search(tree.view(), x, 0.3f, boxed, b);
    ASSERT_EQ(sorted(a), sorted(b)) << "query " << q;
    plain_offers += plain.offered;
    box_offers += boxed.offered;
  }
  EXPECT_LT(box_offers * 10, plain_offers * 9) << box_offers << " against " << plain_offers;
}

// The heap holds the k closest even when far photons arrive first.
TEST(PhotonKdTree, HeapKeepsTheClosest) {
  KnnHeap h;
  h.capacity = 3;
  for (uint32_t i = 0; i < 10; ++i) {
    const float d2 = float(10 - i);
    if (!h.full() || d2 < h.top()) h.push(d2, i);
  }
  const auto v = sorted(h);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0].second, 9u);
  EXPECT_EQ(v[1].second, 8u);
  EXPECT_EQ(v[2].second, 7u);
}

// Every inner node's median photon splits its range on its axis: nothing before it is greater,
// nothing after it smaller. Photons on a coarse lattice share coordinates by the thousand (as
// photons on a level's axis-aligned walls do), which a median search must not stumble on.
void expect_nodes_split_at_their_median(const PhotonKdTreeView& t, uint32_t from, uint32_t to) {
  if (kd_is_leaf(from, to, t.leaf_size)) return;
  const uint32_t mid = kd_middle(from, to);
  const int a = t.axis[mid];
  const float split = t.position[mid][a];
  for (uint32_t i = from; i < mid; ++i) ASSERT_LE(t.position[i][a], split) << i;
  for (uint32_t i = mid + 1; i < to; ++i) ASSERT_GE(t.position[i][a], split) << i;
  expect_nodes_split_at_their_median(t, from, mid);
  expect_nodes_split_at_their_median(t, mid + 1, to);
}

TEST(PhotonKdTree, EveryNodeSplitsAtItsMedian) {
  Pcg32 rng(3);
  MapPhotons lattice;
  for (int i = 0; i < 50000; ++i) {
    lattice.position.push_back(vec3(float(rng.next_u32() % 5), float(rng.next_u32() % 3),
                                    i % 7 ? 0.0f : rng.next_float()));
    lattice.flux.push_back(vec3(1.0f));
    lattice.normal.push_back(vec3(0, 1, 0));
  }
  for (const MapPhotons& photons : {lattice, random_photons(30000, 4)})
    for (const uint32_t leaf : {1u, 8u}) {
      PhotonKdTree tree;
      tree.build(photons, leaf);
      const PhotonKdTreeView view = tree.view();
      ASSERT_EQ(view.count, photons.size());
      expect_nodes_split_at_their_median(view, 0, view.count);
      // The tree holds each photon once, with its own flux and normal.
      double flux = 0.0, expected = 0.0;
      for (uint32_t i = 0; i < view.count; ++i) flux += double(view.flux[i].x);
      for (const vec3& f : photons.flux) expected += double(f.x);
      EXPECT_NEAR(flux, expected, 1e-6 * expected);
    }
}

TEST(PhotonKdTree, EmptyAndTinyMaps) {
  PhotonKdTree tree;
  tree.build(MapPhotons{}, 8);
  KnnHeap h;
  h.capacity = 5;
  const auto all = [](uint32_t) { return true; };
  knn_search(tree.view(), vec3(0.0f), 1.0f, all, h);
  EXPECT_EQ(h.size, 0);
  MapPhotons one;
  one.position = {vec3(0.1f, 0, 0)};
  one.flux = {vec3(1.0f)};
  one.normal = {vec3(0, 1, 0)};
  tree.build(one, 1);
  knn_search(tree.view(), vec3(0.0f), 1.0f, all, h);
  ASSERT_EQ(h.size, 1);
  EXPECT_FLOAT_EQ(h.dist2[0], 0.01f);
}

}  // namespace
}  // namespace bounce
