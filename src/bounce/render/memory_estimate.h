// What a technique keeps in memory beyond the per-pixel buffers, estimated from its parameters
// before any frame, so that a setting that cannot fit (ten million photon paths kept for 64 passes,
// a photon split into 1024^4) is refused at once with a clear message instead of running out of
// memory minutes later (apps/bounce/input_checks.h checks it against the cap).
#pragma once

#include <cstdint>

#include "bounce/scene/scene.h"

namespace bounce {

// Bytes per photon of a PhotonBuffer (photons.h): position and flux, packed incident direction and
// normal, the two clearances, and the unpacked directions the gathers read.
inline constexpr uint64_t kPhotonBufferBytes = 64;

// Photons a path from the lights deposits, on average. A path deposits at every hit after its
// first (photon_path.h). Russian roulette (max_bounces < 0) keeps it alive at a hit with
// probability max_component(albedo), so with the scene's largest such albedo a it deposits at
// most a + a^2 + ... = a / (1 - a), capped at kMaxPhotonDepth; max_bounces = B deposits at most B.
double expected_photon_deposits(const Scene& scene, int max_bounces);

// The product of non-negative factors as bytes, saturating at UINT64_MAX instead of wrapping.
uint64_t saturating_bytes(double product);

}  // namespace bounce
