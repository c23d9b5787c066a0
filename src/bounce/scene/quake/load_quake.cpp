#include "bounce/scene/quake/load_quake.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "bounce/core/error.h"
#include "bounce/core/input_file.h"
#include "bounce/scene/quake/bsp.h"
#include "bounce/scene/quake/entities.h"
#include "bounce/scene/quake/map_lights.h"
#include "bounce/scene/quake/map_textures.h"
#include "bounce/scene/quake/patch.h"
#include "bounce/scene/quake/pk3.h"
#include "bounce/scene/quake/units.h"

namespace bounce::quake {

namespace {

namespace fs = std::filesystem;

constexpr vec3 kMissingGrey{0.5f};
constexpr size_t kMaxBspBytes = kMaxEntryBytes;

std::string lower(std::string s) {
  for (char& c : s) c = (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c;
  return s;
}

// "A.pk3:maps/x.bsp" -> ("A.pk3", "maps/x.bsp"); a bare path gives an empty entry.
std::pair<std::string, std::string> split_spec(const std::string& spec) {
  const std::string l = lower(spec);
  const size_t at = l.rfind(".pk3:");
  if (at == std::string::npos) return {spec, ""};
  return {spec.substr(0, at + 4), spec.substr(at + 5)};
}

std::vector<uint8_t> read_file_bytes(const std::string& path) {
  check_regular_file(path, "map");
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) fail("{}: cannot read its size: {}", path, ec.message());
  if (size > kMaxBspBytes)
    fail("{}: {} bytes is larger than the {} a map may have", path, size, kMaxBspBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open", path);
  std::vector<uint8_t> bytes(size);
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size));
  if (!in) fail("{}: cannot read", path);
  return bytes;
}

// Why a face is not drawn, or null when it is.
// Skies are holes: their sun (q3map_sun), if any, shines through as a directional light. A
// sky's own glow (q3map_surfacelight) is dropped: kept as an emitter it would be seen as a
// glowing wall, not as the sky box the game draws. A fog volume's surface is drawn only when
// its shader has stages (lava and slime are fog volumes too).
const char* skip_reason(const BspTexture& t, const ShaderInfo* s) {
  if (t.surface_flags & kSurfSky || (s && s->sky)) return "sky";
  if (t.surface_flags & (kSurfNoDraw | kSurfHint | kSurfSkip) || (s && s->nodraw)) return "nodraw";
  if ((t.content_flags & kContentsFog || (s && s->fog)) && !(s && s->stages > 0)) return "fog";
  if (s && s->decal) return "decal";
  if (s && s->additive) return "glow";
  return nullptr;
}

struct Builder {
  const BspFile& bsp;
  const QuakeOptions& options;
  const Pk3Set* archives;
  const ShaderTable& shaders;
  Scene& scene;
  QuakeStats& stats;
  std::vector<int> material_of_texture;  // -1: not created yet
  std::vector<std::string> missing;

  const ShaderInfo* shader(int texture) const {
    const auto it = shaders.find(lower(bsp.textures[size_t(texture)].name));
    return it == shaders.end() ? nullptr : &it->second;
  }

  uint32_t material(int texture) {
    int& m = material_of_texture[size_t(texture)];
    if (m >= 0) return uint32_t(m);
    const std::string& name = bsp.textures[size_t(texture)].name;
    const ShaderInfo* s = shader(texture);
    Material mat;
    mat.name = name;
    mat.albedo = kMissingGrey;
    SurfaceImage image;
    const bool alpha_tested = s && s->alpha_test != AlphaTest::kNone;
    if (archives)
      image = find_surface_image(*archives, s, name, options.max_texture_size, alpha_tested);
    if (image.found && alpha_tested) add_cutout(mat, *s, std::move(image.alpha));
    if (image.found) {
      if (options.full_textures) {
        mat.albedo = vec3(1.0f);
        mat.albedo_texture = int(scene.textures.size());
        scene.textures.push_back(std::move(image.texture));
      } else {
        mat.albedo = glm::clamp(image.average, 0.0f, 1.0f);
      }
      ++stats.textures;
    } else {
      missing.push_back(name);
      ++stats.textures_missing;
    }
    if (s && s->surface_light > 0.0f && std::isfinite(s->surface_light)) {
      // The light takes the colour of its light image (q3map_lightimage), else of its texture.
      vec3 colour = image.average;
      if (archives && !s->light_image.empty()) {
        const SurfaceImage li = find_surface_image(*archives, nullptr, s->light_image, 16);
        if (li.found) colour = li.average;
      }
      mat.emission =
          normalized_colour(colour) * surface_radiance(s->surface_light) * options.light_scale;
      ++stats.surface_light_shaders;
    }
    m = int(scene.materials.size());
    scene.materials.push_back(std::move(mat));
    return uint32_t(m);
  }

  // An alphaFunc stage's holes as a glTF-style MASK cut-out on the image's alpha (the grates and
  // foliage every ray passes through). LT128 keeps the texels GE128 drops, which a cut-off
  // below which alpha is a hole cannot say; no OpenArena shader uses it, so it stays opaque.
  void add_cutout(Material& mat, const ShaderInfo& s, Texture alpha) {
    if (alpha.texels.empty()) return;  // an image without alpha: nothing is cut away
    if (s.alpha_test == AlphaTest::kBelowHalf) {
      warn(fmt::format("{}: shader '{}': alphaFunc LT128 is not supported; the surface is opaque",
                       scene.source, mat.name));
      return;
    }
    mat.alpha_mode = AlphaMode::kMask;
    // GT0 keeps alpha > 0, GE128 keeps alpha >= 128/255; below the cut-off is a hole.
    mat.alpha_cutoff =
        s.alpha_test == AlphaTest::kGreaterThanZero ? 0.5f / 255.0f : 128.0f / 255.0f;
    mat.alpha_texture = int(scene.textures.size());
    scene.textures.push_back(std::move(alpha));
    ++stats.cutout_shaders;
  }

  void add_vertex(Mesh& mesh, vec3 position, vec3 normal, vec3 fallback_normal, vec2 uv) {
    mesh.positions.push_back(point_from_quake(position));
    const float length = glm::length(normal);
    vec3 n = length > 1e-6f ? normal / length : fallback_normal;
    mesh.normals.push_back(direction_from_quake(n));
    mesh.uvs.push_back(uv);
  }

  // Polygons and meshes: triangles over the face's vertices through the mesh vertex list. Quake
  // winds front faces clockwise; ours are anticlockwise, so two corners swap.
  void add_triangles(Mesh& mesh, const BspFace& f, uint32_t mat) {
    const uint32_t base = uint32_t(mesh.positions.size());
    const vec3 face_normal = glm::length(vec3(f.normal[0], f.normal[1], f.normal[2])) > 1e-6f
                                 ? glm::normalize(vec3(f.normal[0], f.normal[1], f.normal[2]))
                                 : vec3(0, 0, 1);
    for (int32_t i = 0; i < f.vertex_count; ++i) {
      const BspVertex& v = bsp.vertices[size_t(f.first_vertex + i)];
      add_vertex(mesh, vec3(v.position[0], v.position[1], v.position[2]),
                 vec3(v.normal[0], v.normal[1], v.normal[2]), face_normal, vec2(v.uv[0], v.uv[1]));
    }
    for (int32_t k = 0; k + 2 < f.mesh_vertex_count; k += 3) {
      const int32_t* m = &bsp.mesh_vertices[size_t(f.first_mesh_vertex + k)];
      mesh.triangles.push_back(
          uvec3(base + uint32_t(m[0]), base + uint32_t(m[2]), base + uint32_t(m[1])));
      mesh.materials.push_back(mat);
    }
  }

  void add_patch(Mesh& mesh, const BspFace& f, uint32_t mat) {
    PatchMesh patch;
    tessellate_patch(
        std::span(bsp.vertices).subspan(size_t(f.first_vertex), size_t(f.vertex_count)),
        f.patch_size[0], f.patch_size[1], options.patch_level, patch);
    stats.patches += size_t((f.patch_size[0] - 1) / 2) * size_t((f.patch_size[1] - 1) / 2);
    const uint32_t base = uint32_t(mesh.positions.size());
    for (const auto& v : patch.vertices)
      add_vertex(mesh, v.position, v.normal, vec3(0, 0, 1), v.uv);
    for (const auto& t : patch.triangles) {
      const vec3 a = mesh.positions[base + t[0]], b = mesh.positions[base + t[1]],
                 c = mesh.positions[base + t[2]];
      if (glm::length(glm::cross(b - a, c - a)) == 0.0f) continue;  // collapsed control rows
      mesh.triangles.push_back(uvec3(base + t[0], base + t[1], base + t[2]));
      mesh.materials.push_back(mat);
      ++stats.patch_triangles;
    }
  }

  void add_face(Mesh& mesh, size_t index) {
    const BspFace& f = bsp.faces[index];
    ++stats.faces_by_type[size_t(std::clamp(f.type, 0, 4))];
    if (FaceType(f.type) == FaceType::kBillboard) return;  // flares: no surface
    if (skip_reason(bsp.textures[size_t(f.texture)], shader(f.texture))) {
      ++stats.faces_skipped;
      return;
    }
    const uint32_t mat = material(f.texture);
    if (FaceType(f.type) == FaceType::kPatch)
      add_patch(mesh, f, mat);
    else
      add_triangles(mesh, f, mat);
  }
};

void warn_missing(const std::string& name, const std::vector<std::string>& missing, size_t total) {
  if (missing.empty()) return;
  std::string list;
  for (size_t i = 0; i < std::min<size_t>(missing.size(), 5); ++i)
    list += (i ? ", " : "") + missing[i];
  if (missing.size() > 5) list += ", ...";
  warn(fmt::format("{}: {} of {} textures not found in the archives ({}); those surfaces are grey",
                   name, missing.size(), total, list));
}

}  // namespace

bool is_quake_spec(const std::string& spec) {
  const std::string l = lower(spec);
  return l.find(".pk3:") != std::string::npos || l.ends_with(".bsp");
}

QuakeMap load_quake_bsp(std::span<const uint8_t> bytes, const std::string& name,
                        const QuakeOptions& options, const Pk3Set* archives) {
  if (options.patch_level < 1 || options.patch_level > kMaxPatchLevel)
    fail("{}: patch level {} is outside [1, {}]", name, options.patch_level, kMaxPatchLevel);
  const BspFile bsp = parse_bsp(bytes, name);
  const std::vector<Entity> entities = parse_entities(bsp.entities, name);

  QuakeMap out;
  Scene& scene = out.scene;
  QuakeStats& stats = out.stats;
  scene.source = name;
  ShaderTable shaders;
  if (archives) {
    shaders = read_shaders(*archives, nullptr);
    stats.archives = archives->archives().size();
  }
  stats.shaders = shaders.size();

  Builder b{
      bsp, options, archives, shaders, scene, stats, std::vector<int>(bsp.textures.size(), -1), {}};
  // Model 0 is the world; the others are brush entities (doors, platforms), shown where the
  // map places them. Faces no model claims are drawn with the world.
  std::vector<int> model_of_face(bsp.faces.size(), 0);
  for (size_t m = 1; m < bsp.models.size(); ++m)
    for (int32_t i = 0; i < bsp.models[m].face_count; ++i)
      model_of_face[size_t(bsp.models[m].first_face + i)] = int(m);
  const size_t model_count = std::max<size_t>(bsp.models.size(), 1);
  for (size_t m = 0; m < model_count; ++m) {
    Mesh mesh;
    mesh.name = m == 0 ? "world" : fmt::format("model{}", m);
    for (size_t i = 0; i < bsp.faces.size(); ++i)
      if (size_t(model_of_face[i]) == m) b.add_face(mesh, i);
    stats.triangles += mesh.triangles.size();
    if (!mesh.triangles.empty()) scene.meshes.push_back(std::move(mesh));
  }
  warn_missing(name, b.missing, stats.textures + stats.textures_missing);

  EntityLights lights = entity_lights(entities, options.light_scale);
  stats.point_lights = lights.point;
  stats.spot_lights = lights.spot;
  stats.suns = lights.sun;
  scene.lights = std::move(lights.lights);
  // Suns of the sky shaders the map uses (q3map_sun): directional lights.
  std::vector<bool> seen(bsp.textures.size(), false);
  for (const auto& f : bsp.faces) {
    if (seen[size_t(f.texture)]) continue;
    seen[size_t(f.texture)] = true;
    const ShaderInfo* s = b.shader(f.texture);
    if (!s || !s->sun || !(s->sun->intensity > 0.0f)) continue;
    const float az = glm::radians(s->sun->azimuth_deg), el = glm::radians(s->sun->elevation_deg);
    const vec3 towards(std::cos(az) * std::cos(el), std::sin(az) * std::cos(el), std::sin(el));
    Light sun = Light::directional(direction_from_quake(-towards),
                                   normalized_colour(s->sun->colour) *
                                       sun_irradiance(s->sun->intensity) * options.light_scale);
    sun.name = "sun:" + bsp.textures[size_t(f.texture)].name;
    if (is_finite(sun.irradiance) && is_finite(sun.direction)) {
      scene.lights.push_back(sun);
      ++stats.suns;
    }
  }

  const std::vector<const Entity*> spawns = spawn_points(entities);
  stats.spawn_points = spawns.size();
  if (options.spawn < 0 || (!spawns.empty() && size_t(options.spawn) >= spawns.size()))
    fail("{}: spawn point {} does not exist (the map has {})", name, options.spawn, spawns.size());
  if (!spawns.empty()) {
    scene.camera = spawn_camera(*spawns[size_t(options.spawn)]);
    scene.has_camera = true;
  }
  return out;
}

QuakeMap load_quake_map(const std::string& spec, const QuakeOptions& options) {
  const auto [archive_path, entry] = split_spec(spec);
  Pk3Set archives;
  for (const auto& a : options.archives) archives.add(Pk3Archive(a));
  std::vector<uint8_t> bytes;
  if (!entry.empty()) {
    Pk3Archive map_archive(archive_path);
    bytes = map_archive.read(entry);
    archives.add(std::move(map_archive));
    if (options.sibling_archives) {
      std::vector<fs::path> siblings;
      std::error_code ec;
      const fs::path dir = fs::absolute(fs::path(archive_path), ec).parent_path();
      for (const auto& e : fs::directory_iterator(dir, ec))
        if (lower(e.path().extension().string()) == ".pk3" &&
            !fs::equivalent(e.path(), archive_path, ec))
          siblings.push_back(e.path());
      std::sort(siblings.rbegin(), siblings.rend());
      for (const auto& s : siblings) {
        try {
          archives.add(Pk3Archive(s.string()));
        } catch (const Error& e) {
          warn(fmt::format("{} (skipped)", e.what()));
        }
      }
    }
  } else {
    bytes = read_file_bytes(archive_path);
  }
  return load_quake_bsp(bytes, spec, options, archives.archives().empty() ? nullptr : &archives);
}

}  // namespace bounce::quake
