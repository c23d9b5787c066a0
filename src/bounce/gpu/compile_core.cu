// nvcc check of the core helpers kernels use: sampling, random numbers, QMC, octahedral
// directions, the orthonormal basis and camera rays.
#include "bounce/core/octahedral.h"
#include "bounce/core/qmc.h"
#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/scene/camera.h"

namespace bounce {

__global__ void check_core(CameraRays camera, uint32_t n, vec3* out) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  TeaRng tea = TeaRng::for_path(i, hash_u32(n));
  Pcg32 pcg(i, 7);
  const vec2 u = rotate_unit(hammersley(i, n), tea.next2());
  const vec2 v = sobol2(i) + vec2(radical_inverse(3, i), pcg.next_float()) + pcg.next2();
  const Basis frame = Basis::from_normal(camera.direction(u.x, u.y));
  vec3 d = frame.to_world(sample_cosine_hemisphere(u)) + sample_uniform_sphere(v) +
           sample_uniform_cone(u, 0.5f) + sample_ggx_half_vector(v, 0.3f);
  d += vec3(sample_uniform_triangle(u) + sample_concentric_disk(v) + camera.project(d), 0.0f);
  d += oct_unpack(oct_pack(glm::normalize(d))) + offset_origin(d, frame.n);
  out[i] = d * (uniform_sphere_pdf() + cosine_hemisphere_pdf(d.z) + uniform_cone_pdf(0.5f) +
                float(pcg.next_below(5)) + sqr(max_component(d)) + (is_finite(d) ? 1.0f : 0.0f));
}

}  // namespace bounce
