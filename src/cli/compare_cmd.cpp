// `zsweep compare A.exr B.exr [--diff DIFF.png] [--scale S] [--rgb] [--json]`
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/option_checks.h"
#include "cli/commands.h"
#include "output/image_io.h"
#include "output/image_compare.h"

namespace zs {

void add_compare_command(CLI::App& app) {
  struct Args {
    std::string a, b, diff;
    double scale = 4.0 / 255.0;
    bool json = false, rgb = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("compare", "Compare two images: max abs, RMSE, PSNR, pixels off by > 1/255");
  cmd->add_option("a", a->a, "First image (.exr, .tif, .png)")->required();
  cmd->add_option("b", a->b, "Second image")->required();
  CLI::Option* diff = cmd->add_option("--diff", a->diff, "Write a false-colour difference image");
  cmd->add_option("--scale", a->scale, "Difference shown as full red in --diff")
      ->capture_default_str()
      ->check(number_check(positive_range()))
      ->needs(diff);  // it only scales that image
  cmd->add_flag("--rgb", a->rgb,
                "Compare colour only, not alpha (for an image without alpha, such as VTK's screen grabs over "
                "black, against a premultiplied render)");
  cmd->add_flag("--json", a->json, "Print the numbers as JSON");
  cmd->callback([a] {
    const Image A = read_image(a->a), B = read_image(a->b);
    ImageDiff d;
    try {
      d = compare_images(A, B, a->rgb ? 3 : 4);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(a->a + " vs " + a->b + ": " + e.what());
    }
    if (!a->diff.empty()) write_image(a->diff, difference_image(A, B, a->scale, a->rgb ? 3 : 4));
    // Both with a depth channel: coverage (hit or not) and the largest
    // relative depth difference where both hit.
    const std::vector<float> za = read_depth_channel(a->a), zb = read_depth_channel(a->b);
    const bool with_z = !za.empty() && za.size() == zb.size();
    uint64_t z_mismatch = 0;
    double z_rel = 0;
    for (size_t p = 0; with_z && p < za.size(); ++p) {
      if (std::isinf(za[p]) != std::isinf(zb[p])) {
        ++z_mismatch;
      } else if (!std::isinf(za[p])) {
        const double den = std::max(std::abs(double(za[p])), std::abs(double(zb[p])));
        if (den > 0) z_rel = std::max(z_rel, std::abs(double(za[p]) - double(zb[p])) / den);
      }
    }
    if (a->json) {
      nlohmann::json j = {{"max_abs", d.max_abs},
                          {"rmse", d.rmse},
                          {"psnr", std::isinf(d.psnr) ? nlohmann::json(nullptr) : nlohmann::json(d.psnr)},
                          {"pixels_over_1_255", d.pixels_over_1_255},
                          {"worst_pixel", {d.worst_x, d.worst_y}}};
      if (with_z) j["z"] = {{"coverage_mismatches", z_mismatch}, {"max_rel", z_rel}};
      std::cout << j.dump(2) << "\n";
    } else {
      std::printf("max abs %.6g at (%u, %u), RMSE %.6g, PSNR %s dB, %llu pixels off by more than 1/255\n", d.max_abs,
                  d.worst_x, d.worst_y, d.rmse, std::isinf(d.psnr) ? "inf" : std::to_string(d.psnr).c_str(),
                  (unsigned long long)d.pixels_over_1_255);
      if (with_z)
        std::printf("Z: %llu pixels hit in one image only, max relative depth difference %.3g\n",
                    (unsigned long long)z_mismatch, z_rel);
    }
  });
}

}  // namespace zs
