// Scene-file parsing helpers shared by the scene parsers (scene.cpp,
// surface_scene.cpp): errors name the scene file, keys are checked.
#pragma once

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace zs::scene_json {

using nlohmann::json;

struct Ctx {
  std::string name, base;
  [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(name + ": " + what); }
  std::string resolve(const std::string& p) const {
    if (p.empty() || std::filesystem::path(p).is_absolute() || base.empty()) return p;
    return (std::filesystem::path(base) / p).lexically_normal().string();
  }
};

inline void check_keys(const Ctx& c, const json& obj, const std::string& where, std::initializer_list<const char*> allowed) {
  if (!obj.is_object()) c.fail(where + " must be an object");
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || it.key() == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      c.fail("unknown key '" + where + "." + it.key() + "' (allowed: " + list + ")");
    }
  }
}

inline double num(const Ctx& c, const json& v, const std::string& where) {
  if (!v.is_number()) c.fail(where + " must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) c.fail(where + " must be finite");
  return d;
}

inline glm::dvec3 vec3(const Ctx& c, const json& v, const std::string& where) {
  if (!v.is_array() || v.size() != 3) c.fail(where + " must be [x, y, z]");
  return {num(c, v[0], where + "[0]"), num(c, v[1], where + "[1]"), num(c, v[2], where + "[2]")};
}

inline double memory_budget_mb(const Ctx& c, const json& v) {
  const double mb = num(c, v, "render.memory_budget_mb");
  // Up to 2^44 MiB (2^64 bytes): beyond, the byte count is not representable
  // (a fuzzing finding: the conversion was undefined behaviour).
  if (!(mb > 0 && mb < 17592186044416.0)) c.fail("render.memory_budget_mb must be positive and below 2^44");
  return mb;
}

}  // namespace zs::scene_json
