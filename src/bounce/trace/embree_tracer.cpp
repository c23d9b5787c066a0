// The CPU Tracer on Embree 3: one triangle geometry per mesh (geometry id = mesh index), plus the
// scene's sphere lights tested after Embree. Single rays go through the trace view
// (rtcIntersect1/rtcOccluded1, also what kernels call), every span of rays through Embree's stream
// API (rtcIntersect1M, rtcOccluded1M, flagged coherent or not), which measured faster here than our
// own 8-wide packets and than single rays (docs/benchmarks.md).
// Alpha cut-outs are Embree filter functions on the meshes that have them (cutout_view.h).
// A scene with animated meshes is built two-level (Embree's low scene quality): static meshes
// keep their own high-quality BVHs and animated ones are refitted when their vertices move.
#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/core/timer.h"
#include "bounce/trace/cutouts.h"
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

  Hit intersect(const Ray& ray) const override { return view().intersect(ray); }
  bool occluded(const Ray& ray) const override { return view().occluded(ray); }

  void intersect(std::span<const Ray> rays, std::span<Hit> hits, bool coherent) const override {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags =
        coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    constexpr size_t kChunk = 64;
    RTCRayHit chunk[kChunk];
    for (size_t base = 0; base < rays.size(); base += kChunk) {
      const size_t n = std::min(kChunk, rays.size() - base);
      for (size_t k = 0; k < n; ++k) {
        chunk[k].ray = to_embree(rays[base + k]);
        chunk[k].hit.geomID = RTC_INVALID_GEOMETRY_ID;
        chunk[k].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect1M(scene_, &context, chunk, unsigned(n), sizeof(RTCRayHit));
      for (size_t k = 0; k < n; ++k) {
        Hit& hit = hits[base + k];
        hit = Hit{};
        if (chunk[k].hit.geomID != RTC_INVALID_GEOMETRY_ID) {
          hit.t = chunk[k].ray.tfar;
          hit.mesh = chunk[k].hit.geomID;
          hit.triangle = chunk[k].hit.primID;
          hit.barycentric = {chunk[k].hit.u, chunk[k].hit.v};
        }
        closest_sphere(spheres_.data(), uint32_t(spheres_.size()), rays[base + k], hit);
      }
    }
  }

  void occluded(std::span<const Ray> rays, std::span<uint8_t> blocked) const override {
    // Embree's stream API reorders and packetises the rays internally.
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    constexpr size_t kChunk = 256;
    RTCRay chunk[kChunk];
    for (size_t base = 0; base < rays.size(); base += kChunk) {
      const size_t n = std::min(kChunk, rays.size() - base);
      for (size_t k = 0; k < n; ++k) chunk[k] = to_embree(rays[base + k]);
      rtcOccluded1M(scene_, &context, chunk, unsigned(n), sizeof(RTCRay));
      for (size_t k = 0; k < n; ++k)
        blocked[base + k] =
            chunk[k].tfar < 0.0f ||
                    any_sphere(spheres_.data(), uint32_t(spheres_.size()), rays[base + k])
                ? 1
                : 0;
    }
  }

  TraceView view() const override {
    return {scene_, spheres_.data(), uint32_t(spheres_.size()), {}};
  }

  void rebuild(const Scene& scene) override {
    Stopwatch watch;
    spheres_ = trace_spheres(scene);
    if (scene_) rtcReleaseScene(scene_);
    scene_ = rtcNewScene(device_);
    std::vector<bool> animated(scene.meshes.size(), false);
    for (const auto& am : scene.animation.meshes) animated[am.mesh] = true;
    const bool dynamic = !scene.animation.meshes.empty();
    if (dynamic) rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(scene_, dynamic ? RTC_BUILD_QUALITY_LOW : to_embree(quality_));
    vertex_counts_.assign(scene.meshes.size(), 0);
    cutouts_.build(scene);
    cutout_view_ = cutouts_.view();
    for (unsigned id = 0; id < scene.meshes.size(); ++id)
      if (!scene.meshes[id].triangles.empty())
        attach(scene.meshes[id], id, animated[id] ? RTC_BUILD_QUALITY_REFIT : to_embree(quality_));
    rtcCommitScene(scene_);
    const RTCError error = rtcGetDeviceError(device_);
    if (error != RTC_ERROR_NONE)
      fail("{}: embree failed to build the acceleration structure (error {})", scene.source,
           int(error));
    build_ms_ = watch.elapsed_ms();
  }

  void update(const Scene& scene, std::span<const uint32_t> moved_meshes) override {
    spheres_ = trace_spheres(scene);
    if (moved_meshes.empty()) return;
    for (uint32_t id : moved_meshes) {
      const Mesh& mesh = scene.meshes.at(id);
      if (id >= vertex_counts_.size() || vertex_counts_[id] != mesh.positions.size() ||
          !cutouts_.fits(scene)) {
        rebuild(scene);  // the topology changed: refitting cannot follow
        return;
      }
      if (mesh.triangles.empty()) continue;
      RTCGeometry geometry = rtcGetGeometry(scene_, id);
      auto* vertices =
          static_cast<float*>(rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_VERTEX, 0));
      copy_vertices(mesh, vertices);
      rtcUpdateGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0);
      rtcCommitGeometry(geometry);
    }
    rtcCommitScene(scene_);
    const RTCError error = rtcGetDeviceError(device_);
    if (error != RTC_ERROR_NONE)
      fail("{}: embree failed to update the acceleration structure (error {})", scene.source,
           int(error));
  }

  TracerStats stats() const override { return {size_t(std::max<ssize_t>(0, memory_)), build_ms_}; }

 private:
  // Coordinates within 1e-30 of zero go to Embree as zero (a move of less than 1e-30 m). Its
  // spatial-split builder runs with denormals flushed to zero, and a triangle edge between two
  // such tiny coordinates can cross a split while the difference of its ends flushes to zero:
  // Debian's Embree 3.13.5 then fails an assertion and aborts the process (a fuzzed map with
  // coordinates of 1e-39 to 1e-35 found it). Past 1e-30, two different floats differ by more
  // than the smallest normal float.
  static float embree_coordinate(float v) { return std::fabs(v) < 1e-30f ? 0.0f : v; }
  static void copy_vertices(const Mesh& mesh, float* vertices) {
    for (size_t i = 0; i < mesh.positions.size(); ++i)
      for (int c = 0; c < 3; ++c) vertices[3 * i + c] = embree_coordinate(mesh.positions[i][c]);
  }

  void attach(const Mesh& mesh, unsigned id, RTCBuildQuality quality) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geometry, quality);
    // Embree reads vertices with 16-byte loads, so its own buffers (padded) hold a copy.
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(uint32_t), mesh.triangles.size()));
    if (!vertices || !indices) fail("embree: out of memory for mesh '{}'", mesh.name);
    copy_vertices(mesh, vertices);
    vertex_counts_[id] = mesh.positions.size();
    for (size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int c = 0; c < 3; ++c) indices[3 * i + c] = mesh.triangles[i][c];
    if (id < cutout_view_.mesh_count && cutout_view_.meshes[id].triangles) {
      // Alpha cut-outs: hits in holes are rejected, so rays go on (closest and any hit alike).
      rtcSetGeometryUserData(geometry, &cutout_view_);
      rtcSetGeometryIntersectFilterFunction(geometry, &EmbreeTracer::cutout_filter);
      rtcSetGeometryOccludedFilterFunction(geometry, &EmbreeTracer::cutout_filter);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene_, geometry, id);
    rtcReleaseGeometry(geometry);
  }

  // Embree's filter for geometries with cut-outs: the same test as our BVH's traversal.
  static void cutout_filter(const RTCFilterFunctionNArguments* args) {
    const auto* cutouts = static_cast<const CutoutView*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
      if (args->valid[i] != -1) continue;
      if (cutouts->passes(RTCHitN_geomID(args->hit, args->N, i),
                          RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                          RTCHitN_v(args->hit, args->N, i)))
        args->valid[i] = 0;
    }
  }

  static bool on_memory(void* self, ssize_t bytes, bool) {
    static_cast<EmbreeTracer*>(self)->memory_ += bytes;
    return true;
  }

  BuildQuality quality_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<size_t> vertex_counts_;  // per mesh, as attached
  std::vector<TraceSphere> spheres_;   // the scene's sphere lights
  Cutouts cutouts_;                    // alpha-masked holes, read by cutout_filter
  CutoutView cutout_view_;             // what the filters' user data points at
  std::atomic<ssize_t> memory_{0};
  double build_ms_ = 0.0;
};

}  // namespace

Hit host_intersect_triangles(const void* triangles, const Ray& ray) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray = to_embree(ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(RTCScene(const_cast<void*>(triangles)), &context, &rh);
  Hit hit;
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    hit.t = rh.ray.tfar;
    hit.mesh = rh.hit.geomID;
    hit.triangle = rh.hit.primID;
    hit.barycentric = {rh.hit.u, rh.hit.v};
  }
  return hit;
}

bool host_occluded_triangles(const void* triangles, const Ray& ray) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = to_embree(ray);
  rtcOccluded1(RTCScene(const_cast<void*>(triangles)), &context, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on an occluded ray
}

std::unique_ptr<Tracer> make_embree_tracer(const Scene& scene, BuildQuality quality) {
  return std::make_unique<EmbreeTracer>(scene, quality);
}

}  // namespace bounce
