// parallel_for: the one way bounce spreads work over cores. Kernels are plain callables over an
// index (1D) or a pixel (2D), so the same bodies can later be launched by a CUDA backend. The
// parallel primitives built on it (scan, reduce, sort) are in parallel_primitives.h.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

namespace bounce {

// Calls body(i) for every i in [0, n). Work is chunked by `grain` indices.
template <typename Body>
void parallel_for(size_t n, Body&& body, size_t grain = 256) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i != r.end(); ++i) body(i);
                    });
}

// Calls body(x, y) for every pixel of a width x height grid: the 2D launch of a per-pixel kernel.
// Work goes out in 8 x 8 tiles, so neighbouring pixels run on one core (locality).
template <typename Body>
void parallel_for_2d(int width, int height, Body&& body) {
  constexpr int kTile = 8;
  const int tiles_x = (width + kTile - 1) / kTile;
  const int tiles_y = (height + kTile - 1) / kTile;
  tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y, 1),
                    [&](const tbb::blocked_range<int>& r) {
                      for (int t = r.begin(); t != r.end(); ++t) {
                        const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
                        const int x1 = std::min(x0 + kTile, width);
                        const int y1 = std::min(y0 + kTile, height);
                        for (int y = y0; y < y1; ++y)
                          for (int x = x0; x < x1; ++x) body(x, y);
                      }
                    });
}

// Calls body(x0, y0, x1, y1) for every tile of a width x height image (tile_width x tile_height
// pixels), for host code that batches a tile's work (rays handed to the Tracer as one stream).
template <typename Body>
void parallel_for_tiles(int width, int height, int tile_width, int tile_height, Body&& body) {
  const int tiles_x = (width + tile_width - 1) / tile_width;
  const int tiles_y = (height + tile_height - 1) / tile_height;
  tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y, 1),
                    [&](const tbb::blocked_range<int>& r) {
                      for (int t = r.begin(); t != r.end(); ++t) {
                        const int x0 = (t % tiles_x) * tile_width;
                        const int y0 = (t / tiles_x) * tile_height;
                        body(x0, y0, std::min(x0 + tile_width, width),
                             std::min(y0 + tile_height, height));
                      }
                    });
}

// Square tiles of tile x tile pixels.
template <typename Body>
void parallel_for_tiles(int width, int height, int tile, Body&& body) {
  parallel_for_tiles(width, height, tile, tile, body);
}

// Limits the worker threads while alive (0 = no limit); used by --threads and determinism tests.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads) {
    if (threads > 0)
      control_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                       size_t(threads));
  }

 private:
  std::unique_ptr<tbb::global_control> control_;
};

}  // namespace bounce
