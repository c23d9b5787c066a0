// Wavefront OBJ + MTL through tinyobjloader.
//
// tinyobjloader is forgiving in ways that would hide bad data: it reads "nan" or a cut-off number
// as 0, silently drops faces with fewer than three vertices, and only warns about indices out of
// range. So every OBJ and MTL text is first checked line by line here (numbers must parse and be
// finite, faces need 3..255 vertices), and every index tinyobjloader returns is checked again.
// The check also records the line of each face so that later errors can name it.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

#include <tiny_obj_loader.h>

#include "bounce/core/error.h"
#include "bounce/core/image_io.h"
#include "bounce/core/input_file.h"
#include "bounce/scene/load.h"

namespace bounce {

namespace {

namespace fs = std::filesystem;

// tinyobjloader stores a face's vertex count in an unsigned char.
constexpr size_t kMaxFaceVertices = 255;

// ---------------------------------------------------------------------------------------------
// Line-level checks

// Calls f(line, line_number) for each line, ending lines at "\n", "\r\n" or "\r" as
// tinyobjloader does, so that line numbers agree with its messages.
template <typename F>
void for_each_line(std::string_view text, F&& f) {
  size_t line_number = 0;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = start;
    while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
    f(text.substr(start, end - start), ++line_number);
    if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n')
      ++end;
    start = end + 1;
  }
}

std::vector<std::string_view> split_tokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

// A whole token that is a finite number ("nan", "inf", "1e999" and "0.5x" are not).
bool is_finite_number(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  float value = 0.0f;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size() && std::isfinite(value);
}

bool is_integer(std::string_view token) {
  if (!token.empty() && (token.front() == '-' || token.front() == '+')) token.remove_prefix(1);
  if (token.empty()) return false;
  for (char c : token)
    if (c < '0' || c > '9') return false;
  return true;
}

bool is_zero(std::string_view token) {
  return !token.empty() && token.find_first_not_of("+-0") == std::string_view::npos;
}

// Checks a face vertex: v, v/t, v//n or v/t/n, each a non-zero integer (OBJ counts from 1,
// negative values count back from the last vertex).
void check_face_vertex(std::string_view token, const std::string& name, size_t line) {
  std::string_view parts[3];
  size_t count = 0;
  size_t start = 0;
  while (count < 3) {
    const size_t slash = token.find('/', start);
    parts[count++] = token.substr(start, slash == std::string_view::npos ? slash : slash - start);
    if (slash == std::string_view::npos) break;
    start = slash + 1;
    if (count == 3) count = 4;  // a fourth part
  }
  const bool ok = count <= 3 && is_integer(parts[0]) &&
                  (count < 2 || (count == 3 && parts[1].empty()) || is_integer(parts[1])) &&
                  (count < 3 || is_integer(parts[2]));
  if (!ok) fail("{}:{}: '{}' is not a face vertex (v, v/t, v//n or v/t/n)", name, line, token);
  for (size_t i = 0; i < count; ++i) {
    if (is_zero(parts[i]))
      fail("{}:{}: face vertex '{}' uses index 0 (OBJ indices start at 1)", name, line, token);
    // tinyobjloader reads indices into an int without an overflow check: 4294967295 would wrap
    // to -1 (the last vertex). No file holds 2^31 vertices, so a larger index is an error.
    std::string_view digits = parts[i];
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    int value = 0;
    if (!digits.empty() &&
        std::from_chars(digits.data(), digits.data() + digits.size(), value).ec != std::errc())
      fail("{}:{}: face vertex '{}': index {} is out of range", name, line, token, parts[i]);
  }
}

void check_numbers(const std::vector<std::string_view>& tokens, size_t min_count, size_t max_count,
                   const std::string& name, size_t line) {
  const size_t count = tokens.size() - 1;
  if (count < min_count || count > max_count) {
    if (min_count == max_count)
      fail("{}:{}: '{}' needs {} numbers, found {}", name, line, tokens[0], min_count, count);
    fail("{}:{}: '{}' needs {} to {} numbers, found {}", name, line, tokens[0], min_count,
         max_count, count);
  }
  for (size_t i = 1; i < tokens.size(); ++i)
    if (!is_finite_number(tokens[i]))
      fail("{}:{}: '{}' is not a finite number", name, line, tokens[i]);
}

struct ObjScan {
  std::vector<uint32_t> face_lines;  // the line of every face, in file order
  bool has_mtllib = false;
};

// Checks vertex data and faces (see the top of the file) and records each face's line.
ObjScan scan_obj(std::string_view text, const std::string& name) {
  ObjScan scan;
  for_each_line(text, [&](std::string_view line, size_t number) {
    const std::vector<std::string_view> tokens = split_tokens(line);
    if (tokens.empty() || tokens[0].front() == '#') return;
    const std::string_view key = tokens[0];
    if (key == "v") {
      check_numbers(tokens, 3, 7, name, number);  // x y z, optional w or r g b (+ w)
    } else if (key == "vn") {
      check_numbers(tokens, 3, 3, name, number);
    } else if (key == "vt") {
      check_numbers(tokens, 1, 3, name, number);
    } else if (key == "f") {
      const size_t count = tokens.size() - 1;
      if (count < 3) fail("{}:{}: a face needs at least 3 vertices, found {}", name, number, count);
      if (count > kMaxFaceVertices)
        fail("{}:{}: a face has {} vertices; at most {} are supported", name, number, count,
             kMaxFaceVertices);
      for (size_t i = 1; i < tokens.size(); ++i) check_face_vertex(tokens[i], name, number);
      scan.face_lines.push_back(uint32_t(number));
    } else if (key == "mtllib") {
      scan.has_mtllib = true;
    }
  });
  return scan;
}

// Returns an error message for the first malformed colour or exponent in an MTL text, or "".
// (tinyobjloader would read a missing or garbled number as 0, and "Kd 0.5" as (0.5, 0, 0).)
std::string check_mtl(std::string_view text, const std::string& name) {
  std::string error;
  for_each_line(text, [&](std::string_view line, size_t number) {
    if (!error.empty()) return;
    const std::vector<std::string_view> tokens = split_tokens(line);
    if (tokens.empty()) return;
    const std::string_view key = tokens[0];
    size_t expected = 0;
    if (key == "Kd" || key == "Ks" || key == "Ke") expected = 3;  // only what we use
    if (key == "Ns") expected = 1;
    if (key == "newmtl" && tokens.size() < 2) {
      error = fmt::format("{}:{}: 'newmtl' needs a name", name, number);
      return;
    }
    if (expected == 0) return;
    if (tokens.size() - 1 != expected) {
      error = fmt::format("{}:{}: '{}' needs {} number{}, found {}", name, number, key, expected,
                          expected == 1 ? "" : "s", tokens.size() - 1);
      return;
    }
    for (size_t i = 1; i < tokens.size(); ++i)
      if (!is_finite_number(tokens[i])) {
        error = fmt::format("{}:{}: '{}' is not a finite number", name, number, tokens[i]);
        return;
      }
  });
  return error;
}

bool read_file(const std::string& path, std::string* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) return false;
  *out = std::move(buffer).str();
  return true;
}

// ---------------------------------------------------------------------------------------------
// Materials

// Supplies MTL text to tinyobjloader for each `mtllib`: from files next to the OBJ, or from a
// string for OBJ text. It checks the text first and remembers the directory of each material's
// MTL file, which its texture paths are relative to.
class MtlReader : public tinyobj::MaterialReader {
 public:
  MtlReader(std::string dir, const std::string* text, std::string obj_name)
      : dir_(std::move(dir)), text_(text), obj_name_(std::move(obj_name)) {}

  bool operator()(const std::string& mtl_name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* material_map, std::string* warnings,
                  std::string* errors) override {
    std::string file_text;
    std::string label = obj_name_ + " (material text)";
    const std::string* text = text_;
    fs::path mtl_dir = dir_;
    if (text == nullptr) {
      const fs::path path = fs::path(dir_) / mtl_name;
      label = path.string();
      if (exists_but_not_regular(label)) {
        if (error_.empty())
          error_ =
              fmt::format("{}: mtllib '{}': {} is not a regular file", obj_name_, mtl_name, label);
        return false;
      }
      if (!read_file(label, &file_text)) {
        *warnings += "material file '" + label + "' not found\n";
        return false;
      }
      text = &file_text;
      mtl_dir = path.parent_path();
    }
    if (std::string problem = check_mtl(*text, label); !problem.empty()) {
      if (error_.empty()) error_ = std::move(problem);
      return false;
    }
    dirs_.push_back({materials->size(), mtl_dir.string()});
    std::istringstream stream(*text);
    tinyobj::LoadMtl(material_map, materials, &stream, warnings, errors);
    return true;
  }

  const std::string& error() const { return error_; }

  std::string texture_dir(size_t material) const {
    std::string dir = dir_;
    for (const auto& [first, d] : dirs_)
      if (material >= first) dir = d;
    return dir;
  }

 private:
  std::string dir_;
  const std::string* text_;  // null: read MTL files from dir_
  std::string obj_name_;
  std::string error_;
  std::vector<std::pair<size_t, std::string>> dirs_;  // (first material, its MTL's directory)
};

// Blinn-Phong exponent -> GGX perceptual roughness. Walter et al. 2007 match a Phong lobe of
// exponent Ns to a microfacet distribution of width alpha = sqrt(2 / (Ns + 2)); our material's
// alpha is roughness^2, so roughness = sqrt(alpha). Ns = 0 gives 1 (rough), Ns = 1000 gives 0.21.
float roughness_from_shininess(float ns) {
  const float alpha = std::sqrt(2.0f / (std::max(ns, 0.0f) + 2.0f));
  return glm::clamp(std::sqrt(alpha), 0.0f, 1.0f);
}

vec3 colour(const tinyobj::real_t c[3]) {
  return vec3(c[0], c[1], c[2]);
}

vec3 clamp_unit(vec3 c, const std::string& what, const std::string& name) {
  const vec3 clamped = glm::clamp(c, vec3(0.0f), vec3(1.0f));
  if (clamped != c)
    warn(fmt::format("{}: {} ({}, {}, {}) is outside [0, 1]; clamped", name, what, c.x, c.y, c.z));
  return clamped;
}

Texture texture_from_image(const Image& image, const std::string& name) {
  Texture t;
  t.name = name;
  t.width = image.width();
  t.height = image.height();
  t.texels = image.pixels();
  return t;
}

// Loads a material's map_Kd once per path; on failure warns and returns -1 (use Kd alone).
int load_texture(Scene& scene, std::map<std::string, int>& cache, const std::string& dir,
                 std::string file, const std::string& material, const std::string& name) {
  std::replace(file.begin(), file.end(), '\\', '/');  // paths written on Windows
  const std::string path = (fs::path(dir) / file).lexically_normal().string();
  if (const auto it = cache.find(path); it != cache.end()) return it->second;
  int index = -1;
  try {
    const Image image = load_image(path);
    if (image.width() > 0 && image.height() > 0 &&
        image.pixels().size() == size_t(image.width()) * size_t(image.height())) {
      index = int(scene.textures.size());
      scene.textures.push_back(texture_from_image(image, path));
    } else {
      warn(fmt::format("{}: material '{}': texture '{}' is empty; using its Kd colour alone", name,
                       material, path));
    }
  } catch (const Error& e) {
    warn(fmt::format("{}: material '{}': cannot load texture '{}' ({}); using its Kd colour alone",
                     name, material, path, e.what()));
  }
  cache[path] = index;
  return index;
}

Material convert_material(const tinyobj::material_t& m, const std::string& name) {
  Material out;
  out.name = m.name;
  const std::string where = "material '" + m.name + "'";
  out.albedo = clamp_unit(colour(m.diffuse), where + " Kd", name);
  out.f0 = clamp_unit(colour(m.specular), where + " Ks", name);
  out.roughness = roughness_from_shininess(m.shininess);
  out.emission = colour(m.emission);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Geometry

struct VertexKey {
  int v, n, t;
  bool operator==(const VertexKey&) const = default;
};

struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    uint64_t h = uint64_t(uint32_t(k.v)) * 0x9E3779B97F4A7C15ull;
    h ^= (uint64_t(uint32_t(k.n)) + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2));
    h ^= (uint64_t(uint32_t(k.t)) + 0x94D049BB133111EBull + (h << 6) + (h >> 2));
    return size_t(h);
  }
};

// Everything the mesh builder needs to check indices and name lines in messages.
struct ObjContext {
  const std::string& name;
  const tinyobj::attrib_t& attrib;
  const ObjScan& scan;
  size_t face_base = 0;  // global number of the current shape's first face
  bool lines_known = false;

  std::string where(size_t face) const {
    if (lines_known) return fmt::format("{}:{}", name, scan.face_lines[face_base + face]);
    return fmt::format("{}: face {}", name, face_base + face + 1);
  }
};

// `index` is 0-based as tinyobjloader returns it (relative indices already resolved).
void check_index(const ObjContext& ctx, size_t face, int index, size_t count, bool optional,
                 const char* what, const char* plural) {
  if (optional && index == -1) return;
  if (index < 0)
    fail("{}: a relative {} index points before the first {}", ctx.where(face), what, what);
  if (size_t(index) >= count)
    fail("{}: {} index {} is out of range (the file has {} {})", ctx.where(face), what, index + 1,
         count, plural);
}

// Builds one mesh from a tinyobj shape: de-duplicated (position, normal, uv) vertices and fans
// (0,1,2), (0,2,3), ... over each face.
Mesh build_mesh(ObjContext& ctx, const tinyobj::shape_t& shape, size_t shape_index,
                const std::vector<uint32_t>& material_of, uint32_t default_material,
                bool* used_default) {
  const tinyobj::mesh_t& src = shape.mesh;
  const tinyobj::attrib_t& attrib = ctx.attrib;
  const size_t nv = attrib.vertices.size() / 3;
  const size_t nn = attrib.normals.size() / 3;
  const size_t nt = attrib.texcoords.size() / 2;
  Mesh mesh;
  mesh.name = shape.name;
  while (!mesh.name.empty() && (mesh.name.back() == ' ' || mesh.name.back() == '\t'))
    mesh.name.pop_back();  // tinyobjloader keeps the rest of the "o" line
  if (mesh.name.empty()) mesh.name = fmt::format("shape{}", shape_index);

  // Check every face against the index array and the attribute counts.
  size_t total = 0;
  bool all_normals = true, any_uvs = false;
  for (size_t f = 0; f < src.num_face_vertices.size(); ++f) {
    const size_t count = src.num_face_vertices[f];
    if (count < 3) fail("{}: a face needs at least 3 vertices", ctx.where(f));
    if (total + count > src.indices.size())
      fail("{}: object '{}' has fewer face indices than its faces need", ctx.name, mesh.name);
    for (size_t k = total; k < total + count; ++k) {
      const tinyobj::index_t& i = src.indices[k];
      check_index(ctx, f, i.vertex_index, nv, false, "vertex", "vertices");
      check_index(ctx, f, i.normal_index, nn, true, "normal", "normals");
      check_index(ctx, f, i.texcoord_index, nt, true, "texture coordinate", "texture coordinates");
      all_normals &= i.normal_index >= 0;
      any_uvs |= i.texcoord_index >= 0;
    }
    total += count;
  }
  if (total != src.indices.size())
    fail("{}: object '{}' has {} face indices for faces of {} vertices in all", ctx.name, mesh.name,
         src.indices.size(), total);
  if (src.material_ids.size() != src.num_face_vertices.size())
    fail("{}: object '{}' has {} material ids for {} faces", ctx.name, mesh.name,
         src.material_ids.size(), src.num_face_vertices.size());
  if (!all_normals && nn > 0) {
    bool any = false;
    for (const auto& i : src.indices) any |= i.normal_index >= 0;
    if (any)
      warn(fmt::format("{}: object '{}': only some faces have normals; shading it flat", ctx.name,
                       mesh.name));
  }

  std::unordered_map<VertexKey, uint32_t, VertexKeyHash> ids;
  auto vertex = [&](const tinyobj::index_t& i) {
    const VertexKey key{i.vertex_index, all_normals ? i.normal_index : -1,
                        any_uvs ? i.texcoord_index : -1};
    const auto [it, inserted] = ids.try_emplace(key, uint32_t(mesh.positions.size()));
    if (inserted) {
      const size_t v = size_t(key.v) * 3;
      mesh.positions.push_back(
          {attrib.vertices[v], attrib.vertices[v + 1], attrib.vertices[v + 2]});
      if (all_normals) {
        const size_t n = size_t(key.n) * 3;
        mesh.normals.push_back({attrib.normals[n], attrib.normals[n + 1], attrib.normals[n + 2]});
      }
      if (any_uvs) {
        // A face vertex without a texture coordinate gets (0, 0) so the mesh stays consistent.
        vec2 uv(0.0f, 0.0f);
        if (key.t >= 0) {
          const size_t t = size_t(key.t) * 2;
          uv = vec2(attrib.texcoords[t], 1.0f - attrib.texcoords[t + 1]);  // to top-left origin
        }
        mesh.uvs.push_back(uv);
      }
    }
    return it->second;
  };

  size_t offset = 0;
  for (size_t f = 0; f < src.num_face_vertices.size(); ++f) {
    const size_t count = src.num_face_vertices[f];
    const int mat = src.material_ids[f];
    if (mat < -1 || mat >= int(material_of.size()))
      fail("{}: material index {} is out of range", ctx.where(f), mat);
    uint32_t material = default_material;
    if (mat >= 0) {
      material = material_of[size_t(mat)];
    } else {
      *used_default = true;
    }
    const uint32_t first = vertex(src.indices[offset]);
    uint32_t previous = vertex(src.indices[offset + 1]);
    for (size_t k = 2; k < count; ++k) {
      const uint32_t current = vertex(src.indices[offset + k]);
      mesh.triangles.push_back({first, previous, current});
      mesh.materials.push_back(material);
      previous = current;
    }
    offset += count;
  }
  ctx.face_base += src.num_face_vertices.size();

  // Normals of zero length cannot be normalised: fall back to flat shading for this mesh.
  for (vec3& n : mesh.normals) {
    const float length = glm::length(n);
    if (!(length > 1e-20f)) {
      warn(fmt::format("{}: object '{}' has a zero-length normal; shading it flat", ctx.name,
                       mesh.name));
      mesh.normals.clear();
      break;
    }
    n /= length;
  }
  return mesh;
}

// Passes tinyobjloader's warnings on, except index range warnings (checked with better messages).
void forward_warnings(const std::string& warnings, const std::string& name) {
  std::istringstream lines(warnings);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line == "." || line.find("indices out of bounds") != std::string::npos)
      continue;
    warn(name + ": " + line);
  }
}

// OBJ is ASCII (or UTF-8) text. UTF-16 and binary files would otherwise pass as a file of
// unknown statements and end as "no triangles", which says nothing about the real problem.
void check_text(const std::string& text, const std::string& name) {
  const auto starts = [&](std::string_view prefix) { return text.starts_with(prefix); };
  if (starts("\xFF\xFE") || starts("\xFE\xFF"))
    fail(
        "{}: the file is UTF-16 text; an OBJ must be ASCII or UTF-8 (convert it, e.g. with "
        "iconv -f UTF-16 -t UTF-8)",
        name);
  const size_t nul = text.find('\0');
  if (nul != std::string::npos)
    fail("{}: not a text OBJ: byte {} is a NUL character (UTF-16 or binary data)", name, nul);
}

Scene load_obj_impl(const std::string& obj_text, MtlReader& mtl, bool inline_mtl,
                    const std::string& name) {
  check_text(obj_text, name);
  const ObjScan scan = scan_obj(obj_text, name);
  // OBJ text given with its MTL text but no mtllib line: ask for the MTL so it is still read.
  std::istringstream stream(inline_mtl && !scan.has_mtllib ? "mtllib inline.mtl\n" + obj_text
                                                           : obj_text);

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warnings, errors;
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &stream, &mtl,
                                   /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (!mtl.error().empty()) fail("{}", mtl.error());
  while (!errors.empty() && (errors.back() == '\n' || errors.back() == '.')) errors.pop_back();
  if (!ok) fail("{}: {}", name, errors.empty() ? "cannot parse the OBJ" : errors);
  if (!errors.empty()) fail("{}: {}", name, errors);
  forward_warnings(warnings, name);

  Scene scene;
  scene.source = name;
  std::vector<uint32_t> material_of(materials.size());
  std::map<std::string, int> texture_cache;
  for (size_t i = 0; i < materials.size(); ++i) {
    Material m = convert_material(materials[i], name);
    if (!materials[i].diffuse_texname.empty())
      m.albedo_texture = load_texture(scene, texture_cache, mtl.texture_dir(i),
                                      materials[i].diffuse_texname, m.name, name);
    material_of[i] = uint32_t(scene.materials.size());
    scene.materials.push_back(std::move(m));
  }
  const uint32_t default_material = uint32_t(scene.materials.size());
  bool used_default = false;

  ObjContext ctx{name, attrib, scan};
  size_t face_count = 0;
  for (const auto& s : shapes) face_count += s.mesh.num_face_vertices.size();
  ctx.lines_known = face_count == scan.face_lines.size();
  for (size_t s = 0; s < shapes.size(); ++s) {
    Mesh mesh = build_mesh(ctx, shapes[s], s, material_of, default_material, &used_default);
    if (!mesh.triangles.empty()) scene.meshes.push_back(std::move(mesh));
  }
  if (used_default) {
    Material m;
    m.name = "default";
    m.albedo = vec3(0.8f);
    scene.materials.push_back(m);
  }
  return scene;
}

}  // namespace

Scene load_obj(const std::string& path) {
  check_regular_file(path, "OBJ file");
  std::string text;
  if (!read_file(path, &text)) fail("{}: cannot read the file ({})", path, std::strerror(errno));
  const std::string dir = fs::path(path).parent_path().string();
  MtlReader mtl(dir.empty() ? "." : dir, nullptr, path);
  return load_obj_impl(text, mtl, false, path);
}

Scene load_obj_text(const std::string& obj_text, const std::string& mtl_text,
                    const std::string& name) {
  MtlReader mtl("", &mtl_text, name);
  return load_obj_impl(obj_text, mtl, !mtl_text.empty(), name);
}

}  // namespace bounce
