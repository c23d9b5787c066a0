#include "bounce/techniques/vertex/vertex_photons.h"

#include <algorithm>
#include <cmath>

#include "bounce/core/parallel.h"
#include "bounce/core/qmc.h"
#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/techniques/vertex/point_sets.h"

namespace bounce {

namespace {

enum SetKind { kSphere = 0, kCap = 1, kCosine = 2 };
constexpr uint32_t kPathsPerChunk = 16;

// The seed's random emission (Fig 3.5): rejection sampling in the cube, kept per point so that
// the set is as frame-coherent as the spiral.
vec3 rejection_sphere(TeaRng& rng) {
  for (;;) {
    const vec2 a = rng.next2(), b = rng.next2();
    const vec3 d(2.0f * a.x - 1.0f, 2.0f * a.y - 1.0f, 2.0f * b.x - 1.0f);
    const float len2 = glm::dot(d, d);
    if (len2 <= 1.0f && len2 > 1e-6f) return d / std::sqrt(len2);
  }
}

}  // namespace

std::vector<uint32_t> VertexPhotonTracer::paths_per_emitter(const std::vector<float>& pmf,
                                                            uint32_t photons) {
  std::vector<uint32_t> count(pmf.size(), 0);
  for (size_t l = 0; l < pmf.size(); ++l)
    if (pmf[l] > 0.0f)
      count[l] = std::max(1u, uint32_t(std::lround(double(pmf[l]) * double(photons))));
  return count;
}

const std::vector<vec3>& VertexPhotonTracer::point_set(int kind, uint32_t n, float z_lo,
                                                       bool saff_kuijlaars, uint32_t seed) {
  if (sets_.size() > 256) sets_.clear();  // a moving spot light's cone, many light counts
  auto& set = sets_[{kind, n, z_lo, saff_kuijlaars, seed}];
  if (!set.empty() || n == 0) return set;
  if (saff_kuijlaars) {
    set = kind == kCosine ? bounce::saff_kuijlaars_cosine(n)
                          : bounce::saff_kuijlaars(n, kind == kCap ? z_lo : -1.0f, 1.0f);
    return set;
  }
  set.resize(n);
  for (uint32_t k = 0; k < n; ++k) {
    TeaRng rng = TeaRng::for_path(k, seed ^ 0x68e31da4u);
    if (kind == kSphere)
      set[k] = rejection_sphere(rng);
    else if (kind == kCap)
      set[k] = sample_uniform_cone(rng.next2(), z_lo);
    else
      set[k] = sample_cosine_hemisphere(rng.next2());
  }
  return set;
}

VertexPhotonStats VertexPhotonTracer::trace(const Scene& scene, const SceneView& view,
                                            const Tracer& tracer,
                                            const VertexPhotonSettings& settings, MapPhotons& out,
                                            MapPhotons* moving_out) {
  VertexPhotonStats stats;
  if (moving_out) moving_out->clear();
  const PhotonEmitters emitters = PhotonEmitters::from(scene);
  // Where every path of this slot starts.
  const std::vector<uint32_t> counts = paths_per_emitter(emitters.picker.pmf, settings.photons);
  stats.emission_changed = counts != last_counts_;
  last_counts_ = counts;
  stats.reused = settings.reuse_still && moving_out && !stats.emission_changed;
  if (!stats.reused) out.clear();
  if (emitters.empty() || settings.photons == 0) return stats;
  const uint32_t frames = std::max(settings.frames, 1u);
  const uint32_t slot = settings.slot % frames;
  const uint32_t splits = std::max(settings.splits, 1u);

  const std::tuple<uint32_t, bool, uint32_t> bounce_key{splits, settings.stratified, settings.seed};
  if (bounce_dirs_.empty() || bounce_key != bounce_key_) {
    bounce_dirs_ = bounce_direction_sets(kBounceSets, splits, settings.stratified, settings.seed);
    bounce_key_ = bounce_key;
  }
  // A fresh set (at rest): the whole emission turned about its axes and the area points shifted.
  const uint32_t variant_hash =
      settings.variant == 0 ? 0u : hash_u32(settings.variant * 0x27d4eb2du);
  const float azimuth = settings.variant == 0 ? 0.0f : kTwoPi * bits_to_unit_float(variant_hash);
  const vec2 shift = settings.variant == 0 ? vec2(0.0f)
                                           : vec2(bits_to_unit_float(hash_u32(variant_hash ^ 1u)),
                                                  bits_to_unit_float(hash_u32(variant_hash ^ 2u)));

  const auto moves = [&](uint32_t emitter) {
    return moving_out && emitter < settings.moving.size() && settings.moving[emitter] != 0;
  };
  starts_.clear();
  path_ids_.clear();
  uint32_t first_id = 0;
  for (uint32_t l = 0; l < counts.size(); ++l) {
    const uint32_t c = counts[l];
    if (c == 0) continue;
    const uint32_t n = c * frames;  // the emitter's whole set over the ring
    if (stats.reused && !moves(l)) {
      first_id += n;  // (the path ids of the emitters after it stay as they were)
      continue;
    }
    int kind = kCosine;
    float z_lo = 0.0f;
    vec3 power(0.0f);
    if (l < emitters.picker.light_count) {
      const Light& light = scene.lights[l];
      power = light.power(emitters.scene_radius);
      if (light.type == LightType::kPoint) kind = kSphere;
      if (light.type == LightType::kSpot) kind = kCap, z_lo = light.cos_outer;
    } else {
      power = scene.area_lights[l - emitters.picker.light_count].power();
    }
    const std::vector<vec3>& set = point_set(kind, n, z_lo, settings.saff_kuijlaars, settings.seed);
    for (uint32_t j = 0; j < c; ++j) {
      const uint32_t k = j * frames + slot;
      VertexPathStart s;
      s.emitter = l;
      // Points on area lights come from a Hammersley set in k; the direction takes the spiral
      // point of a permuted index, so that place and direction are not correlated.
      s.local_direction = kind == kSphere || kind == kCap
                              ? set[k]
                              : set[uint32_t((uint64_t(k) * 2654435761ull) % n)];
      s.u = rotate_unit(hammersley(k, n) + vec2(0.5f / float(n), 0.0f), shift);
      s.azimuth = azimuth;
      s.flux = power / float(c);
      starts_.push_back(s);
      path_ids_.push_back(first_id + k);
    }
    first_id += n;
  }

  VertexTraceView v;
  v.scene = view;
  v.trace = tracer.view();
  v.bounce_directions = bounce_dirs_.data();
  v.splits = splits;
  v.recursion_depth = std::clamp(settings.recursion_depth, 0, kMaxRecursionDepth);
  v.roulette = settings.roulette;
  v.store_direct = settings.store_direct;
  v.snowball = std::max(settings.snowball, 1);
  v.snowball_radius = settings.snowball_radius;
  v.stream = hash_u32(settings.seed ^ variant_hash);
  v.every_triangle = settings.every_triangle;
  const PhotonEmitterView emitter_view = emitters.view();

  // Each chunk of paths collects its photons in path order; the chunks are joined in order.
  const size_t paths = starts_.size();
  const size_t chunk_count = (paths + kPathsPerChunk - 1) / kPathsPerChunk;
  if (chunks_.size() < chunk_count) chunks_.resize(chunk_count);
  if (moving_chunks_.size() < chunk_count) moving_chunks_.resize(chunk_count);
  std::vector<uint64_t> rays(chunk_count, 0);
  parallel_for(
      chunk_count,
      [&](size_t c) {
        chunks_[c].clear();
        moving_chunks_[c].clear();
        const size_t end = std::min(paths, (c + 1) * kPathsPerChunk);
        for (size_t i = c * kPathsPerChunk; i < end; ++i) {
          MapPhotons& chunk = moves(starts_[i].emitter) ? moving_chunks_[c] : chunks_[c];
          auto deposit = [&](vec3 position, vec3 flux, vec3 normal) {
            chunk.position.push_back(position);
            chunk.flux.push_back(flux);
            chunk.normal.push_back(normal);
          };
          const EmittedPhoton e = emit_vertex_photon(view, emitter_view, starts_[i]);
          rays[c] += trace_vertex_path(v, e, path_ids_[i], deposit);
        }
      },
      1);
  const auto join = [&](const std::vector<MapPhotons>& chunks, MapPhotons& to) {
    size_t total = 0;
    for (size_t c = 0; c < chunk_count; ++c) total += chunks[c].size();
    to.reserve(to.size() + total);
    for (size_t c = 0; c < chunk_count; ++c) to.append(chunks[c]);
    return total;
  };
  size_t total = join(chunks_, out);
  if (moving_out) total += join(moving_chunks_, *moving_out);
  stats.paths = paths;
  stats.stored = total;
  for (uint64_t r : rays) stats.rays += r;
  return stats;
}

}  // namespace bounce
