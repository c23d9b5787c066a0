// Shared helpers for the path tracer's tests: the white furnace and sample statistics.
#pragma once

#include <cmath>
#include <string>

#include "bounce/scene/scene.h"
#include "scene/hand_built_scenes.h"

namespace bounce::path_test {

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
  s.meshes.push_back(scene_test::inward_box("cube", vec3(-1.0f), vec3(1.0f), 0));
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
