// Reading and writing float RGBA images (raster/image.h) through OpenImageIO.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raster/image.h"

namespace zs {

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
// The view-depth channel "Z" of an EXR/TIFF written by a sphere render or
// reference (+inf where nothing was hit); empty when the file has none.
std::vector<float> read_depth_channel(const std::string& path);

}  // namespace zs
