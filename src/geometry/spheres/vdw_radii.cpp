#include "geometry/spheres/vdw_radii.h"

#include <cctype>

namespace zs {

namespace {

struct Entry {
  const char* symbol;  // upper case, as normalised below
  double radius;
};

// Bondi 1964, Table I and II.
constexpr Entry kBondi[] = {
    {"H", 1.20},  {"D", 1.20},  {"T", 1.20},  {"HE", 1.40}, {"LI", 1.82}, {"C", 1.70},  {"N", 1.55},
    {"O", 1.52},  {"F", 1.47},  {"NE", 1.54}, {"NA", 2.27}, {"MG", 1.73}, {"SI", 2.10}, {"P", 1.80},
    {"S", 1.80},  {"CL", 1.75}, {"AR", 1.88}, {"K", 2.75},  {"NI", 1.63}, {"CU", 1.40}, {"ZN", 1.39},
    {"GA", 1.87}, {"AS", 1.85}, {"SE", 1.90}, {"BR", 1.85}, {"KR", 2.02}, {"PD", 1.63}, {"AG", 1.72},
    {"CD", 1.58}, {"IN", 1.93}, {"SN", 2.17}, {"TE", 2.06}, {"I", 1.98},  {"XE", 2.16}, {"PT", 1.72},
    {"AU", 1.66}, {"HG", 1.55}, {"TL", 1.96}, {"PB", 2.02}, {"U", 1.86},
};

}  // namespace

bool vdw_radius(std::string_view element, double& r) {
  while (!element.empty() && element.front() == ' ') element.remove_prefix(1);
  while (!element.empty() && element.back() == ' ') element.remove_suffix(1);
  if (element.empty() || element.size() > 2) return false;
  char up[3] = {0, 0, 0};
  for (size_t i = 0; i < element.size(); ++i) up[i] = static_cast<char>(std::toupper(static_cast<unsigned char>(element[i])));
  for (const Entry& e : kBondi)
    if (std::string_view(e.symbol) == std::string_view(up, element.size())) {
      r = e.radius;
      return true;
    }
  return false;
}

}  // namespace zs
