// CLI11 validators for numbers whose messages read well, and the one table
// of which input kinds each render option applies to.
//
//   --width: 'abc' is not a number
//   --width: '64.5' is not a whole number
//   --count: 0 is out of range: must be at least 1
//   --tile-size: 5000 is out of range: must be in [8, 4096]
//
// (CLI11's own Range says "Value abc not in range" for a word and writes
// DBL_MAX out in 300 digits.)
#pragma once

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace zs {

// A usage error found after parsing (an option that does not apply to the
// input, a bad option value): exit code 2 like CLI11's own, ValueError in Python.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A numeric option's allowed values: [lo, hi], or (lo, hi] when lo_open.
struct NumberRange {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool integer = false;
  bool lo_open = false;
};
constexpr NumberRange whole_range(double lo, double hi) { return {lo, hi, true, false}; }
constexpr NumberRange real_range(double lo, double hi) { return {lo, hi, false, false}; }
constexpr NumberRange positive_range(double hi = std::numeric_limits<double>::infinity()) {
  return {0, hi, false, true};
}

// "" when `text` is a number in `r`, else why not (without the option's name).
std::string number_error(const std::string& text, const NumberRange& r);
// The same for a value already parsed (the Python module's keywords).
std::string number_error(double v, const NumberRange& r);
CLI::Validator number_check(const NumberRange& r);

// Every option of `app` and its subcommands, recursively, that takes a
// number (CLI11 type INT, UINT or FLOAT) gets a check in front of its own:
// a word is "not a number" (not "not in range"), 64.5 for an integer "not a
// whole number", -1 for an unsigned "out of range" (CLI11 would wrap it).
void check_every_number(CLI::App& app);

// Which inputs a render option applies to (the table in option_checks.cpp).
// `given`: the options the user set, by their command-line name
// ("--integrator"); `input`: how to name the input in the message. Throws
// UsageError "INPUT: --integrator applies to tet meshes, not to a
// sphere set". `python`: name options as the module's keywords. `molecule`:
// the sphere set is a molecule file (--model, --no-waters, --no-hydrogens).
void check_option_scope(const std::vector<std::string>& given, SceneKind kind, const std::string& input,
                        bool python = false, bool molecule = false);
// "--max-list-length" -> "max_list_length" when `python` ("--no-waters" ->
// "waters": the keyword is the scene's key).
std::string option_name(const std::string& cli_name, bool python);

}  // namespace zs
