// Checked reads from a glTF model: buffer views, accessors and the numbers of its JSON objects.
// tinygltf hands over indices, counts and byte ranges as the file states them; every one is
// checked here before use, since a broken file must give an error, never an out-of-bounds read.
#include <cmath>

#include "bounce/core/error.h"
#include "bounce/scene/gltf_internal.h"

namespace bounce::gltf {

namespace {

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    default:
      return "matrix or unknown";
  }
}

}  // namespace

Bytes buffer_view_bytes(const Context& ctx, int index, const std::string& what) {
  const tg::Model& m = ctx.model;
  if (index < 0 || size_t(index) >= m.bufferViews.size())
    fail("{}: {}: bufferView {} does not exist ({} bufferViews)", ctx.path, what, index,
         m.bufferViews.size());
  const tg::BufferView& view = m.bufferViews[size_t(index)];
  if (view.buffer < 0 || size_t(view.buffer) >= m.buffers.size())
    fail("{}: {}: bufferView {} uses buffer {}, which does not exist ({} buffers)", ctx.path, what,
         index, view.buffer, m.buffers.size());
  const std::vector<unsigned char>& data = m.buffers[size_t(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail("{}: {}: bufferView {} (offset {}, length {}) runs past the end of buffer {} ({} bytes)",
         ctx.path, what, index, view.byteOffset, view.byteLength, view.buffer, data.size());
  return {data.data() + view.byteOffset, view.byteLength};
}

AccessorData accessor_data(const Context& ctx, int index, const std::string& what) {
  const tg::Model& m = ctx.model;
  if (index < 0 || size_t(index) >= m.accessors.size())
    fail("{}: {}: accessor {} does not exist ({} accessors)", ctx.path, what, index,
         m.accessors.size());
  const tg::Accessor& a = m.accessors[size_t(index)];
  const std::string where = fmt::format("{} (accessor {})", what, index);
  if (a.sparse.isSparse) fail("{}: {}: sparse accessors are not supported", ctx.path, where);
  const int component_size = tg::GetComponentSizeInBytes(uint32_t(a.componentType));
  const int components = tg::GetNumComponentsInType(uint32_t(a.type));
  if (component_size <= 0)
    fail("{}: {}: unknown component type {}", ctx.path, where, a.componentType);
  if (components <= 0) fail("{}: {}: unknown type {}", ctx.path, where, a.type);
  if (a.bufferView < 0) fail("{}: {}: has no bufferView", ctx.path, where);
  const Bytes view = buffer_view_bytes(ctx, a.bufferView, where);
  const size_t element = size_t(component_size) * size_t(components);
  const size_t declared_stride = m.bufferViews[size_t(a.bufferView)].byteStride;
  const size_t stride = declared_stride != 0 ? declared_stride : element;
  if (stride < element)
    fail("{}: {}: byteStride {} is smaller than an element ({} bytes)", ctx.path, where, stride,
         element);
  AccessorData out;
  out.count = a.count;
  out.stride = stride;
  out.component_type = a.componentType;
  out.components = components;
  out.normalized = a.normalized;
  if (a.count == 0) return out;
  // The last element must end inside the view: offset + stride * (count - 1) + element <= length,
  // checked without overflow.
  const bool fits = a.byteOffset <= view.size && element <= view.size - a.byteOffset &&
                    a.count - 1 <= (view.size - a.byteOffset - element) / stride;
  if (!fits)
    fail(
        "{}: {}: {} elements of {} bytes (stride {}) from byte offset {} run past the end of "
        "bufferView {} ({} bytes)",
        ctx.path, where, a.count, element, stride, a.byteOffset, a.bufferView, view.size);
  out.data = view.data + a.byteOffset;
  return out;
}

void expect_type(const Context& ctx, int index, const AccessorData& a, int components,
                 const char* type, const std::string& what) {
  if (a.components != components)
    fail("{}: {}: expected {} elements, found {}", ctx.path, what, type,
         type_name(ctx.model.accessors[size_t(index)].type));
}

std::vector<vec3> read_vec3(const Context& ctx, int index, const std::string& what) {
  const AccessorData a = accessor_data(ctx, index, what);
  expect_type(ctx, index, a, 3, "VEC3", what);
  if (a.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT)
    fail("{}: {}: expected float components (type {})", ctx.path, what, a.component_type);
  std::vector<vec3> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = a.data + i * a.stride;
    out[i] = vec3(read_at<float>(p), read_at<float>(p + 4), read_at<float>(p + 8));
  }
  return out;
}

std::vector<vec2> read_uv(const Context& ctx, int index, const std::string& what) {
  const AccessorData a = accessor_data(ctx, index, what);
  expect_type(ctx, index, a, 2, "VEC2", what);
  const int t = a.component_type;
  if (t != TINYGLTF_COMPONENT_TYPE_FLOAT &&
      !(a.normalized && (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                         t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)))
    fail("{}: {}: texture coordinates must be float or normalized unsigned byte/short", ctx.path,
         what);
  std::vector<vec2> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = a.data + i * a.stride;
    if (t == TINYGLTF_COMPONENT_TYPE_FLOAT) {
      out[i] = vec2(read_at<float>(p), read_at<float>(p + 4));
    } else if (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
      out[i] = vec2(p[0], p[1]) / 255.0f;
    } else {
      out[i] = vec2(read_at<uint16_t>(p), read_at<uint16_t>(p + 2)) / 65535.0f;
    }
  }
  return out;
}

std::vector<uint32_t> read_indices(const Context& ctx, int index, const std::string& what) {
  const AccessorData a = accessor_data(ctx, index, what);
  expect_type(ctx, index, a, 1, "SCALAR", what);
  std::vector<uint32_t> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = a.data + i * a.stride;
    switch (a.component_type) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        out[i] = p[0];
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        out[i] = read_at<uint16_t>(p);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        out[i] = read_at<uint32_t>(p);
        break;
      default:
        fail("{}: {}: indices must be unsigned byte, short or int (type {})", ctx.path, what,
             a.component_type);
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Numbers from the JSON

double number_or(const tg::Value& object, const char* key, double fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tg::Value& v = object.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

const tg::Value* extension(const tg::ExtensionMap& extensions, const char* name) {
  const auto it = extensions.find(name);
  return it != extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

vec3 vec3_from(const Context& ctx, const std::vector<double>& v, size_t min_size,
               const std::string& what) {
  if (v.size() < 3 || v.size() < min_size)
    fail("{}: {} needs {} numbers, found {}", ctx.path, what, std::max<size_t>(3, min_size),
         v.size());
  const vec3 out(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
  if (!is_finite(out)) fail("{}: {} is not finite", ctx.path, what);
  return out;
}

float finite_number(const Context& ctx, double value, const std::string& what) {
  if (!std::isfinite(value)) fail("{}: {} is not finite", ctx.path, what);
  return float(value);
}

}  // namespace bounce::gltf
