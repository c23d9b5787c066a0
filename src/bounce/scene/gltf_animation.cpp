// glTF node animations: translation, rotation and scale channels of every animation in the file,
// played together, as TrsTracks attached to the meshes and lights they move.
#include <algorithm>
#include <cmath>

#include "bounce/core/error.h"
#include "bounce/scene/gltf_internal.h"

namespace bounce::gltf {

namespace {

std::vector<float> read_times(const Context& ctx, int index, const std::string& what) {
  const AccessorData a = accessor_data(ctx, index, what);
  expect_type(ctx, index, a, 1, "SCALAR", what);
  if (a.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT)
    fail("{}: {}: key times must be floats (component type {})", ctx.path, what, a.component_type);
  std::vector<float> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    out[i] = read_at<float>(a.data + i * a.stride);
    if (!std::isfinite(out[i])) fail("{}: {}: key time {} is not finite", ctx.path, what, i);
  }
  return out;
}

// Quaternions (x, y, z, w) as floats or normalized integers, each one checked to be usable.
std::vector<quat> read_rotations(const Context& ctx, int index, const std::string& what) {
  const AccessorData a = accessor_data(ctx, index, what);
  expect_type(ctx, index, a, 4, "VEC4", what);
  const int t = a.component_type;
  const bool integer =
      t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
      t == TINYGLTF_COMPONENT_TYPE_SHORT || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  if (t != TINYGLTF_COMPONENT_TYPE_FLOAT && !(integer && a.normalized))
    fail("{}: {}: rotations must be floats or normalized (unsigned) bytes or shorts", ctx.path,
         what);
  std::vector<quat> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = a.data + i * a.stride;
    vec4 q;
    for (int c = 0; c < 4; ++c) {
      switch (t) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
          q[c] = read_at<float>(p + 4 * c);
          break;
        case TINYGLTF_COMPONENT_TYPE_BYTE:
          q[c] = std::max(float(read_at<int8_t>(p + c)) / 127.0f, -1.0f);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          q[c] = float(p[c]) / 255.0f;
          break;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
          q[c] = std::max(float(read_at<int16_t>(p + 2 * c)) / 32767.0f, -1.0f);
          break;
        default:
          q[c] = float(read_at<uint16_t>(p + 2 * c)) / 65535.0f;
      }
    }
    const float length = glm::length(q);
    if (!std::isfinite(length) || !(length > 1e-12f))
      fail("{}: {}: key {} is not a usable rotation quaternion", ctx.path, what, i);
    q /= length;
    out[i] = quat(q.w, q.x, q.y, q.z);  // glTF stores x, y, z, w
  }
  return out;
}

// The keys of a glTF sampler into `out`, keeping the value keys of CUBICSPLINE's
// (in-tangent, value, out-tangent) triples.
template <typename T, typename Read>
void read_sampler(Context& ctx, const tg::AnimationSampler& sampler, const std::string& where,
                  Read read, Keyframes<T>* out) {
  const bool cubic = sampler.interpolation == "CUBICSPLINE";
  if (sampler.interpolation != "LINEAR" && sampler.interpolation != "STEP" && !cubic)
    fail("{}: {}: unknown interpolation '{}' (LINEAR, STEP or CUBICSPLINE)", ctx.path, where,
         sampler.interpolation);
  std::vector<float> times = read_times(ctx, sampler.input, where + " input");
  std::vector<T> values = read(ctx, sampler.output, where + " output");
  if (times.empty()) fail("{}: {}: the sampler has no keys", ctx.path, where);
  const size_t expected = cubic ? 3 * times.size() : times.size();
  if (values.size() != expected)
    fail("{}: {}: {} key times but {} output values (expected {}{})", ctx.path, where, times.size(),
         values.size(), expected, cubic ? " for CUBICSPLINE" : "");
  if (cubic) {
    ctx.ignored.insert("CUBICSPLINE tangents (keys are interpolated linearly)");
    for (size_t i = 0; i < times.size(); ++i) values[i] = values[3 * i + 1];
    values.resize(times.size());
  }
  for (size_t i = 1; i < times.size(); ++i)
    if (!(times[i] > times[i - 1]))
      fail("{}: {}: key times must increase (key {} at {} s after {} s)", ctx.path, where, i,
           times[i], times[i - 1]);
  out->times = std::move(times);
  out->values = std::move(values);
  out->step = sampler.interpolation == "STEP";
}

std::vector<vec3> read_finite_vec3(const Context& ctx, int index, const std::string& what) {
  std::vector<vec3> v = read_vec3(ctx, index, what);
  for (size_t i = 0; i < v.size(); ++i)
    if (!is_finite(v[i])) fail("{}: {}: key {} is not finite", ctx.path, what, i);
  return v;
}

}  // namespace

// Every node animation of the file (all animations play together) as one TrsTrack per animated
// node, attached to the meshes and lights of the node and of its descendants.
void read_animations(Context& ctx) {
  const tg::Model& m = ctx.model;
  std::vector<TrsTrack> node_tracks(m.nodes.size());
  std::vector<char> animated(m.nodes.size(), 0);
  for (size_t ai = 0; ai < m.animations.size(); ++ai) {
    const tg::Animation& anim = m.animations[ai];
    const std::string label = anim.name.empty() ? fmt::format("animation {}", ai)
                                                : fmt::format("animation {} ('{}')", ai, anim.name);
    for (size_t ci = 0; ci < anim.channels.size(); ++ci) {
      const tg::AnimationChannel& channel = anim.channels[ci];
      const std::string where = fmt::format("{} channel {}", label, ci);
      if (channel.sampler < 0 || size_t(channel.sampler) >= anim.samplers.size())
        fail("{}: {}: sampler {} does not exist ({} samplers)", ctx.path, where, channel.sampler,
             anim.samplers.size());
      if (channel.target_node < 0) {
        ctx.ignored.insert("animation channels without a target node");
        continue;
      }
      if (size_t(channel.target_node) >= m.nodes.size())
        fail("{}: {}: target node {} does not exist ({} nodes)", ctx.path, where,
             channel.target_node, m.nodes.size());
      const std::string& path = channel.target_path;
      if (path == "weights") {
        ctx.ignored.insert("morph target weight animations");
        continue;
      }
      if (path != "translation" && path != "rotation" && path != "scale")
        fail("{}: {}: unknown target path '{}' (translation, rotation, scale or weights)", ctx.path,
             where, path);
      const tg::AnimationSampler& sampler = anim.samplers[size_t(channel.sampler)];
      const std::string sampler_where = fmt::format("{} sampler {}", label, channel.sampler);
      const size_t node = size_t(channel.target_node);
      TrsTrack& track = node_tracks[node];
      animated[node] = 1;
      Keyframes<vec3> vec3_keys;
      Keyframes<quat> quat_keys;
      bool taken = false;
      if (path == "rotation") {
        read_sampler(ctx, sampler, sampler_where, read_rotations, &quat_keys);
        taken = !track.rotation.empty();
        if (!taken) track.rotation = std::move(quat_keys);
      } else {
        read_sampler(ctx, sampler, sampler_where, read_finite_vec3, &vec3_keys);
        Keyframes<vec3>& keys = path == "translation" ? track.translation : track.scale;
        taken = !keys.empty();
        if (!taken) keys = std::move(vec3_keys);
      }
      if (taken)
        ctx.ignored.insert("further channels animating a node's " + path +
                           " (the first one is used)");
    }
  }

  // Tracks for the animated nodes that were reached and move a mesh or light (theirs or a
  // descendant's), in walk order; then each mesh and light takes the tracks of its animated
  // ancestors (itself included), outermost first.
  std::vector<char> drives(m.nodes.size(), 0);
  for (auto it = ctx.walk_order.rbegin(); it != ctx.walk_order.rend(); ++it) {
    const size_t i = size_t(*it);
    drives[i] |= ctx.meshes_of[i].first != ctx.meshes_of[i].second ||
                 ctx.lights_of[i].first != ctx.lights_of[i].second;
    if (ctx.parent_of[i] >= 0) drives[size_t(ctx.parent_of[i])] |= drives[i];
  }
  Animation& out = ctx.scene.animation;
  std::vector<int> track_of(m.nodes.size(), -1);
  for (int index : ctx.walk_order) {
    const size_t i = size_t(index);
    if (!animated[i] || !drives[i]) continue;
    TrsTrack& track = node_tracks[i];
    const tg::Node& node = m.nodes[i];
    track.name = node.name.empty() ? fmt::format("node {}", index) : node.name;
    const int parent = ctx.parent_of[i];
    track.pivot = parent < 0 ? mat4(1.0f) : ctx.world_of[size_t(parent)];
    track.rest = local_transform(ctx, node, index);
    if (std::abs(glm::determinant(track.rest)) < 1e-12f)
      fail("{}: node {} is animated but its transform is singular", ctx.path, index);
    track_of[i] = int(out.tracks.size());
    out.tracks.push_back(std::move(track));
  }
  if (out.tracks.empty()) return;
  for (int index : ctx.walk_order) {
    std::vector<uint32_t> chain;
    for (int n = index; n >= 0; n = ctx.parent_of[size_t(n)])
      if (track_of[size_t(n)] >= 0) chain.push_back(uint32_t(track_of[size_t(n)]));
    if (chain.empty()) continue;
    std::reverse(chain.begin(), chain.end());
    const auto [mesh_first, mesh_end] = ctx.meshes_of[size_t(index)];
    for (uint32_t k = mesh_first; k < mesh_end; ++k) {
      AnimatedMesh am;
      am.mesh = k;
      am.tracks = chain;
      out.meshes.push_back(std::move(am));
    }
    const auto [light_first, light_end] = ctx.lights_of[size_t(index)];
    for (uint32_t k = light_first; k < light_end; ++k) {
      AnimatedLight al;
      al.light = k;
      al.tracks = chain;
      out.lights.push_back(std::move(al));
    }
  }
}

}  // namespace bounce::gltf
