// Tiny grey-level .inr images written by the generator tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace zs::test {

// A float .inr image of n^3 voxels of size vx: INR header padded to 256
// bytes, then little-endian data, x fastest.
inline void write_inr(const std::filesystem::path& p, int n, double vx, const std::vector<float>& data) {
  std::string h = "#INRIMAGE-4#{\nXDIM=" + std::to_string(n) + "\nYDIM=" + std::to_string(n) +
                  "\nZDIM=" + std::to_string(n) + "\nVDIM=1\nTYPE=float\nPIXSIZE=32 bits\nCPU=decm\nVX=" +
                  std::to_string(vx) + "\nVY=" + std::to_string(vx) + "\nVZ=" + std::to_string(vx) + "\n";
  h.resize(252, '\n');
  h += "##}\n";
  std::ofstream f(p, std::ios::binary);
  f.write(h.data(), static_cast<std::streamsize>(h.size()));
  f.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size() * sizeof(float)));
}

}  // namespace zs::test
