// How a technique's indirect image relates to the frames before it: what the Renderer averages at
// rest and how long a history the denoiser keeps of it (denoise_plan.h's temporal_settings).
#pragma once

namespace bounce {

enum class IndirectHistory {
  kPerFrame,     // a fresh estimate every frame: the Renderer averages it at rest
  kAccumulated,  // already the technique's own running average at rest: not averaged again
  // A fresh estimate every frame from the technique's own store of its last frames (vertex's ring
  // of photon frames): averaged at rest as kPerFrame, but while the world changes the denoiser
  // keeps no history of it. The ring already carries the change in over its frames, and a history
  // clipped to each frame's neighbourhood brought the frames no closer to the references, at the
  // cost of the clip (docs/benchmarks.md, stop 55).
  kRing,
};

}  // namespace bounce
