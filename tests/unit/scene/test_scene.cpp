#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "output/image_io.h"
#include "geometry/tets/io/off_io.h"
#include "scene/scene.h"
#include "scene/scene_input.h"
#include "base/optics/transfer_function.h"
#include "support/test_paths.h"

namespace zs {
namespace {

std::string error_of(const std::string& json) {
  try {
    parse_scene(json, "s.json", "/base");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, ParsesEveryKey) {
  const Scene s = parse_scene(R"({
    "mesh": {"path": "m.off", "scalar": "Density", "q": "q.bin"},
    "image": {"width": 320, "height": 200, "background": [0.1, 0.2, 0.3, 1]},
    "camera": {"projection": "perspective", "eye": [1,2,3], "target": [0,0,0], "up": [0,0,1],
               "height": 2.5, "fov_y": 45},
    "transfer_function": {"color": [[0,1,0,0],[1,0,0,1]], "opacity": [[0,0],[1,0.5]], "unit_distance": 2},
    "render": {"scan": "bbox", "integrator": "linear", "precision": "single", "early_termination": 4}
  })", "s.json", "/base");
  EXPECT_EQ(s.mesh_path, "/base/m.off");
  EXPECT_EQ(s.mesh_options.q_path, "/base/q.bin");
  EXPECT_EQ(s.mesh_options.scalar, "Density");
  EXPECT_EQ(s.settings.width, 320u);
  EXPECT_EQ(s.settings.camera.projection, Projection::Perspective);
  EXPECT_EQ(s.settings.camera.up.z, 1.0);
  EXPECT_EQ(s.settings.integrator, Integrator::Linear);
  EXPECT_TRUE(s.settings.single_precision);
  EXPECT_EQ(s.settings.early_termination, 4.0);
  EXPECT_DOUBLE_EQ(s.settings.tf.opacity(0.5), 0.25);
  EXPECT_DOUBLE_EQ(s.settings.tf.unit_distance(), 2.0);
  EXPECT_TRUE(s.has_camera);
}

TEST(Scene, RejectsBadInputWithOneLine) {
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "camrea": {}})"),
            "s.json: unknown key 'scene.camrea' (allowed: mesh, spheres, surfaces, image, camera, transfer_function, shading, render, ground, lights, shadows, ao, clip, crop, clip_geometry)");
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "render": {"scan": "zigzag"}})"),
            "s.json: render.scan must be \"bbox\", \"bconvert\" or \"span\"");
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "render": {"precision": "half"}})"),
            "s.json: render.precision must be \"double\" or \"single\"");
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "transfer_function": {"color": [[1,0,0,0],[0,1,1,1]], "opacity": [[0,1]]}})"),
            "s.json: transfer_function.color: points must be strictly increasing in the scalar (point 1 is out of order)");
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "transfer_function": {"color": [[0,0,0,0]], "opacity": [[0,1],[0,0.5]]}})"),
            "s.json: transfer_function.opacity: points must be strictly increasing in the scalar (point 1 is a duplicate)");
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "camera": {"eye": [0,0,1], "target": [0,0,1]}})"),
            "s.json: camera.eye and camera.target must differ");
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "image": {"width": 0}})"),
            "s.json: image.width must be an integer from 1 to 1048576");
  EXPECT_NE(error_of("{\"mesh\": \n 3,"), "");
  EXPECT_NE(error_of("{\"mesh\": \n 3,").find("s.json: invalid JSON"), std::string::npos);
}

TEST(Scene, ClipPlanesCropAndAssociation) {
  const Scene s = parse_scene(R"({
    "mesh": {"path": "m.vtu", "association": "cell_to_point"},
    "clip": [{"plane": [0, 0, 2, -1]}, {"plane": [1, 1, 0, -0.5]}],
    "crop": [-1, 1, -2, 2, 0, 3]
  })", "s.json", "/base");
  EXPECT_EQ(s.mesh_options.association, ScalarAssociation::CellToPoint);
  ASSERT_EQ(s.settings.clip.planes.size(), 8u);
  EXPECT_EQ(s.settings.clip.planes[0].n, glm::dvec3(0, 0, 2));
  EXPECT_EQ(s.settings.clip.planes[0].d, -1.0);
  double t0, t1;  // the z axis keeps z in [0, 0.5] (clip[0]) within the crop
  ASSERT_TRUE(s.settings.clip.interval({0, 0, -5}, {0, 0, 1}, &t0, &t1));
  EXPECT_DOUBLE_EQ(t0, 5.0);
  EXPECT_DOUBLE_EQ(t1, 5.5);
  EXPECT_FALSE(s.settings.clip.interval({5, 0, -5}, {0, 0, 1}, &t0, &t1));  // outside the crop's x
  const glm::dvec3 out[4] = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0, 0, 2}};  // all at z >= 0.5
  EXPECT_TRUE(s.settings.clip.excludes(out, 4));
  const glm::dvec3 in[4] = {{0, 0, 0.1}, {1, 0, 1}, {0, 1, 1}, {0, 0, 2}};
  EXPECT_FALSE(s.settings.clip.excludes(in, 4));

  EXPECT_EQ(error_of(R"({"mesh": "a.off", "clip": [{"plane": [0, 0, 0, 1]}]})"),
            "s.json: clip[0].plane's normal (nx, ny, nz) must not be zero");
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "clip": [{"plane": [0, 0, 1]}]})"),
            "s.json: clip[0].plane must be [nx, ny, nz, d]");
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "clip": {"plane": [0, 0, 1, 0]}})"),
            "s.json: clip must be a list of {\"plane\": [nx, ny, nz, d]}");
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "crop": [1, 0, 0, 1, 0, 1]})"), "s.json: crop's xmin must not exceed its max");
  EXPECT_EQ(error_of(R"({"mesh": "a.off", "crop": [0, 1]})"), "s.json: crop must be [xmin, xmax, ymin, ymax, zmin, zmax]");
  EXPECT_EQ(error_of(R"({"spheres": "a.pdb", "crop": [0, 1, 0, 1, 0, 1]})"), "s.json: 'crop' is for volume scenes");
  EXPECT_EQ(error_of(R"({"mesh": {"path": "a.vtu", "association": "cells"}})"),
            "s.json: mesh.association must be \"auto\", \"point\", \"cell\" or \"cell_to_point\"");
}

TEST(Scene, AcceptsParaViewPresetForColour) {
  const auto dir = test::scratch_dir();
  {
    std::ofstream f(dir / "cool.json");
    f << R"([{"Name": "Cool", "ColorSpace": "RGB", "RGBPoints": [0, 0, 0, 1, 10, 1, 0, 0]}])";
  }
  {
    std::ofstream f(dir / "scene.json");
    f << R"({"mesh": "m.off", "transfer_function": {"color": "cool.json", "opacity": [[0, 0.5]]}})";
  }
  const Scene s = load_scene((dir / "scene.json").string());
  EXPECT_DOUBLE_EQ(s.settings.tf.color(5)[0], 0.5);
  EXPECT_DOUBLE_EQ(s.settings.tf.color(5)[2], 0.5);
  // Inline preset object too.
  const Scene t = parse_scene(R"({"mesh": "m.off", "transfer_function":
      {"color": {"RGBPoints": [0, 1, 1, 1, 1, 0, 0, 0]}, "opacity": [[0, 0.5]]}})", "t.json", "");
  EXPECT_DOUBLE_EQ(t.settings.tf.color(0.25)[1], 0.75);
}

TEST(ImageIo, ExrIsFloatAndPngIsQuantizedWithoutGamma) {
  const auto dir = test::scratch_dir();
  Image img(3, 2);
  for (size_t k = 0; k < img.rgba.size(); ++k) img.rgba[k] = float(k) / 23.0f;
  write_image((dir / "a.exr").string(), img);
  write_image((dir / "a.png").string(), img);
  write_image((dir / "a.tif").string(), img);
  const Image exr = read_image((dir / "a.exr").string());
  const Image tif = read_image((dir / "a.tif").string());
  const Image png = read_image((dir / "a.png").string());
  for (size_t k = 0; k < img.rgba.size(); ++k) {
    EXPECT_EQ(exr.rgba[k], img.rgba[k]);
    EXPECT_EQ(tif.rgba[k], img.rgba[k]);
    // PNG holds straight alpha (pixel_quantize.h): colour/α and α are each
    // rounded to 1/510, so the premultiplied colour read back is within
    // α/510 + (colour/α)/510 <= 1/255 (here colour <= α in every pixel).
    EXPECT_NEAR(png.rgba[k], img.rgba[k], (k % 4 == 3 ? 0.5 : 1.0) / 255 + 1e-6);
  }
  EXPECT_THROW(write_image((dir / "nodir" / "x.png").string(), img), std::runtime_error);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 3);
}

}  // namespace
}  // namespace zs

#include "output/image_compare.h"

namespace zs {
namespace {

TEST(ImageCompare, NumbersAndDifferenceImage) {
  Image a(4, 2), b(4, 2);
  for (size_t k = 0; k < a.rgba.size(); ++k) a.rgba[k] = b.rgba[k] = 0.5f;
  ImageDiff same = compare_images(a, b);
  EXPECT_EQ(same.max_abs, 0.0);
  EXPECT_TRUE(std::isinf(same.psnr));
  b.at(3, 1)[2] = 0.5f + 0.1f;  // one channel of one pixel
  b.at(0, 0)[0] = 0.5f + 0.5f / 255.0f;  // below the 1/255 threshold
  const ImageDiff d = compare_images(a, b);
  EXPECT_NEAR(d.max_abs, 0.1, 1e-6);
  EXPECT_EQ(d.worst_x, 3u);
  EXPECT_EQ(d.worst_y, 1u);
  EXPECT_EQ(d.pixels_over_1_255, 1u);
  EXPECT_NEAR(d.rmse, std::sqrt((0.01 + std::pow(0.5 / 255.0, 2)) / 32.0), 1e-6);
  const Image f = difference_image(a, b, 0.1);
  EXPECT_FLOAT_EQ(f.at(3, 1)[0], 1.f);  // full red at the scale
  EXPECT_FLOAT_EQ(f.at(1, 0)[0] + f.at(1, 0)[1] + f.at(1, 0)[2], 0.f);
  EXPECT_THROW(compare_images(a, Image(2, 2)), std::invalid_argument);
}

// --rgb: alpha differs (an image without alpha reads as opaque), colour counts.
TEST(ImageCompare, ColourOnlyIgnoresAlpha) {
  Image a(2, 2), b(2, 2);
  for (size_t k = 0; k < a.rgba.size(); ++k) a.rgba[k] = b.rgba[k] = 0.25f;
  for (size_t p = 0; p < 4; ++p) b.rgba[p * 4 + 3] = 1.0f;
  b.at(1, 0)[1] = 0.25f + 0.02f;
  const ImageDiff all = compare_images(a, b);
  EXPECT_NEAR(all.max_abs, 0.75, 1e-6);
  EXPECT_EQ(all.pixels_over_1_255, 4u);
  const ImageDiff rgb = compare_images(a, b, 3);
  EXPECT_NEAR(rgb.max_abs, 0.02, 1e-6);
  EXPECT_EQ(rgb.worst_x, 1u);
  EXPECT_EQ(rgb.pixels_over_1_255, 1u);
  EXPECT_NEAR(rgb.rmse, std::sqrt(0.02 * 0.02 / 12.0), 1e-6);
  const Image f = difference_image(a, b, 0.02, 3);
  EXPECT_FLOAT_EQ(f.at(1, 0)[0], 1.f);
  EXPECT_FLOAT_EQ(f.at(0, 1)[0] + f.at(0, 1)[1] + f.at(0, 1)[2], 0.f);
  EXPECT_THROW(compare_images(a, b, 2), std::invalid_argument);
}

}  // namespace
}  // namespace zs

namespace zs {
namespace {

// Per-tet culling (face_classes.cpp) asks transparent_over; it must agree
// with the direct definition (max_opacity == 0) on every range, including
// ranges touching a run's ends, single points and ranges outside the points.
// Points closer than 1/width can represent are refused; the default ramp
// widens such a range instead of building one (both fuzzing findings: every
// lookup between subnormally spaced points was NaN, and the exact
// integrator spent seconds per segment splitting NaN).
TEST(TransferFunction, RefusesSubnormalSpacingAndDefaultRampWidens) {
  EXPECT_THROW(TransferFunction({{0, 0, 0, 0}, {1e-310, 1, 1, 1}}, {{0, 0.5}}), std::invalid_argument);
  EXPECT_NO_THROW(TransferFunction({{0, 0, 0, 0}, {1e-300, 1, 1, 1}}, {{0, 0.5}}));
  TetMesh m = parse_off("4 1\n0 0 0 0\n9 0 11 1e-308\n0 1 0 0\n0 0 1 0\n0 1 2 3\n", "mem");
  const TransferFunction tf = default_transfer_function(m);
  for (double s : {0.0, 1e-308, 0.5})
    for (double v : tf.rgba(s)) EXPECT_TRUE(std::isfinite(v)) << s;
  EXPECT_GT(tf.opacity(0.0), 0.0);  // mid-ramp: a nearly constant field shows
  // Scalars at the ends of the double range: a finite ramp, finite values.
  m.scalars = {-1.7e308, 1.7e308, 0, 1};
  const TransferFunction wide = default_transfer_function(m);
  for (double s : {-1.7e308, 0.0, 1.7e308})
    for (double v : wide.rgba(s)) EXPECT_TRUE(std::isfinite(v)) << s;
}

// Extents the automatic camera cannot frame are an error, not a NaN camera.
TEST(Scene, AutoCameraRefusesExtremeExtents) {
  TetMesh m = parse_off("4 1\n0 0 0 0\n1e-300 0 0 1\n0 1e-300 0 2\n0 0 1e-300 3\n0 1 2 3\n", "mem");
  EXPECT_THROW(auto_camera(m, Projection::Orthographic, 8, 8), std::runtime_error);
  m.points = {{0, 0, 0}, {1e150, 0, 0}, {0, 1e150, 0}, {0, 0, 1e150}};
  EXPECT_THROW(auto_camera(m, Projection::Perspective, 8, 8), std::runtime_error);
  m.points = {{0, 0, 0}, {1e100, 0, 0}, {0, 1e100, 0}, {0, 0, 1e100}};
  const Camera c = auto_camera(m, Projection::Perspective, 8, 8);
  EXPECT_TRUE(std::isfinite(c.eye.z));
}

TEST(TransferFunction, TransparentOverMatchesMaxOpacity) {
  const std::vector<ColorPoint> c = {{0, 0.2, 0.3, 0.4}, {1, 0.9, 0.8, 0.7}};
  const std::vector<std::vector<OpacityPoint>> cases = {
      {{0.0, 0.0}, {1.0, 0.6}},                                     // zero below and at the first point
      {{0.0, 0.3}, {0.2, 0.0}, {0.4, 0.0}, {0.6, 0.5}, {1.0, 0.0}},  // an inner run, zero above the last
      {{0.0, 0.2}, {0.5, 0.0}, {1.0, 0.2}},                          // a single zero point
      {{0.0, 0.0}, {1.0, 0.0}},                                      // transparent everywhere
      {{0.0, 0.1}, {1.0, 0.6}},                                      // nowhere
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.3, 1.3);
  for (const auto& op : cases) {
    const TransferFunction tf(c, op);
    std::vector<double> probes = {-1, 0, 0.2, 0.4, 0.5, 0.6, 1, 2};
    for (int k = 0; k < 40; ++k) probes.push_back(u(rng));
    for (double lo : probes)
      for (double hi : probes) {
        if (lo > hi) continue;
        EXPECT_EQ(tf.transparent_over(lo, hi), tf.max_opacity(lo, hi) <= 0) << lo << " " << hi;
      }
  }
}

}  // namespace
}  // namespace zs

namespace zs {
namespace {

// A sphere scene: the renderer is picked by the top-level key, and the sphere
// blocks' values arrive where the renderer reads them.
TEST(Scene, SphereSceneParsesEveryKey) {
  const Scene s = parse_scene(R"({
    "spheres": {"path": "atoms.pdb", "radius_scale": 0.5, "color": "scalar"},
    "image": {"width": 64, "height": 32, "background": [0, 0, 0, 1]},
    "camera": {"projection": "perspective", "eye": [0, 0, 9], "target": [0, 0, 0], "fov_y": 25},
    "shading": {"model": "flat", "light_direction": [1, 0, -1], "ambient": 0.1, "diffuse": 0.6,
                "specular": 0.2, "shininess": 8},
    "render": {"mode": "peel", "surfaces": "front", "tolerance": 4, "max_layers": 16, "grid": 5,
               "culling": false, "memory_budget_mb": 512}})",
                              "s.json", "/data");
  ASSERT_EQ(s.kind, SceneKind::Spheres);
  const SphereScene& sp = s.spheres;
  EXPECT_EQ(sp.path, "/data/atoms.pdb");
  EXPECT_EQ(sp.radius_scale, 0.5);
  EXPECT_TRUE(sp.has_color_mode);
  EXPECT_EQ(sp.color, SphereColorMode::Scalar);
  EXPECT_EQ(sp.shading.model, ShadingModel::Flat);
  EXPECT_EQ(sp.shading.light_direction, glm::dvec3(1, 0, -1));
  EXPECT_EQ(sp.shading.shininess, 8);
  EXPECT_EQ(sp.mode, SphereMode::Peel);
  EXPECT_TRUE(sp.front_surfaces_only);
  EXPECT_EQ(sp.tolerance, 4);
  EXPECT_EQ(sp.max_layers, 16u);
  EXPECT_EQ(sp.grid, 5u);
  EXPECT_FALSE(sp.culling);
  EXPECT_EQ(s.settings.memory_budget_bytes, uint64_t(512) << 20);
  const SphereRenderSettings r = sphere_render_settings(s.settings, sp);
  EXPECT_EQ(r.width, 64u);
  EXPECT_EQ(r.camera.projection, Projection::Perspective);
  EXPECT_EQ(r.background[3], 1.0);
  EXPECT_EQ(r.grid, 5u);
  EXPECT_FALSE(r.culling);
}

// The error a sphere scene's JSON gives ("no error" when it parses).
std::string sphere_scene_error(const std::string& json) {
  try {
    parse_scene(json, "s.json", "");
  } catch (const std::runtime_error& e) {
    return std::string(e.what());
  }
  return std::string("no error");
}

TEST(Scene, SphereSceneErrors) {
  const auto err = &sphere_scene_error;
  EXPECT_NE(err(R"({"surfaces": ["c.obj"], "spheres": "a.sph"})").find("one of 'mesh', 'spheres' or 'surfaces'"), std::string::npos);
  EXPECT_NE(err(R"({"image": {}})").find("missing 'mesh' (volume), 'spheres' or 'surfaces'"), std::string::npos);
  EXPECT_NE(err(R"({"spheres": {"path": "a.sph", "radius_scale": 0}})").find("radius_scale"), std::string::npos);
  EXPECT_NE(err(R"({"spheres": "a.sph", "shading": {"model": "toon"}})").find("shading.model"), std::string::npos);
  EXPECT_NE(err(R"({"spheres": "a.sph", "shading": {"ambient": 2}})").find("shading.ambient"), std::string::npos);
  EXPECT_NE(err(R"({"spheres": "a.sph", "render": {"grid": 0}})").find("render.grid"), std::string::npos);
  EXPECT_NE(err(R"({"spheres": "a.sph", "render": {"grid": "fine"}})").find("render.grid must be \"auto\""),
            std::string::npos);
  // "auto" and no key are the same: resolved from the set's size when the grid is built.
  EXPECT_EQ(parse_scene(R"({"spheres": "a.sph", "render": {"grid": "auto"}})", "s.json", ".").spheres.grid, 0u);
  EXPECT_EQ(parse_scene(R"({"spheres": "a.sph"})", "s.json", ".").spheres.grid, 0u);
  EXPECT_NE(err(R"({"spheres": "a.sph", "render": {"integrator": "exact"}})").find("unknown key 'render.integrator'"),
            std::string::npos);
  EXPECT_NE(err(R"({"mesh": "m.off", "render": {"mode": "opaque"}})").find("unknown key 'render.mode'"),
            std::string::npos);
}

// A bare molecule file of each name (.ent is PDB, .mmcif is mmCIF) is a sphere
// scene; the command line's choices reach the reader.
TEST(Scene, BareMoleculeFilesByName) {
  const auto dir = test::scratch_dir();
  const std::string pdb =
      "ATOM      1  CA  ALA A   1       1.000   2.000   3.000  1.00 10.00           C\n"
      "HETATM    2  O   HOH A 101       4.000   2.000   3.000  1.00 20.00           O\n"
      "END\n";
  const std::string cif =
      "data_x\nloop_\n_atom_site.group_PDB\n_atom_site.id\n_atom_site.type_symbol\n_atom_site.label_atom_id\n"
      "_atom_site.label_comp_id\n_atom_site.label_asym_id\n_atom_site.label_seq_id\n_atom_site.Cartn_x\n"
      "_atom_site.Cartn_y\n_atom_site.Cartn_z\n_atom_site.occupancy\n_atom_site.B_iso_or_equiv\n"
      "_atom_site.auth_asym_id\n_atom_site.pdbx_PDB_model_num\n_atom_site.label_alt_id\n_atom_site.auth_seq_id\n"
      "ATOM 1 C CA ALA A 1 1.0 2.0 3.0 1.0 10.0 A 1 . 1\n"
      "HETATM 2 O O HOH B . 4.0 2.0 3.0 1.0 20.0 A 1 . 101\n";
  for (const auto& [name, text] : {std::pair{"x.ent", pdb}, std::pair{"x.mmcif", cif}}) {
    const std::string path = (dir / name).string();
    std::ofstream(path) << text;
    SceneInput in = load_scene_input(path, {});
    EXPECT_EQ(in.scene.kind, SceneKind::Spheres) << name;
    ASSERT_EQ(in.spheres.size(), 2u) << name;
    EXPECT_EQ(in.spheres.radii[0], 1.70) << name;  // Bondi's C
    EXPECT_EQ(in.spheres.molecule.waters, 1u) << name;
    MoleculeOverrides dry;
    dry.no_waters = true;
    in = load_scene_input(path, {}, dry);
    EXPECT_EQ(in.spheres.size(), 1u) << name;
    EXPECT_EQ(in.spheres.molecule.waters_left_out, 1u) << name;
  }
  std::filesystem::remove_all(dir);
}

// What is read of a molecule file: spheres.model (number or string),
// .waters, .hydrogens; colours by chain and residue.
TEST(Scene, MoleculeKeys) {
  const Scene s = parse_scene(
      R"({"spheres": {"path": "1abc.cif.gz", "model": 2, "waters": false, "hydrogens": false, "color": "chain"}})",
      "s.json", "/d");
  EXPECT_EQ(s.spheres.molecule.model, "2");
  EXPECT_FALSE(s.spheres.molecule.waters);
  EXPECT_FALSE(s.spheres.molecule.hydrogens);
  EXPECT_EQ(s.spheres.color, SphereColorMode::Chain);
  const Scene t = parse_scene(R"({"spheres": {"path": "a.pdb", "model": "3", "color": "residue"}})", "s.json", "/d");
  EXPECT_EQ(t.spheres.molecule.model, "3");
  EXPECT_TRUE(t.spheres.molecule.waters);
  EXPECT_EQ(t.spheres.color, SphereColorMode::Residue);
  EXPECT_EQ(parse_scene(R"({"spheres": "a.pdb"})", "s.json", "/d").spheres.molecule.model, "");
  const auto err = &sphere_scene_error;
  EXPECT_NE(err(R"({"spheres": {"path": "a.sph", "model": 2}})").find("spheres.model applies to molecule files"),
            std::string::npos);
  EXPECT_NE(err(R"({"spheres": {"path": "a.sphb", "waters": false}})").find("spheres.waters applies to molecule files"),
            std::string::npos);
  EXPECT_NE(err(R"({"spheres": {"path": "a.pdb", "model": -1}})").find("spheres.model must be a model number"),
            std::string::npos);
  EXPECT_NE(err(R"({"spheres": {"path": "a.pdb", "model": 1.5}})").find("spheres.model must be"), std::string::npos);
  EXPECT_NE(err(R"({"spheres": {"path": "a.pdb", "waters": "no"}})").find("spheres.waters must be true or false"),
            std::string::npos);
  EXPECT_NE(err(R"({"spheres": {"path": "a.pdb", "color": "bfactor"}})")
                .find(R"(spheres.color must be "element", "chain", "residue", "scalar" or "rgba")"),
            std::string::npos);
  EXPECT_NE(err(R"({"spheres": {"path": "a.pdb", "chains": "A"}})").find("unknown key 'spheres.chains'"),
            std::string::npos);
}

}  // namespace
}  // namespace zs
