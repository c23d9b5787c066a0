// The G-buffer in GPU memory: the arrays of render/gbuffer.h as device buffers, with the same
// views, so the per-pixel kernels that fill and read it are the CPU's.
#pragma once

#include "bounce/gpu/device_buffer.h"
#include "bounce/render/gbuffer_view.h"

namespace bounce {

struct DeviceGBuffer {
  int width = 0, height = 0;
  DeviceBuffer<vec3> position, normal, geometric_normal, albedo, f0, emission;
  DeviceBuffer<float> roughness, depth;
  DeviceBuffer<uint32_t> primitive, mesh;
  DeviceBuffer<vec2> barycentric, motion;

  void resize(int w, int h) {
    width = w;
    height = h;
    const size_t n = size_t(w) * size_t(h);
    for (auto* b : {&position, &normal, &geometric_normal, &albedo, &f0, &emission}) b->resize(n);
    roughness.resize(n);
    depth.resize(n);
    primitive.resize(n);
    mesh.resize(n);
    barycentric.resize(n);
    motion.resize(n);
  }
  GBufferView view() {
    return {position.data(),
            normal.data(),
            geometric_normal.data(),
            albedo.data(),
            roughness.data(),
            f0.data(),
            emission.data(),
            depth.data(),
            primitive.data(),
            mesh.data(),
            barycentric.data(),
            motion.data(),
            width,
            height};
  }
};

}  // namespace bounce
