#include "app/option_checks.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include <CLI/CLI.hpp>

namespace zs {

namespace {

// Bounds as people write them: 1048576, 0.001, 1.7e+13 (not 300 digits).
std::string num(double v) {
  char buf[64];
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (v == std::floor(v) && std::fabs(v) < 1e10)
    std::snprintf(buf, sizeof buf, "%.0f", v);
  else
    std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string allowed(const NumberRange& r) {
  const bool has_lo = std::isfinite(r.lo), has_hi = std::isfinite(r.hi);
  const std::string lo = r.lo_open && r.lo == 0 ? "positive" : (r.lo_open ? "more than " : "at least ") + num(r.lo);
  if (has_lo && has_hi)
    return r.lo_open && r.lo == 0 ? "positive and at most " + num(r.hi)
                                  : std::string("in ") + (r.lo_open ? "(" : "[") + num(r.lo) + ", " + num(r.hi) + "]";
  if (has_lo) return lo;
  if (has_hi) return "at most " + num(r.hi);
  return "";
}

bool in_range(double v, const NumberRange& r) {
  return (r.lo_open ? v > r.lo : v >= r.lo) && v <= r.hi;
}

}  // namespace

std::string number_error(double v, const NumberRange& r) {
  if (std::isnan(v)) return "'nan' is not a number";
  if (!std::isfinite(v)) return num(v) + " is not a finite number";
  if (r.integer && v != std::floor(v)) return num(v) + " is not a whole number";
  if (!in_range(v, r)) return num(v) + " is out of range: must be " + allowed(r);
  return "";
}

std::string number_error(const std::string& text, const NumberRange& r) {
  if (r.integer) {
    // Digits only (with a sign): what CLI11 converts to an integer exactly.
    size_t i = text.size() > 0 && (text[0] == '-' || text[0] == '+') ? 1 : 0;
    bool digits = i < text.size();
    for (; i < text.size(); ++i) digits = digits && text[i] >= '0' && text[i] <= '9';
    if (!digits) {
      char* end = nullptr;
      errno = 0;
      std::strtod(text.c_str(), &end);
      const bool number = !text.empty() && end && *end == '\0';
      return "'" + text + "' is not a " + (number ? "whole number" : "number");
    }
    // Beyond a double's integers the bound check below is still right.
  }
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || !end || *end != '\0' || std::isnan(v)) return "'" + text + "' is not a number";
  if (!std::isfinite(v)) return "'" + text + "' is not a finite number";
  if (!in_range(v, r)) return text + " is out of range: must be " + allowed(r);
  return "";
}

CLI::Validator number_check(const NumberRange& r) {
  const std::string a = allowed(r);
  return CLI::Validator([r](std::string& s) { return number_error(s, r); },
                        std::string(r.integer ? "whole number" : "number") + (a.empty() ? "" : " " + a));
}

void check_every_number(CLI::App& app) {
  for (CLI::Option* o : app.get_options()) {
    const std::string t = o->get_type_name();
    const std::string base = t.substr(0, t.find(':'));
    // An option with checks of its own (described after ':') gets their
    // bounds in the message; one without still refuses a negative unsigned.
    const bool own_checks = t.find(':') != std::string::npos;
    NumberRange r;
    if (base == "INT") r = whole_range(-INFINITY, INFINITY);
    else if (base == "UINT") r = whole_range(own_checks ? -INFINITY : 0, INFINITY);
    else if (base == "FLOAT") r = real_range(-INFINITY, INFINITY);
    else continue;
    // In front of the option's own checks, which would call a word "not in range".
    o->transform(CLI::Validator([r](std::string& s) { return number_error(s, r); }, ""));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) check_every_number(*sub);
}

// ---------------------------------------------------------------- option scope

namespace {

constexpr unsigned kV = 1, kS = 2, kF = 4, kM = 8;  // kM: molecule files (sphere sets too)

struct Scope {
  const char* option;
  unsigned kinds;
};

// Options of render/reference (and the Python module's keywords) that apply
// to some input kinds only. Options not here apply to every kind.
constexpr Scope kScopes[] = {
    {"--q", kV},          {"--scalar", kV},       {"--association", kV},  {"--scan", kV},
    {"--variant", kV},    {"--integrator", kV},   {"--precision", kV},
    {"--early-termination", kV}, {"--max-list-length", kV},
    {"--no-culling", kS | kF}, {"--ao-samples", kS},
    {"--model", kM},      {"--no-waters", kM},    {"--no-hydrogens", kM},
};

// Python keywords that are not the command-line name with '_' for '-'.
struct PythonName {
  const char* option;
  const char* keyword;
};
constexpr PythonName kPythonNames[] = {{"--no-waters", "waters"}, {"--no-hydrogens", "hydrogens"}};

unsigned bits(SceneKind k, bool molecule) {
  return k == SceneKind::Volume ? kV : k == SceneKind::Spheres ? kS | (molecule ? kM : 0) : kF;
}

const char* kind_name(SceneKind k) {
  return k == SceneKind::Volume ? "a tet mesh" : k == SceneKind::Spheres ? "a sphere set" : "a surface scene";
}

std::string kinds_name(unsigned kinds) {
  std::string s;
  const char* names[] = {"tet meshes", "sphere sets", "surfaces", "molecule files (.pdb, .ent, .cif, .mmcif)"};
  int n = 0;
  for (int i = 0; i < 4; ++i)
    if (kinds & (1u << i)) s += (n++ ? " and " : "") + std::string(names[i]);
  return s;
}

}  // namespace

std::string option_name(const std::string& cli_name, bool python) {
  if (!python) return cli_name;
  for (const PythonName& p : kPythonNames)
    if (cli_name == p.option) return p.keyword;
  std::string s = cli_name.substr(cli_name.find_first_not_of('-'));
  for (char& c : s)
    if (c == '-') c = '_';
  return s;
}

void check_option_scope(const std::vector<std::string>& given, SceneKind kind, const std::string& input, bool python,
                        bool molecule) {
  for (const std::string& g : given)
    for (const Scope& s : kScopes)
      if (g == s.option && !(s.kinds & bits(kind, molecule)))
        throw UsageError(input + ": " + option_name(g, python) + " applies to " + kinds_name(s.kinds) +
                                 " only, and this is " + kind_name(kind));
}

}  // namespace zs
