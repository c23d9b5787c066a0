// The CPU Tracer on Embree 3: one triangle geometry per mesh (geometry id = mesh index), single
// rays through rtcIntersect1/rtcOccluded1 and coherent streams as 8-wide packets.
#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>

#include "bounce/core/error.h"
#include "bounce/core/timer.h"
#include "bounce/trace/tracer.h"

namespace bounce {

namespace {

RTCBuildQuality to_embree(BuildQuality q) {
  switch (q) {
    case BuildQuality::kLow:
      return RTC_BUILD_QUALITY_LOW;
    case BuildQuality::kMedium:
      return RTC_BUILD_QUALITY_MEDIUM;
    case BuildQuality::kHigh:
      return RTC_BUILD_QUALITY_HIGH;
  }
  return RTC_BUILD_QUALITY_MEDIUM;
}

RTCRay to_embree(const Ray& r) {
  RTCRay e;
  e.org_x = r.origin.x;
  e.org_y = r.origin.y;
  e.org_z = r.origin.z;
  e.tnear = r.tmin;
  e.dir_x = r.direction.x;
  e.dir_y = r.direction.y;
  e.dir_z = r.direction.z;
  e.time = 0.0f;
  e.tfar = r.tmax;
  e.mask = 0xFFFFFFFFu;
  e.id = 0;
  e.flags = 0;
  return e;
}

class EmbreeTracer final : public Tracer {
 public:
  EmbreeTracer(const Scene& scene, BuildQuality quality) : quality_(quality) {
    device_ = rtcNewDevice(nullptr);
    if (!device_)
      fail("embree: cannot create a device (error {})", int(rtcGetDeviceError(nullptr)));
    rtcSetDeviceMemoryMonitorFunction(device_, &EmbreeTracer::on_memory, this);
    rebuild(scene);
  }
  ~EmbreeTracer() override {
    if (scene_) rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }

  Hit intersect(const Ray& ray) const override {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray = to_embree(ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    Hit hit;
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      hit.t = rh.ray.tfar;
      hit.mesh = rh.hit.geomID;
      hit.triangle = rh.hit.primID;
      hit.barycentric = {rh.hit.u, rh.hit.v};
    }
    return hit;
  }

  bool occluded(const Ray& ray) const override {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r = to_embree(ray);
    rtcOccluded1(scene_, &context, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on an occluded ray
  }

  void intersect(std::span<const Ray> rays, std::span<Hit> hits, bool coherent) const override {
    if (!coherent) {
      for (size_t i = 0; i < rays.size(); ++i) hits[i] = intersect(rays[i]);
      return;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (size_t base = 0; base < rays.size(); base += 8) {
      const size_t n = std::min<size_t>(8, rays.size() - base);
      alignas(32) int valid[8];
      alignas(32) RTCRayHit8 packet;
      for (size_t k = 0; k < 8; ++k) {
        valid[k] = k < n ? -1 : 0;
        const Ray& r = rays[base + (k < n ? k : 0)];
        packet.ray.org_x[k] = r.origin.x;
        packet.ray.org_y[k] = r.origin.y;
        packet.ray.org_z[k] = r.origin.z;
        packet.ray.tnear[k] = r.tmin;
        packet.ray.dir_x[k] = r.direction.x;
        packet.ray.dir_y[k] = r.direction.y;
        packet.ray.dir_z[k] = r.direction.z;
        packet.ray.time[k] = 0.0f;
        packet.ray.tfar[k] = r.tmax;
        packet.ray.mask[k] = 0xFFFFFFFFu;
        packet.ray.id[k] = 0;
        packet.ray.flags[k] = 0;
        packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect8(valid, scene_, &context, &packet);
      for (size_t k = 0; k < n; ++k) {
        Hit& hit = hits[base + k];
        hit = Hit{};
        if (packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) {
          hit.t = packet.ray.tfar[k];
          hit.mesh = packet.hit.geomID[k];
          hit.triangle = packet.hit.primID[k];
          hit.barycentric = {packet.hit.u[k], packet.hit.v[k]};
        }
      }
    }
  }

  void occluded(std::span<const Ray> rays, std::span<uint8_t> blocked) const override {
    for (size_t i = 0; i < rays.size(); ++i) blocked[i] = occluded(rays[i]) ? 1 : 0;
  }

  void rebuild(const Scene& scene) override {
    Stopwatch watch;
    if (scene_) rtcReleaseScene(scene_);
    scene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene_, to_embree(quality_));
    for (unsigned id = 0; id < scene.meshes.size(); ++id)
      if (!scene.meshes[id].triangles.empty()) attach(scene.meshes[id], id);
    rtcCommitScene(scene_);
    const RTCError error = rtcGetDeviceError(device_);
    if (error != RTC_ERROR_NONE)
      fail("{}: embree failed to build the acceleration structure (error {})", scene.source,
           int(error));
    build_ms_ = watch.elapsed_ms();
  }

  TracerStats stats() const override { return {size_t(std::max<ssize_t>(0, memory_)), build_ms_}; }

 private:
  void attach(const Mesh& mesh, unsigned id) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geometry, to_embree(quality_));
    // Embree reads vertices with 16-byte loads, so its own buffers (padded) hold a copy.
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(uint32_t), mesh.triangles.size()));
    if (!vertices || !indices) fail("embree: out of memory for mesh '{}'", mesh.name);
    for (size_t i = 0; i < mesh.positions.size(); ++i)
      for (int c = 0; c < 3; ++c) vertices[3 * i + c] = mesh.positions[i][c];
    for (size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int c = 0; c < 3; ++c) indices[3 * i + c] = mesh.triangles[i][c];
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene_, geometry, id);
    rtcReleaseGeometry(geometry);
  }

  static bool on_memory(void* self, ssize_t bytes, bool) {
    static_cast<EmbreeTracer*>(self)->memory_ += bytes;
    return true;
  }

  BuildQuality quality_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::atomic<ssize_t> memory_{0};
  double build_ms_ = 0.0;
};

}  // namespace

std::unique_ptr<Tracer> make_embree_tracer(const Scene& scene, BuildQuality quality) {
  return std::make_unique<EmbreeTracer>(scene, quality);
}

}  // namespace bounce
