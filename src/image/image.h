// A float RGBA image, premultiplied, linear; row 0 at the top.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace zs {

struct Image {
  uint32_t width = 0, height = 0;
  std::vector<float> rgba;  // 4 floats per pixel
  Image() = default;
  Image(uint32_t w, uint32_t h) : width(w), height(h), rgba(size_t(w) * h * 4, 0.f) {}
  float* at(uint32_t x, uint32_t y) { return &rgba[(size_t(y) * width + x) * 4]; }
  const float* at(uint32_t x, uint32_t y) const { return &rgba[(size_t(y) * width + x) * 4]; }
};

// Writes PNG (8-bit, the same values, no gamma), EXR or TIFF (float) through
// OpenImageIO, to a temporary name renamed on success. Throws std::runtime_error
// naming the file.
// compression: as for output_compression.
void write_image(const std::string& path, const Image& img, const std::string& compression = "");

// The compression an EXR or TIFF output gets: `requested` when given
// (checked against what the format offers; throws std::runtime_error naming
// the file otherwise), else our default: lossless RLE for EXR — four times
// faster to write than zip on our renders for files 1.7–3.2× larger, and
// zip's cost, paid by the one thread that writes, would otherwise cap
// multi-threaded renders (docs/benchmarks.md) — and the library's own for TIFF. "" for formats without a choice.
std::string output_compression(const std::string& format, const std::string& requested, const std::string& path);
Image read_image(const std::string& path);

}  // namespace zs
