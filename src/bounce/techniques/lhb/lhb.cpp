#include "bounce/techniques/lhb/lhb.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/timer.h"
#include "bounce/render/memory_estimate.h"

namespace bounce {

namespace {
constexpr double kMaxBufferBytes = 8.0 * double(1 << 30);  // one slab
}  // namespace

LhbTechnique::LhbTechnique() {
  LhbTechniqueSettings& s = settings_;
  params_.add_int("direction_set", &s.direction_kind, 0, kDirectionKindCount - 1,
                  "buffer directions: 0 icosahedron, 1 octahedron, 2 tetrahedron, 3 Halton, "
                  "4 UV grid");
  params_.add_int("directions", &s.directions, 1, 2048,
                  "number of buffer directions (solids: the nearest of base * 4^level)");
  params_.add_int("size", &s.size, 4, LhbSettings::kMaxSize, "N: texels per side of a buffer");
  params_.add_int("layers", &s.layers, 1, LhbSettings::kMaxLayers, "L: elements per texel");
  params_.add_int("instances", &s.instances, 0, LhbSettings::kMaxInstances,
                  "moving meshes (the largest, of 256 triangles or more) given buffers of their "
                  "own that follow their motion by a transform instead of being rasterized "
                  "again each frame; 0: all in the seed's moving slab");
  params_.add_int("paths", &s.paths, 1, 4096, "paths per pixel per frame");
  params_.add_int("bounces", &s.bounces, 0, 64, "indirect bounces");
  params_.add_float("cone_radius", &s.cone_radius, 0.0, 1000.0,
                    "cone approximation: disc jitter radius, texels");
  params_.add_int("interleave", &s.interleave, 1, 16, "n x n interleaved sample sets (1: off)");
  params_.add_bool("filter", &s.filter, "discontinuity filter over the n x n window");
  params_.add_float("filter_normal", &s.filter_normal, -1.0, 1.0,
                    "filter: least normal agreement of a neighbour");
  params_.add_float("filter_distance", &s.filter_distance, 0.0, 10.0,
                    "filter: largest position gap of a neighbour / view depth");
  params_.add_int("lowres", &s.lowres, 0, 16,
                  "paths at 1/lowres of the width and height (edges, if any, at full); 0: a "
                  "block size that follows the image's width");
  add_edge_params(params_, s.edges);
  params_.add_int("seed", &s.seed, 0, 1 << 30, "seed of the paths' random numbers");
}

std::vector<TechniqueOption> LhbTechnique::options() const {
  return {
      param_option("paths", "paths", "Paths per pixel per frame"),
      param_option("bounces", "bounces", "Indirect bounces (seed default 2)"),
      param_option("directions", "directions", "Number of buffer directions (seed default 320)"),
      param_option("lowres", "lowres", "Paths at 1/N of the width and height, edges at full"),
  };
}

int lhb_auto_lowres(int width) {
  constexpr float kBlocksAcross = 85.0f;
  constexpr int kCoarsest = 6;
  return std::clamp(int(std::lround(float(width) / kBlocksAcross)), 1, kCoarsest);
}

std::vector<std::string> LhbTechnique::still_defaults() const {
  // The seed's dynamic-scene setting (16 paths, 2 bounces) at every pixel, with its filter.
  return {"paths=16", "lowres=1", "filter=true"};
}

double LhbTechnique::hit_buffer_bytes(size_t directions, int size, int layers) {
  // Per texel: L elements and a count byte (LayeredHitBuffers' slabs).
  return double(directions) * double(size) * double(size) *
         (double(layers) * double(sizeof(LhbElement)) + 1.0);
}

uint64_t LhbTechnique::memory_estimate(const Scene& scene) const {
  const LhbTechniqueSettings& s = settings_;
  // The static buffers, and as many again for moving meshes when the scene animates.
  const double copies = scene.animation.empty() ? 1.0 : 2.0;
  return saturating_bytes(copies * hit_buffer_bytes(size_t(s.directions), s.size, s.layers));
}

void LhbTechnique::prepare(const PrepareContext& context) {
  const SceneChange& c = context.change;
  const LhbTechniqueSettings& s = settings_;
  const BuiltWith wanted{s.direction_kind, s.directions, s.size, s.layers, s.instances};
  diagonal_ = std::max(context.scene.bounds.diagonal(), 1e-6f);
  if (c.geometry() || c.lights || c.materials) lights_ = LightPicker::build(context.scene);
  if (wanted.kind != built_.kind || wanted.directions != built_.directions)
    directions_ = DirectionSet::make(DirectionKind(s.direction_kind), s.directions);
  if (c.everything || !(wanted == built_) || buffers_.direction_count() == 0) {
    // directions x N^2 texels x L elements of 8 bytes: refuse sizes that cannot be allocated
    // with a message that names them, instead of failing inside the allocator.
    const double bytes = hit_buffer_bytes(directions_.size(), s.size, s.layers);
    if (bytes > kMaxBufferBytes)
      fail(
          "lhb: {} directions x {}x{} texels x {} layers need {:.1f} GiB of hit buffers (at "
          "most {:.0f} GiB): lower directions, size or layers",
          directions_.size(), s.size, s.size, s.layers, bytes / double(1 << 30),
          kMaxBufferBytes / double(1 << 30));
    ScopedStage stage(context.times, "prepare/lhb build");
    LhbSettings ls;
    ls.size = s.size;
    ls.layers = s.layers;
    ls.dynamic_layers = s.layers;
    ls.max_instances = s.instances;
    buffers_.build(context.scene, directions_.directions(), ls);
    built_ = wanted;
  } else if (c.geometry()) {
    ScopedStage stage(context.times, "prepare/lhb update");
    buffers_.update(context.scene, c);
  }
}

void LhbTechnique::indirect(const FrameContext& context, Image& out) {
  const GBuffer& g = context.gbuffer;
  const ConstGBufferView view = g.view();
  if (settings_.bounces == 0) return;  // out is zeroed
  if (buffers_.direction_count() == 0) fail("lhb: indirect() before prepare()");

  LhbGatherSettings gs;
  gs.paths = settings_.paths;
  gs.bounces = settings_.bounces;
  gs.cone_radius = settings_.cone_radius;
  gs.interleave = settings_.interleave;
  gs.frame = context.frame_index;
  gs.seed = uint32_t(settings_.seed);
  const LhbScene ls{path_scene(context.scene_view, context.tracer, lights_), buffers_.view(),
                    directions_.view()};

  const int lowres = settings_.lowres > 0 ? settings_.lowres : lhb_auto_lowres(g.width);
  gs.interleave_step = lowres;
  incoming_.resize(g.size());
  const ImageView incoming_view{incoming_.data(), g.width, g.height};
  tbb::enumerable_thread_specific<PathCounters> counters;
  const auto paths = [&ls, &gs, view, &counters](int x, int y) {
    return lhb_pixel(ls, gs, view, x, y, counters.local());
  };
  // At lowres > 1 the paths start from one pixel per lowres^2 block, upsampled, and from every
  // pixel where normals or positions disagree (the code tiled shares, render/lowres_kernels.h).
  const EdgeTest edges = settings_.edges.test(diagonal_);
  {
    // estimate_at_low_res times its low-resolution stages; paths at every pixel are timed here.
    std::optional<ScopedStage> every_pixel;
    if (lowres <= 1) every_pixel.emplace(context.times, "indirect/gather");
    edge_pixels_ =
        estimate_at_low_res(view, lowres, edges, paths, low_, incoming_view, context.times);
  }
  for (const PathCounters& pc : counters) context.counters.rays += pc.rays;

  vec3* pixels = out.pixels().data();
  const vec3* incoming = incoming_.data();
  ScopedStage stage(context.times, "indirect/filter");
  if (settings_.edges.show && lowres > 1) {
    // The debug view: the upsampled incoming light as it is, edges in yellow.
    parallel_for(
        g.size(), [&](size_t i) { pixels[i] = incoming[i]; }, 4096);
    return;
  }
  const int n = settings_.filter ? settings_.interleave : 1;
  if (n <= 1) {
    // No filter (the real-time default): the window is the pixel itself, so the filter is the
    // albedo times the incoming light where there is a surface, a row loop the compiler
    // vectorises (the windowed body costs about 2 ms a frame at 512x512 for this).
    parallel_for(
        size_t(g.height),
        [&](size_t y) {
          const size_t row = y * size_t(g.width);
          lhb_albedo_times_incoming(view.albedo + row, view.primitive + row, incoming + row,
                                    pixels + row, g.width);
        },
        4);
    return;
  }
  const float normal_dot = settings_.filter_normal, distance = settings_.filter_distance;
  parallel_for_2d(g.width, g.height, [&](int x, int y) {
    pixels[view.index(x, y)] =
        lhb_discontinuity_pixel(view, incoming, x, y, n, normal_dot, distance);
  });
}

}  // namespace bounce
