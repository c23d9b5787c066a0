// Technique "lhb": indirect light gathered through layered hit buffers after seed 001
// (001_f8684133514c5eaa.txt; notes/seed-001.md), on the CPU. See README.md beside this file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bounce/render/light_picker.h"
#include "bounce/render/lowres_estimate.h"
#include "bounce/render/technique.h"
#include "bounce/techniques/lhb/direction_sets.h"
#include "bounce/techniques/lhb/layered_hit_buffers.h"
#include "bounce/techniques/lhb/lhb_kernels.h"

namespace bounce {

struct LhbTechniqueSettings {
  int direction_kind = int(DirectionKind::kIcosahedron);  // DirectionKind
  int directions = 320;      // count (the nearest a subdivided solid offers)
  int size = 128;            // N: texels per side of each buffer
  int layers = 16;           // L: elements per texel
  int instances = 8;         // moving meshes with buffers of their own (LhbSettings)
  int paths = 1;             // per pixel per frame
  int bounces = 2;           // indirect bounces
  float cone_radius = 1.5f;  // texels
  int interleave = 3;        // n x n interleaved sample sets (1: off)
  // Real-time frames go through the denoiser, whose edge-aware filter does what the seed's
  // discontinuity buffer and the re-estimated edge pixels did, so both are off, and the paths
  // start from one pixel per block of a size that follows the image (lhb_auto_lowres): at
  // 512x512, 6 x 6 pixels, where the first frame scores better MSSIM against the path reference
  // than with paths at every pixel, at a quarter of the frame time (docs/lhb.md, "Real-time
  // defaults"). Stills (still_defaults) take every pixel's paths and the filter.
  bool filter = false;  // the discontinuity buffer over the n x n window
  float filter_normal = 0.9f;
  float filter_distance = 0.05f;  // position gap / view depth
  int lowres = 0;                 // paths at 1/lowres of the width and height; 0: auto
  // Which pixels a low-resolution estimate re-estimates at full resolution: none (no normal
  // agreement is below -1, no gap beyond the scene's diagonal), and where a block's sample saw
  // no surface the neighbouring samples that did are blended instead of tracing the pixel's
  // own paths (at 512x512 on the Cornell box, 5,533 pixels a frame: 1.5 ms).
  EdgeSettings edges = blend_misses(EdgeSettings::none());
  int seed = 0;
};

// The block size `lowres` 0 picks for an image `width` pixels wide: about 85 blocks across
// (6 x 6 pixels at 512), at most 6 (the coarsest measured), and paths at every pixel on images
// too small for blocks to leave enough paths (below about 128 pixels).
int lhb_auto_lowres(int width);

class LhbTechnique final : public Technique {
 public:
  LhbTechnique();
  std::string name() const override { return "lhb"; }
  std::vector<TechniqueOption> options() const override;
  std::vector<std::string> still_defaults() const override;
  // Builds the direction set and the buffers when the scene or the buffer parameters change;
  // when meshes move, re-poses their instances and rebuilds only the moving slab; the light
  // picker on light, material or geometry changes.
  // The layered hit buffers (and their moving-mesh copy in animated scenes).
  uint64_t memory_estimate(const Scene& scene) const override;
  // Bytes of the buffers for `directions` directions of size x size texels and `layers` layers.
  static double hit_buffer_bytes(size_t directions, int size, int layers);
  void prepare(const PrepareContext& context) override;
  // Paths per pixel through the buffers, then the discontinuity filter.
  void indirect(const FrameContext& context, Image& out) override;

  LhbTechniqueSettings& settings() { return settings_; }
  const LhbTechniqueSettings& settings() const { return settings_; }
  const DirectionSet& direction_set() const { return directions_; }
  const LayeredHitBuffers& buffers() const { return buffers_; }
  // Pixels of the last frame estimated at full resolution as edges (0 at lowres 1).
  size_t edge_pixels() const { return edge_pixels_; }

 private:
  struct BuiltWith {
    int kind = -1, directions = 0, size = 0, layers = 0, instances = 0;
    bool operator==(const BuiltWith&) const = default;
  };

  LhbTechniqueSettings settings_;
  DirectionSet directions_;
  LayeredHitBuffers buffers_;
  BuiltWith built_;
  LightPicker lights_;
  std::vector<vec3> incoming_;  // per pixel, before the filter
  LowResBuffers low_;
  float diagonal_ = 1.0f;
  size_t edge_pixels_ = 0;
};

}  // namespace bounce
