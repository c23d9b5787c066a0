// bounce info: what a scene holds, and what its acceleration structure costs.
#include <fmt/format.h>

#include "bounce/scene/load.h"
#include "bounce/scene/quake/load_quake.h"
#include "bounce/techniques/registry.h"
#include "bounce/trace/tracer.h"
#include "options.h"

namespace bounce::app {

namespace {

void print_light(const Light& l) {
  const vec3 p = l.position;
  switch (l.type) {
    case LightType::kPoint:
      fmt::print(
          "  point '{}' at ({:.4g}, {:.4g}, {:.4g}), intensity ({:.4g}, {:.4g}, {:.4g}) W/sr\n",
          l.name, p.x, p.y, p.z, l.intensity.x, l.intensity.y, l.intensity.z);
      break;
    case LightType::kSpot:
      fmt::print(
          "  spot '{}' at ({:.4g}, {:.4g}, {:.4g}), intensity ({:.4g}, {:.4g}, {:.4g}) W/sr\n",
          l.name, p.x, p.y, p.z, l.intensity.x, l.intensity.y, l.intensity.z);
      break;
    case LightType::kDirectional:
      fmt::print(
          "  directional '{}' along ({:.4g}, {:.4g}, {:.4g}), irradiance ({:.4g}, {:.4g}, "
          "{:.4g}) W/m^2\n",
          l.name, l.direction.x, l.direction.y, l.direction.z, l.irradiance.x, l.irradiance.y,
          l.irradiance.z);
      break;
    case LightType::kSphere:
      fmt::print(
          "  sphere '{}' at ({:.4g}, {:.4g}, {:.4g}), radius {:.4g}, radiance ({:.4g}, "
          "{:.4g}, {:.4g})\n",
          l.name, p.x, p.y, p.z, l.radius, l.radiance.x, l.radiance.y, l.radiance.z);
      break;
    case LightType::kEnvironment:
      fmt::print(
          "  environment '{}', radiance ({:.4g}, {:.4g}, {:.4g}) times the map's mean ({:.4g}, "
          "{:.4g}, {:.4g}), rotated {:.4g} degrees about +y\n",
          l.name, l.radiance.x, l.radiance.y, l.radiance.z, l.map_mean.x, l.map_mean.y,
          l.map_mean.z, glm::degrees(l.rotation));
      break;
  }
}

// What a Quake 3 map held, beyond what every scene shows.
void print_quake_stats(const quake::QuakeStats& s) {
  fmt::print(
      "map faces   {} polygons, {} patches, {} meshes, {} billboards (skipped); {} not drawn "
      "(sky, nodraw, fog, decals, glows)\n",
      s.faces_by_type[1], s.faces_by_type[2], s.faces_by_type[3], s.faces_by_type[4],
      s.faces_skipped);
  fmt::print("map patches {} Bezier patches, {} triangles\n", s.patches, s.patch_triangles);
  fmt::print("map lights  {} point, {} spot, {} sun; {} glowing shaders\n", s.point_lights,
             s.spot_lights, s.suns, s.surface_light_shaders);
  fmt::print("map images  {} found, {} missing, from {} archives ({} shaders, {} alpha-tested)\n",
             s.textures, s.textures_missing, s.archives, s.shaders, s.cutout_shaders);
  fmt::print("map spawns  {}\n", s.spawn_points);
}

void run_info(const std::string& spec) {
  quake::QuakeStats quake_stats;
  const bool is_map = quake::is_quake_spec(spec);
  const Scene scene = [&] {
    if (!is_map) return load_scene(spec);
    quake::QuakeMap map = quake::load_quake_map(spec);
    quake_stats = map.stats;
    map.scene.source = spec;
    map.scene.finalize();
    return std::move(map.scene);
  }();
  size_t vertices = 0;
  for (const auto& m : scene.meshes) vertices += m.positions.size();
  fmt::print("scene       {}\n", scene.source);
  fmt::print("meshes      {}\n", scene.meshes.size());
  fmt::print("triangles   {}\n", scene.triangle_count());
  fmt::print("vertices    {}\n", vertices);
  fmt::print("materials   {}\n", scene.materials.size());
  fmt::print("textures    {}\n", scene.textures.size());
  const Bounds& b = scene.bounds;
  fmt::print("bounds      ({:.4g}, {:.4g}, {:.4g}) to ({:.4g}, {:.4g}, {:.4g}), diagonal {:.4g}\n",
             b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z, b.diagonal());
  const Camera& c = scene.camera;
  fmt::print(
      "camera      at ({:.4g}, {:.4g}, {:.4g}) looking at ({:.4g}, {:.4g}, {:.4g}), "
      "vertical fov {:.4g} deg\n",
      c.position.x, c.position.y, c.position.z, c.look_at.x, c.look_at.y, c.look_at.z, c.vfov_deg);
  fmt::print("lights      {} (+ {} area lights from emissive triangles)\n", scene.lights.size(),
             scene.area_lights.size());
  if (is_map) print_quake_stats(quake_stats);
  // Levels have hundreds of lights: list the first few.
  constexpr size_t kListed = 12;
  for (size_t i = 0; i < scene.lights.size() && i < kListed; ++i) print_light(scene.lights[i]);
  if (scene.lights.size() > kListed) fmt::print("  ... {} more\n", scene.lights.size() - kListed);
  for (const auto& a : scene.area_lights)
    fmt::print("  area '{}': {} triangles, {:.4g} m^2, radiance ({:.4g}, {:.4g}, {:.4g})\n", a.name,
               a.triangles.size(), a.area, a.radiance.x, a.radiance.y, a.radiance.z);
  // What each technique keeps beyond its per-pixel buffers, at its default parameters: photons,
  // refined meshes, hit buffers (Technique::memory_estimate).
  std::string kept;
  for (const std::string& name : technique_names()) {
    const uint64_t bytes = make_technique(name)->memory_estimate(scene);
    if (bytes > 0)
      kept += fmt::format("{}{} {:.1f} MiB", kept.empty() ? "" : ", ", name,
                          double(bytes) / (1024.0 * 1024.0));
  }
  if (!kept.empty()) fmt::print("memory      {} (technique data at default parameters)\n", kept);
  for (auto [quality, name] :
       {std::pair{BuildQuality::kHigh, "high"}, std::pair{BuildQuality::kLow, "low"}}) {
    const auto tracer = make_embree_tracer(scene, quality);
    const TracerStats s = tracer->stats();
    fmt::print("BVH ({:<4})  {:.2f} MiB, built in {:.1f} ms\n", name,
               double(s.memory_bytes) / (1024.0 * 1024.0), s.build_ms);
  }
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto scene = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("info", "Describe a scene and its acceleration structure");
  cmd->add_option("scene", *scene, "Scene: cornell, cubes:N[:SEED], leak, or a file")->required();
  cmd->callback([scene] { run_info(*scene); });
}

}  // namespace bounce::app
