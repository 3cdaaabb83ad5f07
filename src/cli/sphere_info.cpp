#include "cli/sphere_info.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "geometry/spheres/sphere_io.h"
#include "geometry/spheres/vdw_radii.h"

namespace zs {

namespace {

std::string joined(const std::vector<std::string>& v) {
  std::string out;
  for (const std::string& x : v) out += (out.empty() ? "" : ", ") + x;
  return out;
}

// "C 1003, O 356, N 263, S 9" (most first; "?" for atoms without an element).
std::string element_counts(const MoleculeCounts& m) {
  std::vector<std::string> parts;
  for (const auto& [symbol, n] : m.elements) parts.push_back(symbol + " " + std::to_string(n));
  return joined(parts);
}

nlohmann::json molecule_json(const SphereSet& s) {
  const MoleculeCounts& m = s.molecule;
  nlohmann::json elements = nlohmann::json::object();
  for (const auto& [symbol, n] : m.elements) elements[symbol] = n;
  return {
      {"atoms", m.atoms},
      {"elements", elements},
      {"chains", s.chain_names},
      {"residues", m.residues},
      {"models", m.models},
      {"model", m.model},
      {"waters", m.waters},
      {"hydrogens", m.hydrogens},
      {"inferred", {{"elements_from_atom_names", m.elements_inferred},
                    {"element_columns_cleared", m.element_columns_cleared},
                    {"charge_columns_cleared", m.charge_columns_cleared}}},
      {"left_out", {{"altlocs", m.altlocs_left_out}, {"waters", m.waters_left_out},
                    {"hydrogens", m.hydrogens_left_out}}},
      {"unknown_elements", m.unknown_elements},
      {"unknown_element_radius", kDefaultVdwRadius},
  };
}

void print_molecule(const SphereSet& s) {
  const MoleculeCounts& m = s.molecule;
  auto line = [](const char* key, const std::string& v) { std::printf("%-27s %s\n", key, v.c_str()); };
  auto n = [](size_t v) { return std::to_string(v); };
  char r[32];
  std::snprintf(r, sizeof r, "%g", kDefaultVdwRadius);
  line("atoms:", n(m.atoms));
  line("elements:", element_counts(m));
  std::vector<std::string> chains = s.chain_names;
  for (std::string& c : chains)
    if (c.empty()) c = "(blank)";
  line("chains:", n(m.chains) + (chains.empty() ? "" : " (" + joined(chains) + ")"));
  line("residues:", n(m.residues));
  line("models:", n(m.models) + " (read: " + (m.model.empty() ? "the first" : m.model) + ")");
  line("waters:", n(m.waters) + " atoms" + (m.waters_left_out ? " (" + n(m.waters_left_out) + " left out)" : ""));
  line("hydrogens:", n(m.hydrogens) + (m.hydrogens_left_out ? " (" + n(m.hydrogens_left_out) + " left out)" : ""));
  line("inferred:", n(m.elements_inferred) + " elements from atom names; columns 77-80 cleared on " +
                        n(std::max(m.element_columns_cleared, m.charge_columns_cleared)) + " records");
  line("left out:", n(m.altlocs_left_out) + " alternate locations, " + n(m.waters_left_out) + " water atoms, " +
                        n(m.hydrogens_left_out) + " hydrogens");
  line("unknown elements:", n(m.unknown_elements) + " (drawn at " + r + " Å)");
}

}  // namespace

void print_sphere_info(const std::string& path, bool json, const MoleculeOptions& molecule) {
  const SphereSet s = read_sphere_file(path, molecule);  // never empty: the readers refuse that
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
    if (s.is_molecule()) j["molecule"] = molecule_json(s);
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
  if (s.is_molecule()) print_molecule(s);
  line("colours:", s.has_rgba()       ? "rgba"
                   : s.is_molecule()  ? "by element (also: chain, residue, scalar)"
                   : s.has_elements() ? "by element"
                                      : "none");
  for (const std::string& note : s.notes) line("note:", note);
}

}  // namespace zs
