// field_distance(): kept apart from the analytic fields because the CGAL AABB
// tree is a heavy include.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>

#include "geometry/tets/generate/scalar_fields.h"
#include "geometry/tets/generate/tet_ops.h"

namespace zs {

void field_distance(TetMesh& m) {
  using K = CGAL::Simple_cartesian<double>;
  using Tri = K::Triangle_3;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, std::vector<Tri>::iterator>>>;
  auto pt = [&](uint32_t i) { return K::Point_3(m.points[i].x, m.points[i].y, m.points[i].z); };

  std::vector<Tri> tris;
  for (const auto& f : boundary_faces(m)) tris.emplace_back(pt(f[0]), pt(f[1]), pt(f[2]));
  m.scalars.assign(m.points.size(), 0.0);
  m.scalar_name = "distance";
  if (tris.empty()) return;
  Tree tree(tris.begin(), tris.end());
  tree.accelerate_distance_queries();
  for (size_t i = 0; i < m.points.size(); ++i)
    m.scalars[i] = std::sqrt(tree.squared_distance(pt(static_cast<uint32_t>(i))));
}

}  // namespace zs
