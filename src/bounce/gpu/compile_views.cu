// nvcc check of the buffer views: image, G-buffer and photons, read and written by a kernel.
#include "bounce/core/image_view.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/render/photon_view.h"

namespace bounce {

__global__ void check_views(ConstGBufferView g, ConstPhotonView photons, ImageView out,
                            PhotonView written) {
  const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= out.width || y >= out.height) return;
  const size_t i = g.index(x, y);
  vec3 value = g.hit(i) ? g.albedo[i] * g.normal[i] + g.emission[i] : vec3(g.depth[i]);
  if (i < photons.size()) {
    value += photons.flux[i] + photons.position[i];
    if (photons.clearance) value += vec3(photons.clearance_of(i)[0]);
    written.flux[i] = value;
  }
  out.at(x, y) = value;
}

}  // namespace bounce
