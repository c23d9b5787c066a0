#include "bounce/techniques/tiled/tiled.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/render/photon_clearance.h"
#include "bounce/render/photon_gather.h"

namespace bounce {

TiledPhotonMapping::TiledPhotonMapping() {
  TiledSettings& s = settings_;
  params_.add_int("photons", &s.photons, 1, 10000000, "photon paths per frame");
  params_.add_float("radius", &s.radius, 0.0, 1e9, "gather radius (scene units; 0: radius_rel)");
  params_.add_float("radius_rel", &s.radius_rel, 1e-6, 1.0, "gather radius / scene diagonal");
  params_.add_int("bounces", &s.bounces, -1, kMaxPhotonDepth,
                  "photon bounces (-1: until Russian roulette ends the path)");
  params_.add_int("lowres", &s.lowres, 1, 16, "indirect at 1/lowres of the width and height");
  params_.add_int("tile", &s.tile, 1, 256, "screen tile size, pixels");
  params_.add_int("gather", &s.gather, 0, 1, "density estimation: 0 screen tiles, 1 hash grid");
  params_.add_float("slab", &s.slab, 0.0, 1.0, "tangent slab half-thickness / radius");
  params_.add_bool("leak_guard", &s.leak_guard, "clearance rays stop light through thin walls");
  params_.add_float("alpha", &s.alpha, 0.01, 1.0, "radius reduction of passes at rest");
  params_.add_float("edge_normal", &s.edge_normal, -1.0, 1.0, "edge test: normal agreement");
  params_.add_float("edge_distance", &s.edge_distance, 0.0, 1.0,
                    "edge test: position gap / scene diagonal");
  params_.add_bool("show_edges", &s.show_edges, "show re-estimated pixels in yellow");
  params_.add_int("seed", &s.seed, 0, 1 << 30, "photon sample seed");
}

std::vector<TechniqueOption> TiledPhotonMapping::options() const {
  return {
      param_option("photons", "photons",
                   "Photon paths per frame (render: 20000 per pass unless given)"),
      {"radius", "Gather radius: scene units (0.05) or percent of the scene diagonal (3%)",
       [](ParamSet& params, const std::string& text) {
         if (text.empty() || text.back() != '%') return params.set("radius", text);
         // Percent of the diagonal, as the relative radius; the absolute one is turned off.
         const std::string number = text.substr(0, text.size() - 1);
         char* end = nullptr;
         const double percent = std::strtod(number.c_str(), &end);
         if (number.empty() || *end != '\0') fail("--radius: '{}' is not a percentage", text);
         params.set("radius_rel", fmt::format("{}", percent / 100.0));
         params.set("radius", "0");
       }},
      param_option("bounces", "bounces",
                   "Photon bounces: -1 = until Russian roulette ends the path, 1 = the seed's"),
      param_option("lowres", "lowres", "Indirect light at 1/N of the width and height"),
      param_option("tile", "tile", "Screen tile size in pixels (tile gather)"),
      {"gather", "Density estimation: tiles or grid",
       [](ParamSet& params, const std::string& text) {
         if (text != "tiles" && text != "grid")
           fail("--gather: '{}' is neither 'tiles' nor 'grid'", text);
         params.set("gather", text == "tiles" ? "0" : "1");
       }},
  };
}

std::vector<std::string> TiledPhotonMapping::still_defaults() const {
  return {"photons=20000"};  // a still affords ten times the real-time frame's photons per pass
}

vec3 TiledPhotonMapping::estimate_at(const GBuffer& g, int x, int y, float radius) const {
  const size_t i = size_t(y) * g.width + x;
  if (!g.hit(i)) return vec3(0.0f);
  const vec3 p = g.position[i], n = g.normal[i];
  const GatherSettings gs{radius, slab_, settings_.leak_guard};
  vec3 sum(0.0f);
  const auto visit = [&](uint32_t k) {
    const float w = gather_weight(photons_, k, p, n, gs);
    if (w > 0.0f) sum += photons_.flux[k] * w;
  };
  if (settings_.gather == 0) {
    const size_t t = bins_.tile_of_pixel(x, y);
    for (const uint32_t* k = bins_.begin(t); k != bins_.end(t); ++k) visit(*k);
  } else {
    grid_.for_each_within(p, radius, visit);
  }
  return cone_filter_radiance(sum, g.albedo[i], radius);
}

void TiledPhotonMapping::estimate(const FrameContext& c, float radius, Image& out) {
  const GBuffer& g = c.gbuffer;
  const int f = settings_.lowres;
  if (f == 1) {
    parallel_for_tiles(g.width, g.height, 8, [&](int x0, int y0, int x1, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) out.at(x, y) = estimate_at(g, x, y, radius);
    });
    edge_pixels_ = 0;
    return;
  }
  // Low resolution: estimate at one full-resolution pixel near the centre of each f x f block.
  LowRes& low = low_;
  low.width = (g.width + f - 1) / f;
  low.height = (g.height + f - 1) / f;
  const size_t n = size_t(low.width) * low.height;
  low.radiance.resize(n);
  low.normal.resize(n);
  low.position.resize(n);
  low.valid.resize(n);
  {
    ScopedStage stage(c.times, "indirect/estimate low-res");
    parallel_for_tiles(low.width, low.height, 8, [&](int x0, int y0, int x1, int y1) {
      for (int ly = y0; ly < y1; ++ly)
        for (int lx = x0; lx < x1; ++lx) {
          const int x = std::min(lx * f + f / 2, g.width - 1);
          const int y = std::min(ly * f + f / 2, g.height - 1);
          const size_t i = size_t(y) * g.width + x, l = size_t(ly) * low.width + lx;
          low.valid[l] = g.hit(i);
          low.normal[l] = g.normal[i];
          low.position[l] = g.position[i];
          low.radiance[l] = estimate_at(g, x, y, radius);
        }
    });
  }
  // Bilinear upsampling; where the interpolated normal or position disagrees with the pixel's
  // own (an edge), estimate the pixel at full resolution.
  ScopedStage stage(c.times, "indirect/upsample + edges");
  const float max_gap = settings_.edge_distance * diagonal_;
  std::vector<uint32_t> edge_counts(size_t(g.height), 0);
  parallel_for(
      size_t(g.height),
      [&](size_t y) {
        const float gy = (float(y) + 0.5f) / float(f) - 0.5f;
        const int ly0 = glm::clamp(int(std::floor(gy)), 0, low.height - 1);
        const int ly1 = std::min(ly0 + 1, low.height - 1);
        const float fy = glm::clamp(gy - float(ly0), 0.0f, 1.0f);
        for (int x = 0; x < g.width; ++x) {
          const size_t i = y * size_t(g.width) + size_t(x);
          if (!g.hit(i)) {
            out.at(x, int(y)) = vec3(0.0f);
            continue;
          }
          const float gx = (float(x) + 0.5f) / float(f) - 0.5f;
          const int lx0 = glm::clamp(int(std::floor(gx)), 0, low.width - 1);
          const int lx1 = std::min(lx0 + 1, low.width - 1);
          const float fx = glm::clamp(gx - float(lx0), 0.0f, 1.0f);
          const size_t l[4] = {size_t(ly0) * low.width + lx0, size_t(ly0) * low.width + lx1,
                               size_t(ly1) * low.width + lx0, size_t(ly1) * low.width + lx1};
          const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
          bool edge = false;
          vec3 normal(0.0f), position(0.0f), radiance(0.0f);
          for (int k = 0; k < 4; ++k) {
            if (!low.valid[l[k]]) edge = edge || w[k] > 0.0f;
            normal += w[k] * low.normal[l[k]];
            position += w[k] * low.position[l[k]];
            radiance += w[k] * low.radiance[l[k]];
          }
          const float len = glm::length(normal);
          edge = edge || len <= 0.0f ||
                 glm::dot(g.normal[i], normal / len) < settings_.edge_normal ||
                 glm::length(g.position[i] - position) > max_gap;
          if (edge) {
            ++edge_counts[y];
            radiance =
                settings_.show_edges ? vec3(1.0f, 1.0f, 0.0f) : estimate_at(g, x, int(y), radius);
          }
          out.at(x, int(y)) = radiance;
        }
      },
      4);
  edge_pixels_ = 0;
  for (uint32_t e : edge_counts) edge_pixels_ += e;
}

void TiledPhotonMapping::indirect(const FrameContext& c, Image& out) {
  diagonal_ = std::max(c.scene.bounds.diagonal(), 1e-6f);
  const float base = settings_.radius > 0.0f ? settings_.radius : settings_.radius_rel * diagonal_;
  if (!c.continue_accumulation() || passes_ == 0 || accumulated_.width() != out.width() ||
      accumulated_.height() != out.height()) {
    passes_ = 0;
    radius2_ = base * base;
    accumulated_ = Image(out.width(), out.height());
  }
  const float radius = std::sqrt(radius2_);
  last_radius_ = radius;
  slab_ = settings_.slab * radius;

  {
    ScopedStage stage(c.times, "indirect/photon trace");
    PhotonTraceSettings ts;
    ts.paths = uint32_t(settings_.photons);
    ts.max_bounces = settings_.bounces;
    ts.seed = uint32_t(settings_.seed);
    ts.pass = passes_;
    const PhotonTraceStats stats = tracer_.trace(c.scene, c.tracer, ts, photons_);
    c.counters.photon_paths += stats.paths;
    c.counters.photons_stored += stats.stored;
    c.counters.rays += stats.rays;
  }
  if (settings_.leak_guard) {
    ScopedStage stage(c.times, "indirect/clearance");
    c.counters.rays += compute_photon_clearance(c.tracer, radius, photons_);
  } else {
    photons_.clearance.clear();
  }
  {
    ScopedStage stage(c.times, settings_.gather == 0 ? "indirect/tile bins" : "indirect/hash grid");
    if (settings_.gather == 0)
      bins_.build(c.gbuffer, c.camera, photons_, radius, settings_.tile);
    else
      grid_.build(photons_.position, radius);
  }
  if (pass_estimate_.width() != out.width() || pass_estimate_.height() != out.height())
    pass_estimate_ = Image(out.width(), out.height());
  estimate(c, radius, pass_estimate_);

  // Progressive photon mapping as the average of independent passes whose radius shrinks
  // (Knaus and Zwicker 2011): r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1).
  ++passes_;
  radius2_ *= (float(passes_ - 1) + settings_.alpha) / float(passes_);
  const float inv_passes = 1.0f / float(passes_);
  parallel_for(
      out.pixel_count(),
      [&](size_t i) {
        vec3& sum = accumulated_.pixels()[i];
        sum += pass_estimate_.pixels()[i];
        out.pixels()[i] = sum * inv_passes;
      },
      4096);
}

}  // namespace bounce
