// DevicePipeline: the frame's stages run on another device (the CUDA backend, src/bounce/gpu).
// The Renderer keeps everything that decides what a frame is (what changed, the camera's rays,
// the jitter, the history state, the scene's flattened arrays and light tables) and hands the
// stages to the pipeline, which writes the frame's colour, tone-mapped image, counters and stage
// times. The interface lives here, below the backend, so the Renderer needs no CUDA to build.
#pragma once

#include <cstdint>
#include <string>

#include "bounce/core/math.h"
#include "bounce/render/light_change_region.h"
#include "bounce/render/technique.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_change.h"
#include "bounce/scene/scene_data.h"

namespace bounce {

struct Frame;
struct FrameSettings;
struct LightPicker;
class Denoiser;
enum class HistoryState;

struct DeviceFrameInput {
  const Scene& scene;
  const SceneData& scene_data;  // current: the Renderer refreshed it for this frame's change
  const LightPicker& lights;
  Technique& technique;
  const FrameSettings& settings;
  const SceneChange& change;
  const CameraRays& rays;
  const CameraRays& previous_rays;  // for motion; equal to rays on the first frame
  vec2 subpixel;                    // primary-ray position in the pixel
  bool rest;                        // accumulating and nothing changed
  HistoryState history;             // for the denoiser
  LightChangeRegion direct_region;  // where it clips direct light's history (DenoiseFrame)
  const Denoiser& denoiser;         // its settings
  uint32_t frame_index;
};

class DevicePipeline {
 public:
  virtual ~DevicePipeline() = default;
  virtual std::string name() const = 0;
  // Runs the stages from "prepare" to "tonemap" and fills frame.color, frame.ldr, the counters
  // and frame.times (the G-buffer and the direct and indirect images stay on the device).
  virtual void render(const DeviceFrameInput& input, Frame& frame) = 0;
};

}  // namespace bounce
