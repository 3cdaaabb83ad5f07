#include "cli/sphere_info.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "geometry/spheres/sphere_io.h"

namespace zs {

void print_sphere_info(const std::string& path, bool json) {
  const SphereSet s = read_sphere_file(path);  // never empty: the readers refuse that
  const double inf = std::numeric_limits<double>::infinity();
  glm::dvec3 lo(inf), hi(-inf);
  for (const glm::dvec3& c : s.centres) lo = glm::min(lo, c), hi = glm::max(hi, c);
  const auto [rmin, rmax] = std::minmax_element(s.radii.begin(), s.radii.end());
  double slo = inf, shi = -inf;
  for (double v : s.scalars)
    if (std::isfinite(v)) slo = std::min(slo, v), shi = std::max(shi, v);
  if (json) {
    nlohmann::json j = {
        {"file", path},
        {"spheres", s.size()},
        {"skipped", s.skipped},
        {"invalid", s.invalid},
        {"degenerate", s.degenerate},
        {"bounds", {{lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z}}},
        {"radius", {*rmin, *rmax}},
        {"scalar", s.has_scalars() ? nlohmann::json{{"name", s.scalar_name}, {"min", slo}, {"max", shi}}
                                   : nlohmann::json(nullptr)},
        {"notes", s.notes},
    };
    std::cout << j.dump(2) << "\n";
    return;
  }
  auto line = [](const char* key, const std::string& v) { std::printf("%-27s %s\n", key, v.c_str()); };
  char buf[256];
  line("file:", path);
  line("spheres:", std::to_string(s.size()));
  line("skipped records:", std::to_string(s.skipped));
  line("invalid (skipped):", std::to_string(s.invalid) + " (zero, negative or non-finite radius, non-finite centre)");
  line("degenerate:", std::to_string(s.degenerate) + " (non-finite scalar)");
  std::snprintf(buf, sizeof buf, "[%.9g, %.9g, %.9g] - [%.9g, %.9g, %.9g]", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
  line("centre bounds:", buf);
  std::snprintf(buf, sizeof buf, "[%.9g, %.9g]", *rmin, *rmax);
  line("radius range:", buf);
  if (s.has_scalars()) {
    std::snprintf(buf, sizeof buf, "%s, range [%.9g, %.9g]", s.scalar_name.c_str(), slo, shi);
    line("scalar:", buf);
  } else {
    line("scalar:", "none");
  }
  line("colours:", s.has_rgba() ? "rgba" : s.has_elements() ? "by element" : "none");
  for (const std::string& note : s.notes) line("note:", note);
}

}  // namespace zs
