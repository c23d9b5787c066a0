#include "bounce/render/photon_tracing.h"

#include <array>

#include "bounce/core/octahedral.h"
#include "bounce/core/parallel.h"
#include "bounce/core/qmc.h"
#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/render/photon_emission.h"
#include "bounce/render/surface.h"

namespace bounce {

namespace {

constexpr uint32_t kPathsPerChunk = 256;

struct PathTracePass {
  const Scene& scene;
  const Tracer& tracer;
  const PhotonEmitters& emitters;
  PhotonTraceSettings settings;
  vec2 rotation;    // Cranley-Patterson shift of the Hammersley set for this pass
  uint32_t stream;  // TEA stream for this pass

  struct PathState {
    Ray ray;
    vec3 flux;
    TeaRng rng;
  };

  // Traces paths [begin, end) a bounce at a time, each bounce's rays as one stream; appends
  // their photons to `out` (bounce by bounce, path order within a bounce). Returns rays traced.
  uint64_t trace_chunk(uint32_t begin, uint32_t end, PhotonBuffer& out) const {
    std::array<PathState, kPathsPerChunk> paths;
    std::array<Ray, kPathsPerChunk> rays;
    std::array<Hit, kPathsPerChunk> hits;
    size_t active = 0;
    for (uint32_t i = begin; i < end; ++i) {
      TeaRng rng = TeaRng::for_path(i, stream);
      const vec2 u = rotate_unit(hammersley(i, settings.paths), rotation);
      const EmittedPhoton e = emit_photon(scene, emitters, u, rng.next2(), settings.paths);
      paths[active++] = {Ray{e.origin, 0.0f, e.direction}, e.flux, rng};
    }
    const bool roulette = settings.max_bounces < 0;
    const int max_depth = roulette ? kMaxPhotonDepth : settings.max_bounces;
    uint64_t traced = 0;
    for (int depth = 0; active > 0; ++depth) {
      for (size_t k = 0; k < active; ++k) rays[k] = paths[k].ray;
      tracer.intersect(std::span<const Ray>(rays.data(), active),
                       std::span<Hit>(hits.data(), active), false);
      traced += active;
      size_t next = 0;
      for (size_t k = 0; k < active; ++k)
        if (bounce(paths[k], hits[k], depth, max_depth, roulette, out)) paths[next++] = paths[k];
      active = next;
    }
    return traced;
  }

  // Deposits the photon at a hit (after the first) and scatters the path; false when it ends.
  bool bounce(PathState& path, const Hit& hit, int depth, int max_depth, bool roulette,
              PhotonBuffer& out) const {
    if (!hit.valid()) return false;
    const SurfaceHit s = surface_at(scene, hit, path.ray.direction);
    if (depth >= 1) {
      out.position.push_back(s.position);
      out.flux.push_back(path.flux);
      out.incident.push_back(oct_pack(path.ray.direction));
      out.normal.push_back(oct_pack(s.normal));
    }
    if (depth >= max_depth) return false;
    // Diffuse bounce, cosine-weighted: the Lambert BRDF times cosine over the pdf is the albedo.
    const vec2 r = path.rng.next2();
    if (roulette) {
      const float survive = glm::min(1.0f, max_component(s.albedo));
      if (!(r.x < survive)) return false;
      path.flux *= s.albedo / survive;
    } else {
      path.flux *= s.albedo;
      if (!(max_component(path.flux) > 0.0f)) return false;
    }
    const vec3 dir =
        Basis::from_normal(s.normal).to_world(sample_cosine_hemisphere(path.rng.next2()));
    if (glm::dot(dir, s.geometric_normal) <= 0.0f) return false;  // shading normal points inside
    path.ray = Ray{offset_origin(s.position, s.geometric_normal), 0.0f, dir};
    return true;
  }
};

}  // namespace

PhotonTraceStats PhotonTracer::trace(const Scene& scene, const Tracer& tracer,
                                     const PhotonTraceSettings& settings, PhotonBuffer& out) {
  PhotonTraceStats stats;
  out.clear();
  const PhotonEmitters emitters = PhotonEmitters::from(scene);
  if (emitters.empty() || settings.paths == 0 || settings.max_bounces == 0) return stats;
  stats.paths = settings.paths;
  stats.emitted_power = emitters.total_power;

  const uint32_t stream = hash_u32(settings.seed * 0x9E3779B9u ^ hash_u32(settings.pass));
  const vec2 rotation = settings.pass == 0
                            ? vec2(0.0f)
                            : vec2(bits_to_unit_float(hash_u32(stream)),
                                   bits_to_unit_float(hash_u32(stream ^ 0x5bd1e995u)));
  const PathTracePass pass{scene, tracer, emitters, settings, rotation, stream};

  // Each chunk of paths fills its own buffer; buffers are joined in chunk order, so the result
  // does not depend on which thread traced which chunk.
  const size_t chunk_count = (settings.paths + kPathsPerChunk - 1) / kPathsPerChunk;
  if (chunks_.size() < chunk_count) chunks_.resize(chunk_count);
  std::vector<uint64_t> rays(chunk_count, 0);
  parallel_for(
      chunk_count,
      [&](size_t c) {
        PhotonBuffer& chunk = chunks_[c];
        chunk.clear();
        const uint32_t begin = uint32_t(c * kPathsPerChunk);
        const uint32_t end = std::min(settings.paths, begin + kPathsPerChunk);
        rays[c] = pass.trace_chunk(begin, end, chunk);
      },
      1);

  size_t total = 0;
  for (size_t c = 0; c < chunk_count; ++c) total += chunks_[c].size();
  out.resize(total);
  std::vector<size_t> offsets(chunk_count, 0);
  for (size_t c = 1; c < chunk_count; ++c) offsets[c] = offsets[c - 1] + chunks_[c - 1].size();
  parallel_for(
      chunk_count,
      [&](size_t c) {
        const PhotonBuffer& chunk = chunks_[c];
        std::copy(chunk.position.begin(), chunk.position.end(), out.position.begin() + offsets[c]);
        std::copy(chunk.flux.begin(), chunk.flux.end(), out.flux.begin() + offsets[c]);
        std::copy(chunk.incident.begin(), chunk.incident.end(), out.incident.begin() + offsets[c]);
        std::copy(chunk.normal.begin(), chunk.normal.end(), out.normal.begin() + offsets[c]);
      },
      1);
  out.unpack_directions();
  stats.stored = total;
  for (uint64_t r : rays) stats.rays += r;
  return stats;
}

}  // namespace bounce
