#include "bounce/gpu/device_denoiser_check.h"

#include "bounce/gpu/device_denoiser.h"
#include "bounce/gpu/device_gbuffer.h"

namespace bounce {

struct DeviceDenoiserHost::Impl {
  DeviceGBuffer g;
  DeviceBuffer<vec3> direct, indirect;
  DeviceDenoiser denoiser;
};

DeviceDenoiserHost::DeviceDenoiserHost() : impl_(std::make_unique<Impl>()) {}
DeviceDenoiserHost::~DeviceDenoiserHost() = default;

void DeviceDenoiserHost::run(const DenoiseSettings& settings, const GBuffer& g, HistoryState state,
                             IndirectHistory indirect_history, Image& direct, Image* indirect,
                             const LightChangeRegion& direct_region) {
  const size_t n = g.size();
  if (direct.pixel_count() != n || (indirect && indirect->pixel_count() != n))
    gpu_fail("DeviceDenoiserHost: the images are not the G-buffer's size");
  Impl& d = *impl_;
  d.g.resize(g.width, g.height);
  d.g.position.upload(g.position);
  d.g.normal.upload(g.normal);
  d.g.geometric_normal.upload(g.geometric_normal);
  d.g.albedo.upload(g.albedo);
  d.g.f0.upload(g.f0);
  d.g.emission.upload(g.emission);
  d.g.roughness.upload(g.roughness);
  d.g.depth.upload(g.depth);
  d.g.primitive.upload(g.primitive);
  d.g.mesh.upload(g.mesh);
  d.g.barycentric.upload(g.barycentric);
  d.g.motion.upload(g.motion);
  d.direct.upload(direct.data(), n);
  if (indirect) d.indirect.upload(indirect->data(), n);
  const DeviceDenoiseFrame frame{d.g.view(), state, indirect_history, direct_region};
  d.denoiser.run(settings, frame, d.direct.data(), indirect ? d.indirect.data() : nullptr);
  d.direct.download(direct.data(), n);  // (a blocking copy: waits for the kernels)
  if (indirect) d.indirect.download(indirect->data(), n);
}

}  // namespace bounce
