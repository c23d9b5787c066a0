// What the GPU tests share: skip cleanly where no GPU can run them.
#pragma once

#include <gtest/gtest.h>

#include "bounce/gpu/cuda_device.h"

#define BOUNCE_REQUIRE_GPU()                                                       \
  do {                                                                             \
    if (!::bounce::cuda_device_info().available)                                   \
      GTEST_SKIP() << "needs a CUDA GPU: " << ::bounce::cuda_device_info().reason; \
  } while (0)
