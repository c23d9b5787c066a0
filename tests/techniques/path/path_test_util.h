// Shared helpers for the path tracer's tests: small analytic scenes and sample statistics.
#pragma once

#include <cmath>
#include <string>

#include "bounce/scene/scene.h"

namespace bounce::path_test {

// A quad (0,1,2), (0,2,3) facing where cross(p1 - p0, p2 - p0) points.
inline void add_quad(Mesh& mesh, vec3 p0, vec3 p1, vec3 p2, vec3 p3, uint32_t material) {
  const uint32_t base = uint32_t(mesh.positions.size());
  for (const vec3& p : {p0, p1, p2, p3}) mesh.positions.push_back(p);
  mesh.triangles.push_back({base, base + 1, base + 2});
  mesh.triangles.push_back({base, base + 2, base + 3});
  mesh.materials.insert(mesh.materials.end(), 2, material);
}

// The six faces of the cube [-h, h]^3, facing inwards.
inline Mesh inward_cube(float h, uint32_t material) {
  Mesh mesh;
  mesh.name = "cube";
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.0f, 1.0f}) {
      vec3 c(0.0f), u(0.0f), v(0.0f);
      c[axis] = sign * h;
      u[(axis + 1) % 3] = h;
      v[(axis + 2) % 3] = h;
      // cross(u, v) points along +axis: the face at +h must face -axis, so swap there.
      if (sign > 0.0f) std::swap(u, v);
      add_quad(mesh, c - u - v, c + u - v, c + u + v, c - u + v, material);
    }
  return mesh;
}

// A white furnace: the inside of a cube whose walls all reflect with `albedo` (Lambert) and
// emit `radiance`; the camera sits at the centre.
inline Scene furnace(vec3 albedo, vec3 radiance) {
  Scene s;
  s.source = "furnace";
  Material m;
  m.name = "wall";
  m.albedo = albedo;
  m.emission = radiance;
  s.materials.push_back(m);
  s.meshes.push_back(inward_cube(1.0f, 0));
  s.camera.position = vec3(0.0f);
  s.camera.look_at = vec3(0.3f, 0.2f, 1.0f);
  s.camera.vfov_deg = 90.0f;
  s.has_camera = true;
  s.finalize();
  return s;
}

// Le * (1 + a + ... + a^n) per channel; n < 0 gives the limit Le / (1 - a).
inline vec3 geometric_sum(vec3 radiance, vec3 a, int n) {
  if (n < 0) return radiance / (vec3(1.0f) - a);
  vec3 sum(0.0f), term(1.0f);
  for (int k = 0; k <= n; ++k, term *= a) sum += term;
  return radiance * sum;
}

// Running mean and standard error of a per-channel estimator.
struct Estimate {
  double n = 0.0;
  double sum[3] = {0, 0, 0};
  double sum2[3] = {0, 0, 0};

  void add(vec3 v) {
    n += 1.0;
    for (int k = 0; k < 3; ++k) {
      sum[k] += v[k];
      sum2[k] += double(v[k]) * v[k];
    }
  }
  double mean(int k) const { return sum[k] / n; }
  double standard_error(int k) const {
    const double m = mean(k);
    return std::sqrt(std::max(0.0, sum2[k] / n - m * m) / (n - 1.0));
  }
};

}  // namespace bounce::path_test
