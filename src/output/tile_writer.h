// Streams a render's tiles to an image file so that no full image is ever
// held in memory (offline stills of 16384² and beyond).
//
// EXR and TIFF are written as tiled float RGBA files whose tiles are the
// engine's tiles: each tile goes to disk as it arrives, in any order. PNG
// (and any other scanline-only format) is 8-bit and must be written top to
// bottom, so arriving tiles are quantized into their row band and a band is
// written once it and every band above it are complete; only the bands that
// arrived out of order are held. The values are those write_image() stores
// for the same image, bit for bit.
//
// Write-then-rename: nothing appears under the final name unless commit()
// succeeded; destroying the writer without commit leaves no file.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "raster/tile_sink.h"

namespace zs {

class ImageTileWriter : public TileSink {
 public:
  // Opens the output (a temporary beside `path`) for an image cut as `grid`,
  // with `compression` for EXR/TIFF (output_compression, image.h; "" = our
  // default). Throws std::runtime_error naming the file.
  // `channel_names`: the float formats' names of channels past Z (index 5
  // on; the first five are always R, G, B, A, Z).
  ImageTileWriter(const std::string& path, const TileGrid& grid, const std::string& compression = "",
                  const std::vector<std::string>& channel_names = {});
  ~ImageTileWriter() override;
  ImageTileWriter(const ImageTileWriter&) = delete;
  ImageTileWriter& operator=(const ImageTileWriter&) = delete;

  // One tile of grid: r must be one of its rects, each delivered once.
  // Throws std::runtime_error naming the file.
  void tile(const TileRect& r, const float* rgba) override;

  // What the writer expects to hold while the engine delivers tiles in
  // roughly row-major order, for the caller's memory budget.
  uint64_t buffer_bytes_estimate() const;
  // The same for a writer not yet opened (nothing is opened or allocated), so
  // the caller can check its budget before the file library allocates its
  // tables; also rejects an image the format cannot hold. Throws
  // std::runtime_error naming the file.
  static uint64_t buffer_bytes_estimate(const std::string& path, const TileGrid& grid);
  // Whether `path`'s format stores the channels past RGBA (EXR and TIFF:
  // float; the 8-bit formats keep R, G, B, A only). Nothing is opened.
  static bool keeps_extra_channels(const std::string& path);
  // The most it actually held (band buffers; tiled formats hold none).
  uint64_t peak_buffer_bytes() const;
  // True when written as a tiled file, false when in scanline bands.
  bool tiled() const;

  // Checks that every tile arrived, closes and renames onto the final name.
  // Throws std::runtime_error (one line naming the file) on failure.
  void commit();

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace zs
