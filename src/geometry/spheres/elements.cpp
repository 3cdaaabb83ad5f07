#include "geometry/spheres/elements.h"

#include <cctype>

namespace zs {

namespace {

// Index + 1 is the atomic number.
constexpr const char* kSymbols[] = {
    "H",  "HE", "LI", "BE", "B",  "C",  "N",  "O",  "F",  "NE", "NA", "MG", "AL", "SI", "P",  "S",  "CL", "AR",
    "K",  "CA", "SC", "TI", "V",  "CR", "MN", "FE", "CO", "NI", "CU", "ZN", "GA", "GE", "AS", "SE", "BR", "KR",
    "RB", "SR", "Y",  "ZR", "NB", "MO", "TC", "RU", "RH", "PD", "AG", "CD", "IN", "SN", "SB", "TE", "I",  "XE",
    "CS", "BA", "LA", "CE", "PR", "ND", "PM", "SM", "EU", "GD", "TB", "DY", "HO", "ER", "TM", "YB", "LU", "HF",
    "TA", "W",  "RE", "OS", "IR", "PT", "AU", "HG", "TL", "PB", "BI", "PO", "AT", "RN", "FR", "RA", "AC", "TH",
    "PA", "U",  "NP", "PU", "AM", "CM", "BK", "CF", "ES", "FM", "MD", "NO", "LR", "RF", "DB", "SG", "BH", "HS",
    "MT", "DS", "RG", "CN", "NH", "FL", "MC", "LV", "TS", "OG",
};
static_assert(sizeof kSymbols / sizeof kSymbols[0] == 118);

}  // namespace

unsigned atomic_number(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  if (s.empty() || s.size() > 2) return 0;
  char up[2] = {0, 0};
  for (size_t i = 0; i < s.size(); ++i) up[i] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[i])));
  const std::string_view u(up, s.size());
  if (u == "D" || u == "T") return 1;
  for (unsigned i = 0; i < 118; ++i)
    if (u == kSymbols[i]) return i + 1;
  return 0;
}

}  // namespace zs
