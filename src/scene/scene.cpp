#include "scene/scene.h"

#include "lighting/ao_directions.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "scene/scene_json.h"
#include "geometry/spheres/molecule_reader.h"
#include "base/util/input_file.h"
#include "lighting/ao_directions.h"

namespace zs {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;
using namespace scene_json;

std::vector<ColorPoint> paraview_points(const Ctx& c, const json& preset, const std::string& where) {
  const json* p = &preset;
  if (preset.is_array()) {
    if (preset.empty()) c.fail(where + ": empty ParaView preset list");
    p = &preset[0];
  }
  if (!p->is_object() || !p->contains("RGBPoints") || !(*p)["RGBPoints"].is_array())
    c.fail(where + ": not a ParaView colormap preset (no RGBPoints)");
  const json& pts = (*p)["RGBPoints"];
  if (pts.size() % 4 != 0 || pts.empty()) c.fail(where + ": RGBPoints must hold s,r,g,b quadruples");
  std::vector<ColorPoint> out;
  for (size_t i = 0; i < pts.size(); i += 4)
    out.push_back({num(c, pts[i], where), num(c, pts[i + 1], where), num(c, pts[i + 2], where),
                   num(c, pts[i + 3], where)});
  return out;
}

std::vector<ColorPoint> colors(const Ctx& c, const json& v) {
  const std::string where = "transfer_function.color";
  if (v.is_string()) {
    // A ParaView colormap preset file (its first preset).
    const std::string path = c.resolve(v.get<std::string>());
    std::error_code ec;
    if (fs::is_directory(path, ec)) c.fail(where + ": " + path + " is a directory, not a ParaView preset");
    std::ifstream in(path);
    if (!in) c.fail(where + ": cannot open ParaView preset '" + path + "'");
    json preset;
    try {
      preset = json::parse(in);
    } catch (const json::exception& e) {
      c.fail(where + ": " + path + ": invalid JSON: " + e.what());
    }
    return paraview_points(c, preset, where);
  }
  if (v.is_object()) return paraview_points(c, v, where);
  if (!v.is_array()) c.fail(where + " must be [[s,r,g,b],...] or a ParaView preset");
  std::vector<ColorPoint> out;
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string w = where + "[" + std::to_string(i) + "]";
    if (!v[i].is_array() || v[i].size() != 4) c.fail(w + " must be [s, r, g, b]");
    out.push_back({num(c, v[i][0], w), num(c, v[i][1], w), num(c, v[i][2], w), num(c, v[i][3], w)});
  }
  return out;
}

std::vector<OpacityPoint> opacities(const Ctx& c, const json& v) {
  const std::string where = "transfer_function.opacity";
  if (!v.is_array()) c.fail(where + " must be [[s,a],...]");
  std::vector<OpacityPoint> out;
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string w = where + "[" + std::to_string(i) + "]";
    if (!v[i].is_array() || v[i].size() != 2) c.fail(w + " must be [s, a]");
    out.push_back({num(c, v[i][0], w), num(c, v[i][1], w)});
  }
  return out;
}

// spheres.model, .waters and .hydrogens: what is read of a molecule file.
void parse_molecule_keys(const Ctx& c, const json& v, SphereScene* sp) {
  MoleculeOptions& m = sp->molecule;
  for (const char* k : {"model", "waters", "hydrogens"})
    if (v.contains(k) && !is_molecule_file(sp->path))
      c.fail(std::string("spheres.") + k + " applies to molecule files (.pdb, .ent, .cif, .mmcif and their .gz), and " +
             sp->path + " is not one");
  if (v.contains("model")) {
    const json& x = v["model"];
    if (x.is_number_unsigned()) m.model = std::to_string(x.get<uint64_t>());
    else if (x.is_string() && !x.get<std::string>().empty()) m.model = x.get<std::string>();
    else c.fail("spheres.model must be a model number (a whole number or a string, as the file's MODEL record names it)");
  }
  auto flag = [&](const char* k, bool* out) {
    if (!v.contains(k)) return;
    if (!v[k].is_boolean()) c.fail(std::string("spheres.") + k + " must be true or false");
    *out = v[k].get<bool>();
  };
  flag("waters", &m.waters);
  flag("hydrogens", &m.hydrogens);
}

// `spheres`, `shading` and the sphere `render` keys (docs/spheres.md);
// render_keys false: `render` is another renderer's (a volume's).
void parse_spheres_block(const Ctx& c, const json& j, Scene* s, bool render_keys = true) {
  SphereScene& sp = s->spheres;
  const json& v = j["spheres"];
  if (v.is_string()) {
    sp.path = c.resolve(v.get<std::string>());
  } else {
    check_keys(c, v, "spheres", {"path", "radius_scale", "color", "model", "waters", "hydrogens"});
    if (!v.contains("path") || !v["path"].is_string()) c.fail("spheres.path must be a string");
    sp.path = c.resolve(v["path"].get<std::string>());
    parse_molecule_keys(c, v, &sp);
    if (v.contains("radius_scale")) {
      sp.radius_scale = num(c, v["radius_scale"], "spheres.radius_scale");
      if (!(sp.radius_scale > 0) || !std::isfinite(sp.radius_scale)) c.fail("spheres.radius_scale must be positive");
    }
    if (v.contains("color")) {
      if (!v["color"].is_string() || !parse_sphere_color_mode(v["color"].get<std::string>(), &sp.color))
        c.fail("spheres.color must be \"element\", \"chain\", \"residue\", \"scalar\" or \"rgba\"");
      sp.has_color_mode = true;
    }
  }
  if (j.contains("shading")) {
    const json& sh = j["shading"];
    check_keys(c, sh, "shading", {"model", "light_direction", "ambient", "diffuse", "specular", "shininess"});
    Shading& S = sp.shading;
    if (sh.contains("model")) {
      const std::string m = sh["model"].is_string() ? sh["model"].get<std::string>() : "";
      if (m == "phong") S.model = ShadingModel::Phong;
      else if (m == "flat") S.model = ShadingModel::Flat;
      else c.fail("shading.model must be \"phong\" or \"flat\"");
    }
    if (sh.contains("light_direction")) {
      S.light_direction = vec3(c, sh["light_direction"], "shading.light_direction");
      if (!(glm::length(S.light_direction) > 0)) c.fail("shading.light_direction must not be zero");
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
  if (j.contains("ao")) {
    const json& a = j["ao"];
    check_keys(c, a, "ao", {"directions", "map_size", "bias", "depth", "occluders"});
    SphereAo& A = sp.ao;
    A.directions = 66;
    if (a.contains("directions")) {
      const json& d = a["directions"];
      if (!d.is_number_unsigned() || !valid_direction_count(d.get<uint64_t>()) || d.get<uint64_t>() > 16386)
        c.fail("ao.directions must be 6, 18, 66, 258, 1026, 4098 or 16386 (2 + 4^(s+1))");
      A.directions = d.get<uint32_t>();
    }
    if (a.contains("map_size")) {
      const json& m = a["map_size"];
      if (!m.is_number_unsigned() || m.get<uint64_t>() < 16 || m.get<uint64_t>() > 16384)
        c.fail("ao.map_size must be an integer from 16 to 16384");
      A.map_size = m.get<uint32_t>();
    }
    if (a.contains("bias")) {
      A.bias = num(c, a["bias"], "ao.bias");
      if (!(A.bias >= 0) || !std::isfinite(A.bias)) c.fail("ao.bias must be >= 0 (world units)");
    }
    if (a.contains("depth")) {
      const json& d = a["depth"];
      if (!d.is_string() || (d != "disc" && d != "impostor")) c.fail("ao.depth must be \"disc\" or \"impostor\"");
      A.impostor_depth = d == "impostor";
    }
    if (a.contains("occluders")) {
      const json& o = a["occluders"];
      if (!o.is_string() || (o != "opaque" && o != "alpha")) c.fail("ao.occluders must be \"opaque\" or \"alpha\"");
      A.alpha_occluders = o == "alpha";
    }
  }
  if (j.contains("render") && render_keys) {
    const json& r = j["render"];
    check_keys(c, r, "render",
               {"mode", "surfaces", "tolerance", "max_layers", "grid", "culling", "memory_budget_mb"});
    if (r.contains("mode")) {
      if (!r["mode"].is_string() || !parse_sphere_mode(r["mode"].get<std::string>(), &sp.mode))
        c.fail("render.mode must be \"opaque\", \"sorted\", \"peel\", \"dual_peel\" or \"weighted\"");
    }
    if (r.contains("surfaces")) {
      const json& f = r["surfaces"];
      if (!f.is_string() || (f != "both" && f != "front")) c.fail("render.surfaces must be \"both\" or \"front\"");
      sp.front_surfaces_only = f == "front";
    }
    if (r.contains("tolerance")) {
      sp.tolerance = num(c, r["tolerance"], "render.tolerance");
      if (!(sp.tolerance >= 0 && sp.tolerance <= 255)) c.fail("render.tolerance must be in [0, 255]");
    }
    auto count = [&](const char* k, uint32_t lo, uint32_t hi, uint32_t* out) {
      if (!r.contains(k)) return;
      if (!r[k].is_number_unsigned() || r[k].get<uint64_t>() < lo || r[k].get<uint64_t>() > hi)
        c.fail(std::string("render.") + k + " must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
      *out = r[k].get<uint32_t>();
    };
    count("max_layers", 0, 1000000, &sp.max_layers);
    if (r.contains("grid") && r["grid"].is_string()) {
      if (r["grid"] != "auto") c.fail("render.grid must be \"auto\" or an integer from 1 to 64");
    } else {
      count("grid", 1, 64, &sp.grid);  // 64³ cells: 262,144 boxes, a few MiB
    }
    if (r.contains("culling")) {
      if (!r["culling"].is_boolean()) c.fail("render.culling must be true or false");
      sp.culling = r["culling"].get<bool>();
    }
    if (r.contains("memory_budget_mb"))
      s->settings.memory_budget_bytes = uint64_t(memory_budget_mb(c, r["memory_budget_mb"]) * 1048576.0);
  }
}

}  // namespace

namespace {

// A "camera" object over `k`: the keys it names replace k's, then the whole
// camera is checked.
void parse_camera(const Ctx& c, const json& cam, Camera* camera) {
  check_keys(c, cam, "camera", {"projection", "eye", "target", "up", "height", "fov_y"});
  Camera& k = *camera;
  if (cam.contains("projection")) {
    const std::string p = cam["projection"].is_string() ? cam["projection"].get<std::string>() : "";
    if (p == "orthographic") k.projection = Projection::Orthographic;
    else if (p == "perspective") k.projection = Projection::Perspective;
    else c.fail("camera.projection must be \"orthographic\" or \"perspective\"");
  }
  if (cam.contains("eye")) k.eye = vec3(c, cam["eye"], "camera.eye");
  if (cam.contains("target")) k.target = vec3(c, cam["target"], "camera.target");
  if (cam.contains("up")) k.up = vec3(c, cam["up"], "camera.up");
  if (cam.contains("height")) k.height = num(c, cam["height"], "camera.height");
  if (cam.contains("fov_y")) k.fov_y = num(c, cam["fov_y"], "camera.fov_y");
  const glm::dvec3 f = k.target - k.eye;
  if (glm::length(f) == 0) c.fail("camera.eye and camera.target must differ");
  if (glm::length(glm::cross(f, k.up)) <= 1e-12 * glm::length(f) * glm::length(k.up))
    c.fail("camera.up must not be parallel to the view direction");
  if (!(k.height > 0)) c.fail("camera.height must be positive");
  if (!(k.fov_y > 0 && k.fov_y < 180)) c.fail("camera.fov_y must be in (0, 180) degrees");
}

}  // namespace

void parse_camera_json(const std::string& text, const std::string& name, Camera* camera) {
  const Ctx c{name, ""};
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    c.fail(std::string("invalid JSON: ") + e.what());
  }
  parse_camera(c, j, camera);
}

namespace {

// "clip": [{"plane": [nx, ny, nz, d]}, ...] (keep n·x + d <= 0) and
// "crop": [xmin, xmax, ymin, ymax, zmin, zmax], into one region.
void parse_clip(const Ctx& c, const json& j, ClipRegion* out) {
  if (j.contains("clip")) {
    const json& cl = j["clip"];
    if (!cl.is_array()) c.fail("clip must be a list of {\"plane\": [nx, ny, nz, d]}");
    for (size_t i = 0; i < cl.size(); ++i) {
      const std::string w = "clip[" + std::to_string(i) + "]";
      check_keys(c, cl[i], w, {"plane"});
      const json& p = cl[i].contains("plane") ? cl[i]["plane"] : json();
      if (!p.is_array() || p.size() != 4) c.fail(w + ".plane must be [nx, ny, nz, d]");
      const glm::dvec3 n{num(c, p[0], w + ".plane[0]"), num(c, p[1], w + ".plane[1]"), num(c, p[2], w + ".plane[2]")};
      if (n == glm::dvec3(0.0)) c.fail(w + ".plane's normal (nx, ny, nz) must not be zero");
      out->planes.push_back({n, num(c, p[3], w + ".plane[3]")});
    }
  }
  if (j.contains("crop")) {
    const json& b = j["crop"];
    if (!b.is_array() || b.size() != 6) c.fail("crop must be [xmin, xmax, ymin, ymax, zmin, zmax]");
    glm::dvec3 lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = num(c, b[2 * a], "crop[" + std::to_string(2 * a) + "]");
      hi[a] = num(c, b[2 * a + 1], "crop[" + std::to_string(2 * a + 1) + "]");
      if (!(lo[a] <= hi[a])) c.fail("crop's " + std::string(1, char('x' + a)) + "min must not exceed its max");
    }
    out->add_box(lo, hi);
  }
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name, const std::string& base_dir) {
  const Ctx c{name, base_dir};
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    // Syntax errors say "... at line L, column C: ..."; a number too large
    // for a double (1e999) is nlohmann's out_of_range. One line either way.
    c.fail(std::string("invalid JSON: ") + e.what());
  }
  check_keys(c, j, "scene", {"mesh", "spheres", "surfaces", "image", "camera", "transfer_function", "shading", "render",
                             "ground", "lights", "shadows", "ao", "clip", "crop", "clip_geometry"});
  Scene s;
  RenderSettings& rs = s.settings;

  const bool mesh = j.contains("mesh");
  if (j.contains("spheres") && j.contains("surfaces") && !mesh)
    c.fail("a scene has one of 'mesh', 'spheres' or 'surfaces' (or a 'mesh' with either or both of the others)");
  if (!mesh && !j.contains("spheres") && !j.contains("surfaces"))
    c.fail("missing 'mesh' (volume), 'spheres' or 'surfaces'");
  if (!j.contains("surfaces"))
    for (const char* k : {"ground", "lights", "shadows"})
      if (j.contains(k)) c.fail(std::string("'") + k + "' is for surface scenes");
  if (j.contains("ao") && !j.contains("spheres")) c.fail("'ao' is for sphere scenes");
  if (mesh && j.contains("render") && j["render"].is_object() && j["render"].contains("mode") && j.contains("spheres"))
    c.fail("spheres inside a volume are opaque: translucent spheres (render.mode) would need the volume's segments "
           "sorted against every sphere layer, which zsweep does not do");
  if (mesh && (j.contains("surfaces") || j.contains("spheres"))) {
    // A volume with geometry inside: `render` is the volume's. With both
    // kinds, `shading` is shared (light_direction is the spheres' own).
    s.with_surfaces = j.contains("surfaces");
    s.with_spheres = j.contains("spheres");
    if (s.with_surfaces) {
      json js = j;
      if (s.with_spheres && js.contains("shading") && js["shading"].is_object()) js["shading"].erase("light_direction");
      parse_surface_blocks(c, js, &s, false);
    }
    if (s.with_spheres) parse_spheres_block(c, j, &s, false);
  } else if (j.contains("surfaces")) {
    s.kind = SceneKind::Surfaces;
    if (j.contains("transfer_function")) c.fail("'transfer_function' is not for surface scenes");
    parse_surface_blocks(c, j, &s);
  } else if (j.contains("spheres")) {
    s.kind = SceneKind::Spheres;
    parse_spheres_block(c, j, &s);
  } else if (j.contains("shading")) {
    c.fail("'shading' is for sphere and surface scenes");
  }
  const json& m = j.contains("mesh") ? j["mesh"] : json("");
  if (s.kind != SceneKind::Volume) {
    // parsed above
  } else if (m.is_string()) {
    s.mesh_path = c.resolve(m.get<std::string>());
  } else {
    check_keys(c, m, "mesh", {"path", "scalar", "q", "association"});
    if (!m.contains("path") || !m["path"].is_string()) c.fail("mesh.path must be a string");
    s.mesh_path = c.resolve(m["path"].get<std::string>());
    if (m.contains("scalar")) {
      if (!m["scalar"].is_string()) c.fail("mesh.scalar must be a string");
      s.mesh_options.scalar = m["scalar"].get<std::string>();
    }
    if (m.contains("association") &&
        (!m["association"].is_string() ||
         !parse_association(m["association"].get<std::string>(), &s.mesh_options.association)))
      c.fail("mesh.association must be \"auto\", \"point\", \"cell\" or \"cell_to_point\"");
    if (m.contains("q")) {
      if (!m["q"].is_string()) c.fail("mesh.q must be a string");
      s.mesh_options.q_path = c.resolve(m["q"].get<std::string>());
    }
  }

  if (j.contains("image")) {
    const json& im = j["image"];
    check_keys(c, im, "image", {"width", "height", "background"});
    auto dim = [&](const char* k, uint32_t def) -> uint32_t {
      if (!im.contains(k)) return def;
      if (!im[k].is_number_integer() || im[k].get<int64_t>() < 1 || im[k].get<int64_t>() > (int64_t(1) << 20))
        c.fail(std::string("image.") + k + " must be an integer from 1 to 1048576");
      return uint32_t(im[k].get<int64_t>());
    };
    rs.width = dim("width", rs.width);
    rs.height = dim("height", rs.height);
    if (im.contains("background")) {
      const json& b = im["background"];
      if (!b.is_array() || b.size() != 4) c.fail("image.background must be [r, g, b, a]");
      for (int k = 0; k < 4; ++k) rs.background[k] = num(c, b[k], "image.background");
    }
  }

  if (j.contains("camera")) {
    s.has_camera = true;
    parse_camera(c, j["camera"], &rs.camera);
  }

  if (j.contains("transfer_function")) {
    const json& tf = j["transfer_function"];
    check_keys(c, tf, "transfer_function", {"color", "opacity", "unit_distance"});
    if (!tf.contains("color") || !tf.contains("opacity")) c.fail("transfer_function needs 'color' and 'opacity'");
    const double unit = tf.contains("unit_distance") ? num(c, tf["unit_distance"], "transfer_function.unit_distance") : 1.0;
    try {
      rs.tf = TransferFunction(colors(c, tf["color"]), opacities(c, tf["opacity"]), unit);
    } catch (const std::invalid_argument& e) {
      c.fail(e.what());
    }
    s.has_transfer_function = true;
  }

  if (j.contains("clip_geometry")) {
    if (!j["clip_geometry"].is_boolean()) c.fail("clip_geometry must be true or false");
    s.clip_geometry = j["clip_geometry"].get<bool>();
    if (s.clip_geometry && (s.with_spheres || !s.with_surfaces))
      c.fail(s.with_spheres ? "clip_geometry cuts surfaces; spheres are not cut (drop it, or the spheres)"
                            : "clip_geometry is for a volume scene with surfaces (the planes always cut the volume)");
  }
  if (j.contains("clip") || j.contains("crop")) {
    if (s.kind != SceneKind::Volume) c.fail(std::string("'") + (j.contains("clip") ? "clip" : "crop") + "' is for volume scenes");
    parse_clip(c, j, &rs.clip);
  }

  if (j.contains("render") && s.kind == SceneKind::Volume) {
    const json& r = j["render"];
    check_keys(c, r, "render",
               {"scan", "bconvert_variant", "integrator", "precision", "early_termination", "max_list_length",
                "memory_budget_mb"});
    if (r.contains("bconvert_variant")) {
      if (!r["bconvert_variant"].is_string() ||
          !parse_bconvert_variant(r["bconvert_variant"].get<std::string>(), &rs.bconvert_variant))
        c.fail("render.bconvert_variant must be \"truncate\", \"round\", \"dilate\", \"dda3d\" or \"runlength\"");
    }
    if (r.contains("scan")) {
      if (!r["scan"].is_string() || !parse_scan_strategy(r["scan"].get<std::string>(), &rs.scan))
        c.fail("render.scan must be \"bbox\", \"bconvert\" or \"span\"");
    }
    if (r.contains("integrator")) {
      if (!r["integrator"].is_string() || !parse_integrator(r["integrator"].get<std::string>(), &rs.integrator))
        c.fail("render.integrator must be \"exact\", \"linear\", \"preintegrated\" or \"taylor2\"");
    }
    if (r.contains("precision")) {
      const json& p = r["precision"];
      if (!p.is_string() || (p != "double" && p != "single")) c.fail("render.precision must be \"double\" or \"single\"");
      rs.single_precision = p == "single";
    }
    if (r.contains("early_termination")) {
      rs.early_termination = num(c, r["early_termination"], "render.early_termination");
      if (rs.early_termination < 0 || rs.early_termination > 255) c.fail("render.early_termination must be in [0, 255]");
    }
    if (r.contains("max_list_length")) {
      if (!r["max_list_length"].is_number_unsigned() || r["max_list_length"].get<uint64_t>() > UINT32_MAX)
        c.fail("render.max_list_length must be an integer from 0 to 4294967295");
      rs.max_list_length = r["max_list_length"].get<uint32_t>();
    }
    if (r.contains("memory_budget_mb")) {
      rs.memory_budget_bytes = uint64_t(memory_budget_mb(c, r["memory_budget_mb"]) * 1048576.0);
    }
  }
  return s;
}

SphereRenderSettings sphere_render_settings(const RenderSettings& common, const SphereScene& sp) {
  SphereRenderSettings r;
  r.width = common.width, r.height = common.height;
  for (int k = 0; k < 4; ++k) r.background[k] = common.background[k];
  r.camera = common.camera;
  r.shading = sp.shading;
  r.ao = sp.ao;
  r.mode = sp.mode;
  r.front_surfaces_only = sp.front_surfaces_only;
  r.tolerance = sp.tolerance;
  r.max_layers = sp.max_layers;
  r.grid = sp.grid;
  r.culling = sp.culling;
  r.threads = common.threads;
  r.tile_size = common.tile_size;
  r.memory_budget_bytes = common.memory_budget_bytes;
  r.progress = common.progress;
  return r;
}

Scene load_scene(const std::string& path) {
  require_input_file(path, "a scene file");
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open scene file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), path, fs::path(path).parent_path().string());
}

}  // namespace zs
