// Where a line meets the mesh boundary: every boundary face, binned once by
// the screen rectangle its lines-of-sight cover, and a watertight line–
// triangle test (Woop, Benthin and Wald 2013) so that a ray through an edge or
// vertex shared by boundary faces is never lost between them.
//
// The reference walks whole lines (t from -inf to +inf) so that an eye inside
// the mesh needs no point location: the walk starts at the line's first
// boundary entry, behind the eye, and only t >= 0 is integrated.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "geometry/tets/tet_mesh.h"
#include "geometry/tets/topology.h"
#include "render/reference/tet_walk.h"
#include "base/view/camera.h"

namespace zs {

struct BoundaryHit {
  double t;       // distance along the (unit) direction from the ray origin
  uint32_t face;  // boundary face id (Topology)
  bool entry;     // the line goes into the mesh here
};

// Watertight line–triangle test: true when the line o + t·d meets triangle
// (a, b, c), edges and vertices included; *t gets the parameter.
bool line_hits_triangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
                        const glm::dvec3& c, double* t);

class BoundaryBins {
 public:
  // Boundary faces of the solid mesh (tet_walk.h: flat tets left out).
  BoundaryBins(const TetMesh& m, const Topology& topo, const SolidFaces& solid, const View& view);

  // All boundary faces met by the line through pixel centre (i, j), sorted
  // by t (entries before exits at equal t).
  void hits(uint32_t i, uint32_t j, const glm::dvec3& o, const glm::dvec3& d, std::vector<BoundaryHit>* out) const;

  size_t num_faces() const { return faces_.size(); }
  size_t everywhere_faces() const { return everywhere_.size(); }

 private:
  const TetMesh& m_;
  const Topology& topo_;
  std::vector<uint32_t> faces_;        // boundary face ids
  std::vector<uint8_t> outward_sign_;  // per boundary face: 1 if (b-a)x(c-a) points out of the mesh
  uint32_t bin_px_ = 8, bins_x_ = 1, bins_y_ = 1;
  std::vector<uint32_t> offsets_, items_;  // CSR: bin -> indices into faces_
  std::vector<uint32_t> everywhere_;       // faces whose lines of sight are unbounded on screen
};

}  // namespace zs
