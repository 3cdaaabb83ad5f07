// Where tests find their inputs. The real meshes live in ../shared/datasets
// beside the checkout (never copied into the repo); ZSWEEP_SHARED overrides.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace zs::test {

inline std::string test_data(const std::string& name) {
  return std::string(ZS_TEST_DATA) + "/" + name;
}

inline std::string shared_dataset(const std::string& name) {
  const char* env = std::getenv("ZSWEEP_SHARED");
  std::string dir = env ? std::string(env) : std::string(ZS_SHARED_DATA);
  std::string p = dir + "/" + name;
  return std::filesystem::exists(p) ? p : std::string();
}

// A unique scratch directory per test, removed by the caller if wanted.
inline std::filesystem::path scratch_dir() {
  auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  auto dir = std::filesystem::temp_directory_path() /
             ("zsweep-test-" + std::string(info->test_suite_name()) + "-" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace zs::test

// Skips (with a reason ctest shows) when a shared dataset is absent.
#define ZS_REQUIRE_SHARED(var, name)                                            \
  std::string var = ::zs::test::shared_dataset(name);                           \
  if (var.empty()) GTEST_SKIP() << "shared dataset " << (name)                 \
                                << " not found (expected in ../shared/datasets " \
                                   "or $ZSWEEP_SHARED)"
