// A scene as the command line names it: a scene .json, a bare mesh file
// (automatic camera and transfer function), or nothing at all (the embedded
// default scene). Shared by render, reference and the benchmarks.
#pragma once

#include <map>
#include <string>

#include "geometry/tets/io/mesh_io.h"
#include "geometry/tets/tet_mesh.h"
#include "scene/scene.h"
#include "geometry/spheres/sphere_set.h"
#include "geometry/triangles/clip_triangles.h"
#include "geometry/triangles/closed_solids.h"
#include "geometry/triangles/triangle_mesh.h"

namespace zs {

// The embedded default scene: the default ball of blobs, seen obliquely.
Scene default_scene();

struct SceneInput {
  Scene scene;
  TetMesh mesh;        // volume scenes
  SphereSet spheres;   // sphere scenes (radii already scaled by spheres.radius_scale)
  TriangleMesh surface;  // surface scenes: every surface, transformed, then the ground; point normals set
  uint64_t surface_polygons_split = 0, surface_elements_dropped = 0;
  SolidCounts surface_solids;     // before turning inward-wound solids outward (load_surfaces)
  TriangleClipCounts surface_clip;  // clip_geometry: triangles the planes dropped or cut
  double ground_lowered_by = 0;   // automatic ground: gap below the lowest y (0: at it)
  double ms_load = 0;
};

// Data that a scene names in place of a file (the Python module's arrays):
// where the scene's path equals a key here, the data is used and no file is
// read. Each entry is checked as a reader checks its file.
struct SceneData {
  std::map<std::string, TetMesh> meshes;
  std::map<std::string, SphereSet> spheres;
  std::map<std::string, TriangleMesh> surfaces;
  bool empty() const { return meshes.empty() && spheres.empty() && surfaces.empty(); }
};

// What the command line (or the Python module's keywords) chose to read of a
// molecule file: --model, --no-waters, --no-hydrogens. They override the
// scene's spheres.model/.waters/.hydrogens; SceneArgs refuses them for other inputs.
struct MoleculeOverrides {
  std::string model;  // "" = the scene's (default: the first model)
  bool no_waters = false, no_hydrogens = false;
  void apply(MoleculeOptions& m) const {
    if (!model.empty()) m.model = model;
    if (no_waters) m.waters = false;
    if (no_hydrogens) m.hydrogens = false;
  }
};

// Reads the scene (if any) and its mesh, sphere set or surfaces (a bare
// molecule, .sph or .sphb file is a sphere scene with defaults; a bare .obj/.ply/.stl
// or OFF surface a surface scene over a ground plane with one light). Throws std::runtime_error naming the
// file. Camera and transfer function are filled in by finish_scene, after the
// caller has applied its overrides (the automatic camera depends on the size).
SceneInput load_scene_input(const std::string& input, const ReadOptions& mesh_options,
                            const MoleculeOverrides& molecule = {});
// A scene given as JSON text (`name` in messages, relative paths from
// `base_dir`) whose files may be `data` instead.
SceneInput load_scene_input_text(const std::string& json_text, const std::string& name, const std::string& base_dir,
                                 const SceneData& data, const MoleculeOverrides& molecule = {});
void finish_scene(SceneInput& in, Projection auto_projection = Projection::Orthographic);

}  // namespace zs
