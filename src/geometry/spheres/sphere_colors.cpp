#include "geometry/spheres/sphere_colors.h"

#include <cmath>
#include <stdexcept>

namespace zs {

const char* to_string(SphereColorMode m) {
  switch (m) {
    case SphereColorMode::Element: return "element";
    case SphereColorMode::Rgba: return "rgba";
    case SphereColorMode::Scalar: return "scalar";
    case SphereColorMode::Chain: return "chain";
    case SphereColorMode::Residue: return "residue";
  }
  return "?";
}

bool parse_sphere_color_mode(const std::string& s, SphereColorMode* out) {
  if (s == "element") *out = SphereColorMode::Element;
  else if (s == "rgba") *out = SphereColorMode::Rgba;
  else if (s == "scalar") *out = SphereColorMode::Scalar;
  else if (s == "chain") *out = SphereColorMode::Chain;
  else if (s == "residue") *out = SphereColorMode::Residue;
  else return false;
  return true;
}

SphereColorMode default_color_mode(const SphereSet& s) {
  if (s.has_rgba()) return SphereColorMode::Rgba;
  if (s.has_elements()) return SphereColorMode::Element;
  if (s.has_scalars()) return SphereColorMode::Scalar;
  return SphereColorMode::Element;
}

glm::vec4 element_color(unsigned z) {
  // Jmol's CPK colours (0-255) for the elements of proteins, nucleic acids,
  // their ligands and common ions.
  struct Entry {
    unsigned z;
    unsigned char r, g, b;
  };
  static constexpr Entry kTable[] = {
      {1, 255, 255, 255}, {5, 255, 181, 181}, {6, 144, 144, 144}, {7, 48, 80, 248},   {8, 255, 13, 13},
      {9, 144, 224, 80},  {11, 171, 92, 242}, {12, 138, 255, 0},  {15, 255, 128, 0},  {16, 255, 255, 48},
      {17, 31, 240, 31},  {19, 143, 64, 212}, {20, 61, 255, 0},   {25, 156, 122, 199}, {26, 224, 102, 51},
      {27, 240, 144, 160}, {28, 80, 208, 80}, {29, 200, 128, 51}, {30, 125, 128, 176}, {34, 255, 161, 0},
      {35, 166, 41, 41},  {53, 148, 0, 148},
  };
  for (const Entry& e : kTable)
    if (e.z == z) return {e.r / 255.f, e.g / 255.f, e.b / 255.f, 1.f};
  return {0.75f, 0.75f, 0.75f, 1.f};
}

namespace {

glm::vec4 rgb255(unsigned char r, unsigned char g, unsigned char b) { return {r / 255.f, g / 255.f, b / 255.f, 1.f}; }

}  // namespace

glm::vec4 chain_color(unsigned chain_index) {
  // Paul Tol's "bright" (less its grey), then "vibrant" orange and teal, then
  // "muted" olive, wine, indigo and sand: twelve colours apart from one another
  // and from a white or black background.
  static constexpr unsigned char kPalette[kChainColors][3] = {
      {68, 119, 170}, {238, 102, 119}, {34, 136, 51}, {204, 187, 68}, {102, 204, 238}, {170, 51, 119},
      {238, 119, 51}, {0, 153, 136},   {153, 153, 51}, {136, 34, 85}, {51, 34, 136},   {221, 204, 119},
  };
  const unsigned char* c = kPalette[chain_index % kChainColors];
  return rgb255(c[0], c[1], c[2]);
}

glm::vec4 residue_color(ResidueClass c) {
  // Acidic red, basic blue, polar green as VMD's "ResType"; hydrophobic sand
  // (not white: backgrounds are often white).
  switch (c) {
    case ResidueClass::Hydrophobic: return rgb255(240, 200, 120);
    case ResidueClass::Polar: return rgb255(80, 190, 80);
    case ResidueClass::Acidic: return rgb255(220, 50, 50);
    case ResidueClass::Basic: return rgb255(50, 90, 220);
    case ResidueClass::OtherAminoAcid: return rgb255(190, 140, 220);
    case ResidueClass::Nucleic: return rgb255(240, 140, 40);
    case ResidueClass::Water: return rgb255(120, 210, 240);
    case ResidueClass::Other: break;
  }
  return rgb255(150, 150, 150);
}

std::vector<glm::vec4> sphere_colors(const SphereSet& s, SphereColorMode mode, const TransferFunction& tf) {
  std::vector<glm::vec4> out(s.size());
  switch (mode) {
    case SphereColorMode::Rgba:
      if (!s.has_rgba()) throw std::runtime_error("spheres.color is \"rgba\" but the sphere set has no colours");
      return s.rgba;
    case SphereColorMode::Element:
      for (size_t i = 0; i < s.size(); ++i) out[i] = element_color(s.has_elements() ? s.element[i] : 0);
      return out;
    case SphereColorMode::Scalar:
      if (!s.has_scalars()) throw std::runtime_error("spheres.color is \"scalar\" but the sphere set has no scalar");
      for (size_t i = 0; i < s.size(); ++i) {
        const double v = s.scalars[i];
        if (!std::isfinite(v)) {  // a degenerate sphere: drawn grey, opaque
          out[i] = element_color(0);
          continue;
        }
        const auto c = tf.color(v);
        out[i] = {float(c[0]), float(c[1]), float(c[2]), float(tf.opacity(v))};
      }
      return out;
    case SphereColorMode::Chain:
      if (s.chain.size() != s.size())
        throw std::runtime_error("spheres.color is \"chain\" but the sphere set is not a molecule (no chains)");
      for (size_t i = 0; i < s.size(); ++i) out[i] = chain_color(s.chain[i]);
      return out;
    case SphereColorMode::Residue:
      if (s.residue_class.size() != s.size())
        throw std::runtime_error("spheres.color is \"residue\" but the sphere set is not a molecule (no residues)");
      for (size_t i = 0; i < s.size(); ++i) out[i] = residue_color(s.residue_class[i]);
      return out;
  }
  return out;
}

}  // namespace zs
