// ImageView: an image's pixels as a pointer and a size, for kernels (Image::view()).
#pragma once

#include <cstddef>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

template <bool kConst>
struct ImageViewT {
  maybe_const_t<vec3, kConst>* pixels = nullptr;  // row-major from the top row
  int width = 0;
  int height = 0;

  // A writable view reads as a read-only one.
  template <bool kTo>
  requires(kTo && !kConst) BOUNCE_HD operator ImageViewT<kTo>() const {
    return {pixels, width, height};
  }

  BOUNCE_HD size_t size() const { return size_t(width) * size_t(height); }
  BOUNCE_HD maybe_const_t<vec3, kConst>& at(int x, int y) const {
    return pixels[size_t(y) * size_t(width) + size_t(x)];
  }
};
using ImageView = ImageViewT<false>;
using ConstImageView = ImageViewT<true>;
static_assert(std::is_trivially_copyable_v<ImageView>);

}  // namespace bounce
