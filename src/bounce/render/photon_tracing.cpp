#include "bounce/render/photon_tracing.h"

#include <array>

#include "bounce/core/parallel.h"
#include "bounce/core/parallel_primitives.h"
#include "bounce/scene/scene_data.h"

namespace bounce {

namespace {

constexpr uint32_t kPathsPerChunk = 256;

}  // namespace

PhotonPass photon_pass(const PhotonTraceSettings& settings) {
  PhotonPass pass;
  if (settings.paths == 0 || settings.max_bounces == 0) return pass;
  pass.paths = settings.paths;
  pass.roulette = settings.max_bounces < 0;
  pass.max_depth = pass.roulette ? kMaxPhotonDepth : settings.max_bounces;
  pass.stream = hash_u32(settings.seed * 0x9E3779B9u ^ hash_u32(settings.pass));
  pass.rotation = settings.pass == 0
                      ? vec2(0.0f)
                      : vec2(bits_to_unit_float(hash_u32(pass.stream)),
                             bits_to_unit_float(hash_u32(pass.stream ^ 0x5bd1e995u)));
  return pass;
}

PhotonTraceStats PhotonTracer::trace(const Scene& scene, const Tracer& tracer,
                                     const PhotonTraceSettings& settings, PhotonBuffer& out) {
  const SceneData data = SceneData::from(scene);
  return trace(scene, data.view(), tracer, settings, out);
}

PhotonTraceStats PhotonTracer::trace(const Scene& scene, const SceneView& view,
                                     const Tracer& tracer, const PhotonTraceSettings& settings,
                                     PhotonBuffer& out) {
  PhotonTraceStats stats;
  out.clear();
  const PhotonEmitters emitters = PhotonEmitters::from(scene);
  const PhotonPass pass = photon_pass(settings);
  if (emitters.empty() || pass.paths == 0) return stats;
  stats.paths = pass.paths;
  stats.emitted_power = emitters.total_power;
  const PhotonEmitterView emitter_view = emitters.view();

  // Count: every chunk of paths is traced a bounce at a time, each bounce's rays one stream; its
  // photons wait in the chunk, and each path's count goes to first_.
  const size_t chunk_count = (pass.paths + kPathsPerChunk - 1) / kPathsPerChunk;
  if (chunks_.size() < chunk_count) chunks_.resize(chunk_count);
  first_.assign(pass.paths, 0);
  std::vector<uint64_t> rays(chunk_count, 0);
  parallel_for(
      chunk_count,
      [&](size_t c) {
        Chunk& chunk = chunks_[c];
        chunk.photons.clear();
        chunk.path.clear();
        chunk.rank.clear();
        const uint32_t begin = uint32_t(c * kPathsPerChunk);
        const uint32_t end = std::min(pass.paths, begin + kPathsPerChunk);
        std::array<PhotonPath, kPathsPerChunk> paths;
        std::array<uint32_t, kPathsPerChunk> index;
        std::array<Ray, kPathsPerChunk> segment;
        std::array<Hit, kPathsPerChunk> hits;
        size_t active = 0;
        for (uint32_t i = begin; i < end; ++i) {
          paths[active] = start_photon_path(view, emitter_view, pass, i);
          index[active++] = i;
        }
        for (int depth = 0; active > 0; ++depth) {
          for (size_t k = 0; k < active; ++k) segment[k] = paths[k].ray;
          tracer.intersect(std::span<const Ray>(segment.data(), active),
                           std::span<Hit>(hits.data(), active), false);
          rays[c] += active;
          size_t next = 0;
          for (size_t k = 0; k < active; ++k) {
            PhotonDeposit deposit;
            bool stored;
            const bool goes_on =
                photon_bounce(view, pass, paths[k], hits[k], depth, deposit, stored);
            if (stored) {
              chunk.photons.push_back(deposit);
              chunk.path.push_back(index[k]);
              chunk.rank.push_back(first_[index[k]]++);
            }
            if (goes_on) {
              paths[next] = paths[k];
              index[next++] = index[k];
            }
          }
          active = next;
        }
      },
      1);

  // Scan: each path's first slot. Write: every photon to its path's slots, in bounce order.
  const uint32_t total = exclusive_scan(first_.data(), first_.data(), first_.size());
  out.resize(total);
  const PhotonView slots = out.view();
  parallel_for(
      chunk_count,
      [&](size_t c) {
        const Chunk& chunk = chunks_[c];
        for (size_t k = 0; k < chunk.photons.size(); ++k)
          store_photon(slots, first_[chunk.path[k]] + chunk.rank[k], chunk.photons[k]);
      },
      1);
  out.unpack_directions();
  stats.stored = total;
  for (uint64_t r : rays) stats.rays += r;
  return stats;
}

}  // namespace bounce
