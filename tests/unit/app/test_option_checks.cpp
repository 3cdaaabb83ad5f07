// Option checks (src/app/option_checks.h): number messages people can read,
// and options refused for inputs they do not apply to (issue 38, items 7, 14).
#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "app/option_checks.h"
#include "app/scene_args.h"
#include "app/scene_job.h"

namespace zs {
namespace {

TEST(OptionChecks, NumberMessages) {
  EXPECT_EQ(number_error("abc", whole_range(1, 1 << 20)), "'abc' is not a number");
  EXPECT_EQ(number_error("64.5", whole_range(1, 1 << 20)), "'64.5' is not a whole number");
  EXPECT_EQ(number_error("1e3", whole_range(1, 1 << 20)), "'1e3' is not a whole number");
  EXPECT_EQ(number_error("0", whole_range(1, 1 << 20)), "0 is out of range: must be in [1, 1048576]");
  EXPECT_EQ(number_error("0", whole_range(1, INFINITY)), "0 is out of range: must be at least 1");
  EXPECT_EQ(number_error("0", positive_range(1.7e13)), "0 is out of range: must be positive and at most 1.7e+13");
  EXPECT_EQ(number_error("-1", real_range(0, 255)), "-1 is out of range: must be in [0, 255]");
  EXPECT_EQ(number_error("nan", real_range(0, 255)), "'nan' is not a number");
  EXPECT_EQ(number_error("inf", positive_range()), "'inf' is not a finite number");
  EXPECT_EQ(number_error("12", whole_range(1, 1 << 20)), "");
  EXPECT_EQ(number_error("0.5", positive_range()), "");
  EXPECT_EQ(number_error(64.5, whole_range(1, 1 << 20)), "64.5 is not a whole number");
  EXPECT_EQ(number_error(0.0, whole_range(1, 1 << 20)), "0 is out of range: must be in [1, 1048576]");
}

TEST(OptionChecks, EveryNumericOptionSaysNotANumber) {
  CLI::App app;
  double scale = 1;
  int count = 0;
  uint64_t seed = 0;
  CLI::App* sub = app.add_subcommand("sub");
  sub->add_option("--scale", scale);
  sub->add_option("--count", count)->check(CLI::Range(1, 10));  // CLI11's own would say "not in range"
  sub->add_option("--seed", seed);
  check_every_number(app);
  auto error = [&](std::vector<std::string> args) -> std::string {
    std::reverse(args.begin(), args.end());
    try {
      app.parse(args);
    } catch (const CLI::ParseError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error({"sub", "--scale", "abc"}), "--scale: 'abc' is not a number");
  EXPECT_EQ(error({"sub", "--count", "abc"}), "--count: 'abc' is not a number");
  EXPECT_EQ(error({"sub", "--count", "2.5"}), "--count: '2.5' is not a whole number");
  EXPECT_EQ(error({"sub", "--seed", "-1"}), "--seed: -1 is out of range: must be at least 0");
  EXPECT_EQ(error({"sub", "--seed", "7"}), "");
}

TEST(OptionChecks, OptionsThatDoNotApplyToTheInputAreRefused) {
  EXPECT_THROW(check_option_scope({"--integrator"}, SceneKind::Spheres, "a.pdb"), UsageError);
  EXPECT_THROW(check_option_scope({"--no-culling"}, SceneKind::Volume, "a.off"), UsageError);
  EXPECT_THROW(check_option_scope({"--ao-samples"}, SceneKind::Surfaces, "a.obj"), UsageError);
  EXPECT_NO_THROW(check_option_scope({"--integrator", "--scalar", "--q"}, SceneKind::Volume, "a.off"));
  EXPECT_NO_THROW(check_option_scope({"--no-culling", "--ao-samples"}, SceneKind::Spheres, "a.sph"));
  try {
    check_option_scope({"--max-list-length"}, SceneKind::Surfaces, "cow.off", true);
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "cow.off: max_list_length applies to tet meshes only, and this is a surface scene");
  }
}

TEST(OptionChecks, KnobsThatNeedAnotherSettingAreRefused) {
  SceneArgs a;
  a.variant = "dilate";  // without --scan bconvert it changes nothing
  SceneInput in = load_scene_input("", {});
  EXPECT_THROW(a.apply(in), UsageError);
  a.scan = "bconvert";
  in = load_scene_input("", {});
  EXPECT_NO_THROW(a.apply(in));
  SceneArgs b;
  b.integrator = "linear";
  b.precision = "single";  // the exact integrator's kernel only
  in = load_scene_input("", {});
  EXPECT_THROW(b.apply(in), UsageError);
  SceneArgs c;
  c.projection = "perspective";  // the default scene has its own camera
  in = load_scene_input("", {});
  EXPECT_THROW(c.apply(in), UsageError);
  SceneArgs d;
  d.opt.scalar = "nosuch";  // no mesh file to pick it from
  in = load_scene_input("", {});
  EXPECT_THROW(d.apply(in), UsageError);
}

TEST(OptionChecks, LeftOutNote) {
  EXPECT_EQ(left_out_note({{0, "tet", "tets"}}), "");
  EXPECT_EQ(left_out_note({{1, "tet", "tets"}, {0, "x", "xs"}, {3, "line", "lines"}}), "; left out: 1 tet, 3 lines");
}

}  // namespace
}  // namespace zs
