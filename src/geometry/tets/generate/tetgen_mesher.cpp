#include "geometry/tets/generate/tetgen_mesher.h"

#include <tetgen.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/tets/generate/tet_ops.h"
#include "geometry/tets/io/stdio_capture.h"

namespace zs {

namespace {

REAL* copy_points(const std::vector<glm::dvec3>& pts) {
  REAL* a = new REAL[3 * pts.size()];
  for (size_t i = 0; i < pts.size(); ++i) {
    a[3 * i] = pts[i].x;
    a[3 * i + 1] = pts[i].y;
    a[3 * i + 2] = pts[i].z;
  }
  return a;
}

// Fills `in` from the PLC; tetgenio's destructor frees everything with delete[].
void fill_input(const Plc& plc, tetgenio& in) {
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(plc.points.size());
  in.pointlist = copy_points(plc.points);
  in.numberoffacets = static_cast<int>(plc.facets.size());
  in.facetlist = new tetgenio::facet[plc.facets.size()];
  for (size_t i = 0; i < plc.facets.size(); ++i) {
    const PlcFacet& src = plc.facets[i];
    tetgenio::facet& f = in.facetlist[i];
    tetgenio::init(&f);
    f.numberofpolygons = static_cast<int>(src.polygons.size());
    f.polygonlist = new tetgenio::polygon[src.polygons.size()];
    for (size_t j = 0; j < src.polygons.size(); ++j) {
      tetgenio::polygon& p = f.polygonlist[j];
      tetgenio::init(&p);
      p.numberofvertices = static_cast<int>(src.polygons[j].size());
      p.vertexlist = new int[src.polygons[j].size()];
      for (size_t k = 0; k < src.polygons[j].size(); ++k)
        p.vertexlist[k] = static_cast<int>(src.polygons[j][k]);
    }
    if (!src.holes.empty()) {
      f.numberofholes = static_cast<int>(src.holes.size());
      f.holelist = copy_points(src.holes);
    }
  }
  if (!plc.holes.empty()) {
    in.numberofholes = static_cast<int>(plc.holes.size());
    in.holelist = copy_points(plc.holes);
  }
}

// Volume enclosed by a closed triangle surface (cavities wound inward count
// negative); 0 for other PLCs, which only the built-in shapes make.
double enclosed_volume(const Plc& plc) {
  if (!plc.is_triangle_surface()) return 0;
  double v6 = 0;
  for (const auto& t : plc.triangles())
    v6 += glm::dot(plc.points[t[0]], glm::cross(plc.points[t[1]], plc.points[t[2]]));
  return std::abs(v6) / 6;
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

}  // namespace

TetMesh tetrahedralize(const Plc& plc, const TetgenOptions& opt) {
  if (plc.points.size() < 4 || plc.facets.empty())
    throw std::runtime_error("surface has too few points or faces to enclose a volume");
  if (plc.points.size() > INT_MAX / 3) throw std::runtime_error("surface too large for TetGen");
  // TetGen's refinement is only guaranteed to terminate for ratios above ~1.1.
  if (opt.quality > 0 && opt.quality < 1.1)
    throw std::invalid_argument("quality (radius-edge ratio) must be 0 (off) or >= 1.1");
  if (!(opt.max_volume >= 0) || !std::isfinite(opt.max_volume))
    throw std::invalid_argument("max volume must be 0 (none) or a positive number");
  if (opt.max_tets > 0 && opt.max_volume > 0) {
    const double need = enclosed_volume(plc) / opt.max_volume;  // each tet holds at most max_volume
    if (need > static_cast<double>(opt.max_tets))
      throw std::invalid_argument("max volume " + num(opt.max_volume) + " needs at least " + num(need) +
                                  " tets inside this surface (volume " + num(enclosed_volume(plc)) +
                                  "), over the limit of " + std::to_string(opt.max_tets) +
                                  " (--max-tets); use a larger max volume");
  }

  tetgenio in, out;
  fill_input(plc, in);

  // p: mesh the PLC; Q: quiet; z: number from 0; q/a/Y as requested.
  std::string sw = "pzQ";
  char num[64];
  if (opt.quality > 0) {
    std::snprintf(num, sizeof num, "q%.6g", opt.quality);
    sw += num;
  }
  if (opt.max_volume > 0) {
    std::snprintf(num, sizeof num, "a%.9g", opt.max_volume);
    sw += num;
  }
  if (opt.preserve_surface) sw += "Y";
  const long max_added = opt.max_tets > 0 ? static_cast<long>(std::min<size_t>(opt.max_tets / 4 + 1, INT_MAX)) : -1;
  if (max_added > 0) sw += "S" + std::to_string(max_added);
  std::vector<char> swbuf(sw.begin(), sw.end());
  swbuf.push_back('\0');

  StdioCapture cap;
  bool ok = true;
  std::string fallback = "TetGen failed";
  try {
    ::tetrahedralize(swbuf.data(), &in, &out);
  } catch (const std::bad_alloc&) {
    ok = false;
    fallback = "TetGen ran out of memory";
  } catch (int code) {  // terminatetetgen(): 1 memory, 2 internal, 3 self-intersection...
    ok = false;
    if (code == 3) fallback = "TetGen: the input surface self-intersects";
    else fallback = "TetGen failed (code " + std::to_string(code) + ")";
  }
  std::string text = cap.finish();
  if (!ok) throw std::runtime_error(tetgen_error_line(text, fallback));
  if (max_added > 0 && out.numberofpoints - in.numberofpoints >= max_added)
    throw std::runtime_error("TetGen reached the limit of " + std::to_string(max_added) + " added points (--max-tets " +
                             std::to_string(opt.max_tets) + ") before meeting the quality and volume bounds");

  TetMesh m;
  m.points.resize(static_cast<size_t>(out.numberofpoints));
  for (size_t i = 0; i < m.points.size(); ++i)
    m.points[i] = {out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]};
  m.tets.resize(static_cast<size_t>(out.numberoftetrahedra));
  const size_t nc = static_cast<size_t>(out.numberofcorners);
  for (size_t t = 0; t < m.tets.size(); ++t)
    for (int k = 0; k < 4; ++k) m.tets[t][k] = static_cast<uint32_t>(out.tetrahedronlist[t * nc + k]);
  finalize_generated(m);
  return m;
}

}  // namespace zs
