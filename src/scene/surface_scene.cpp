#include "scene/surface_scene.h"

#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>

#include "scene/scene.h"
#include "scene/scene_json.h"

namespace zs {

using namespace scene_json;

namespace {

glm::dvec3 color3(const Ctx& c, const json& v, const std::string& where) {
  const glm::dvec3 col = vec3(c, v, where);
  for (int k = 0; k < 3; ++k)
    if (!(col[k] >= 0 && col[k] <= 1)) c.fail(where + " components must be in [0, 1]");
  return col;
}

// volume: the scene has a mesh, whose boundary and isosurfaces an entry may be.
SurfaceEntry parse_entry(const Ctx& c, const json& v, const std::string& where, bool volume) {
  SurfaceEntry e;
  if (v.is_string()) {
    e.path = c.resolve(v.get<std::string>());
    return e;
  }
  check_keys(c, v, where, {"path", "boundary", "isosurface", "color", "transform"});
  const int sources = int(v.contains("path")) + int(v.contains("boundary")) + int(v.contains("isosurface"));
  if (sources != 1) c.fail(where + " needs one of 'path', 'boundary' (the mesh's) or 'isosurface' (of its scalar)");
  if (!volume && !v.contains("path"))
    c.fail(where + (v.contains("boundary") ? ".boundary" : ".isosurface") + " is for a volume scene's mesh");
  if (v.contains("boundary")) {
    if (!(v["boundary"].is_boolean() && v["boundary"].get<bool>())) c.fail(where + ".boundary must be true");
    e.source = SurfaceSource::Boundary;
  } else if (v.contains("isosurface")) {
    const json& iso = v["isosurface"];
    if (!iso.is_array() || iso.empty()) c.fail(where + ".isosurface must be a non-empty list of scalar values");
    for (size_t i = 0; i < iso.size(); ++i) e.iso_values.push_back(num(c, iso[i], where + ".isosurface[" + std::to_string(i) + "]"));
    e.source = SurfaceSource::Isosurface;
  } else {
    if (!v["path"].is_string()) c.fail(where + ".path must be a string");
    e.path = c.resolve(v["path"].get<std::string>());
  }
  if (v.contains("color")) e.color = color3(c, v["color"], where + ".color");
  if (v.contains("transform")) {
    const json& t = v["transform"];
    const std::string w = where + ".transform";
    check_keys(c, t, w, {"translate", "rotate_deg", "scale"});
    if (t.contains("translate")) e.translate = vec3(c, t["translate"], w + ".translate");
    if (t.contains("rotate_deg")) e.rotate_deg = vec3(c, t["rotate_deg"], w + ".rotate_deg");
    if (t.contains("scale")) {
      e.scale = num(c, t["scale"], w + ".scale");
      if (!(e.scale > 0)) c.fail(w + ".scale must be positive");
    }
  }
  return e;
}

Light parse_light(const Ctx& c, const json& v, const std::string& where) {
  check_keys(c, v, where, {"type", "direction", "position", "target", "fov_deg"});
  Light l;
  const std::string type = v.contains("type") && v["type"].is_string() ? v["type"].get<std::string>() : "";
  if (type == "directional") {
    l.type = LightType::Directional;
    if (!v.contains("direction")) c.fail(where + ": a directional light needs 'direction'");
    l.direction = vec3(c, v["direction"], where + ".direction");
    if (!(glm::length(l.direction) > 0)) c.fail(where + ".direction must not be zero");
    for (const char* k : {"position", "target", "fov_deg"})
      if (v.contains(k)) c.fail(where + "." + k + " is for spot lights");
  } else if (type == "spot") {
    l.type = LightType::Spot;
    if (!v.contains("position") || !v.contains("target")) c.fail(where + ": a spot light needs 'position' and 'target'");
    if (v.contains("direction")) c.fail(where + ".direction is for directional lights (a spot light has 'target')");
    l.position = vec3(c, v["position"], where + ".position");
    l.target = vec3(c, v["target"], where + ".target");
    if (!(glm::length(l.target - l.position) > 0)) c.fail(where + ".position and .target must differ");
    if (v.contains("fov_deg")) l.fov_deg = num(c, v["fov_deg"], where + ".fov_deg");
    if (!(l.fov_deg > 0 && l.fov_deg <= 170)) c.fail(where + ".fov_deg must be in (0, 170]");
  } else {
    c.fail(where + ".type must be \"directional\" or \"spot\"");
  }
  return l;
}

}  // namespace

void parse_surface_blocks(const Ctx& c, const json& j, Scene* s, bool render_keys) {
  SurfaceScene& ss = s->surfaces;
  const json& v = j["surfaces"];
  if (!v.is_array() || v.empty()) c.fail("surfaces must be a non-empty array of meshes");
  for (size_t i = 0; i < v.size(); ++i)
    ss.surfaces.push_back(parse_entry(c, v[i], "surfaces[" + std::to_string(i) + "]", !render_keys));
  if (j.contains("ground")) {
    const json& g = j["ground"];
    if (g.is_boolean()) {
      ss.ground = g.get<bool>();
      ss.ground_auto_height = true;
    } else {
      check_keys(c, g, "ground", {"height", "color"});
      ss.ground = true;
      ss.ground_auto_height = !g.contains("height");
      if (g.contains("height")) ss.ground_height = num(c, g["height"], "ground.height");
      if (g.contains("color")) ss.ground_color = color3(c, g["color"], "ground.color");
    }
  }
  if (j.contains("lights")) {
    const json& L = j["lights"];
    if (!L.is_array()) c.fail("lights must be an array");
    if (L.size() > 64) c.fail("lights: at most 64");
    ss.has_lights = true;
    for (size_t i = 0; i < L.size(); ++i) ss.lights.push_back(parse_light(c, L[i], "lights[" + std::to_string(i) + "]"));
  }
  if (j.contains("shading")) {
    const json& sh = j["shading"];
    check_keys(c, sh, "shading", {"model", "ambient", "diffuse", "specular", "shininess"});
    SurfaceShading& S = ss.shading;
    if (sh.contains("model")) {
      const std::string m = sh["model"].is_string() ? sh["model"].get<std::string>() : "";
      if (m == "phong") S.model = ShadingModel::Phong;
      else if (m == "flat") S.model = ShadingModel::Flat;
      else c.fail("shading.model must be \"phong\" or \"flat\"");
    }
    auto coef = [&](const char* k, double* out, double hi) {
      if (!sh.contains(k)) return;
      *out = num(c, sh[k], std::string("shading.") + k);
      if (!(*out >= 0 && *out <= hi)) c.fail(std::string("shading.") + k + " must be in [0, " + std::to_string(int(hi)) + "]");
    };
    coef("ambient", &S.ambient, 1);
    coef("diffuse", &S.diffuse, 1);
    coef("specular", &S.specular, 1);
    coef("shininess", &S.shininess, 10000);
  }
  if (j.contains("shadows")) {
    const json& sh = j["shadows"];
    if (sh.is_boolean()) {
      ss.shadows_enabled = sh.get<bool>();
    } else {
      check_keys(c, sh, "shadows", {"map_size", "bias", "slope_bias", "depths", "select", "pcf", "mode", "caster_culling"});
      ShadowSettings& S = ss.shadows;
      auto count = [&](const char* k, uint64_t lo, uint64_t hi, uint32_t* out) {
        if (!sh.contains(k)) return;
        if (!sh[k].is_number_unsigned() || sh[k].get<uint64_t>() < lo || sh[k].get<uint64_t>() > hi)
          c.fail(std::string("shadows.") + k + " must be an integer from " + std::to_string(lo) + " to " +
                 std::to_string(hi));
        *out = sh[k].get<uint32_t>();
      };
      count("map_size", 1, 32768, &S.map_size);
      count("depths", 1, 9, &S.depths);
      count("pcf", 1, 16, &S.pcf);
      if (S.pcf != 1 && S.pcf != 4 && S.pcf != 9 && S.pcf != 16) c.fail("shadows.pcf must be 1, 4, 9 or 16");
      if (sh.contains("bias")) {
        S.bias = num(c, sh["bias"], "shadows.bias");
        if (!(S.bias >= 0)) c.fail("shadows.bias must be >= 0 (world units)");
      }
      if (sh.contains("slope_bias")) {
        S.slope_bias = num(c, sh["slope_bias"], "shadows.slope_bias");
        if (!(S.slope_bias >= 0 && S.slope_bias <= 1000)) c.fail("shadows.slope_bias must be in [0, 1000] (texels)");
      }
      if (sh.contains("select")) {
        const json& x = sh["select"];
        if (!x.is_string() || (x != "max" && x != "min")) c.fail("shadows.select must be \"max\" or \"min\"");
        S.select = x == "max" ? DepthSelect::Max : DepthSelect::Min;
      }
      if (sh.contains("mode")) {
        const json& x = sh["mode"];
        if (!x.is_string() || (x != "map" && x != "exact")) c.fail("shadows.mode must be \"map\" or \"exact\"");
        S.mode = x == "map" ? ShadowMode::Map : ShadowMode::Exact;
      }
      if (sh.contains("caster_culling")) {
        if (!sh["caster_culling"].is_boolean()) c.fail("shadows.caster_culling must be true or false");
        S.cull_casters = sh["caster_culling"].get<bool>();
      }
    }
  }
  if (j.contains("render") && render_keys) {
    const json& r = j["render"];
    check_keys(c, r, "render", {"back_face_culling", "view_culling", "memory_budget_mb"});
    for (const char* k : {"back_face_culling", "view_culling"})
      if (r.contains(k) && !r[k].is_boolean()) c.fail(std::string("render.") + k + " must be true or false");
    if (r.contains("back_face_culling")) ss.cull_back = r["back_face_culling"].get<bool>();
    if (r.contains("view_culling")) ss.cull_view = r["view_culling"].get<bool>();
    if (r.contains("memory_budget_mb"))
      s->settings.memory_budget_bytes = uint64_t(memory_budget_mb(c, r["memory_budget_mb"]) * 1048576.0);
  }
}

SurfaceRenderSettings surface_render_settings(const RenderSettings& common, const SurfaceScene& ss) {
  SurfaceRenderSettings r;
  r.width = common.width;
  r.height = common.height;
  r.tile_size = common.tile_size;
  r.threads = common.threads;
  r.camera = common.camera;
  for (int k = 0; k < 4; ++k) r.background[size_t(k)] = common.background[k];
  r.cull_back = ss.cull_back;
  r.cull_view = ss.cull_view;
  for (const SurfaceEntry& e : ss.surfaces) r.colors.push_back(e.color);
  r.colors.push_back(ss.ground_color);
  r.lights = ss.has_lights ? ss.lights : std::vector<Light>{Light{}};
  r.shading = ss.shading;
  r.shadows = ss.shadows;
  r.shadows_enabled = ss.shadows_enabled;
  r.memory_budget_bytes = common.memory_budget_bytes;
  r.progress = common.progress;
  return r;
}

}  // namespace zs
