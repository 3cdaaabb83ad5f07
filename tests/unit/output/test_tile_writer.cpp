// ImageTileWriter: tiles in any order make the same file write_image() makes
// from the whole image, and nothing is left behind unless commit() succeeded.
#include <algorithm>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/resource.h>

#include "output/image_io.h"
#include "output/tile_writer.h"
#include "support/test_paths.h"

namespace zs {
namespace {

namespace fs = std::filesystem;

// Values that exercise the 8-bit path: out of range (clamped), exactly half
// way between two levels, and plain random floats.
Image test_image(uint32_t w, uint32_t h, uint32_t seed = 1) {
  Image img(w, h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.1f, 1.1f);
  for (size_t i = 0; i < img.rgba.size(); ++i) {
    switch (rng() % 4) {
      case 0: img.rgba[i] = (float(rng() % 256) + 0.5f) / 255.f; break;
      case 1: img.rgba[i] = float(rng() % 256) / 255.f; break;
      default: img.rgba[i] = u(rng);
    }
  }
  return img;
}

// The grid's rects, computed here rather than by TileGrid::rect so the
// writer is checked against an independent tiling.
std::vector<TileRect> tile_rects(const TileGrid& g) {
  std::vector<TileRect> rects;
  for (uint32_t y = 0; y < g.height; y += g.size)
    for (uint32_t x = 0; x < g.width; x += g.size)
      rects.push_back({x, y, std::min(x + g.size, g.width), std::min(y + g.size, g.height)});
  return rects;
}

std::vector<float> crop(const Image& img, const TileRect& r) {
  std::vector<float> t;
  t.reserve(size_t(r.width()) * r.height() * 4);
  for (uint32_t y = r.y0; y < r.y1; ++y) t.insert(t.end(), img.at(r.x0, y), img.at(r.x1 - 1, y) + 4);
  return t;
}

// Hands `img` to `w` tile by tile, shuffled with `seed` (0 = row-major).
void send_tiles(ImageTileWriter& w, const Image& img, uint32_t size, uint32_t seed) {
  std::vector<TileRect> rects = tile_rects({img.width, img.height, size});
  if (seed) std::shuffle(rects.begin(), rects.end(), std::mt19937(seed));
  for (const TileRect& r : rects) w.tile(r, crop(img, r).data());
}

size_t entries(const fs::path& dir) {
  return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

// Both files read back through read_image, compared value for value: floats
// for EXR/TIFF, and the 8-bit levels (k/255 exactly) for PNG.
void expect_same_as_write_image(const std::string& ext, uint32_t w, uint32_t h, uint32_t size, uint32_t seed,
                                bool expect_tiled) {
  SCOPED_TRACE(ext + " " + std::to_string(w) + "x" + std::to_string(h) + " tile " + std::to_string(size));
  const fs::path dir = test::scratch_dir();
  const Image img = test_image(w, h, seed);
  const std::string tiled_path = (dir / ("tiled" + ext)).string(), whole_path = (dir / ("whole" + ext)).string();
  {
    ImageTileWriter writer(tiled_path, {w, h, size});
    EXPECT_EQ(writer.tiled(), expect_tiled);
    send_tiles(writer, img, size, seed);
    writer.commit();
  }
  write_image(whole_path, img);
  EXPECT_EQ(entries(dir), 2u) << "temporaries left behind";
  const Image a = read_image(tiled_path), b = read_image(whole_path);
  ASSERT_EQ(a.width, w);
  ASSERT_EQ(a.height, h);
  ASSERT_EQ(b.width, w);
  ASSERT_EQ(b.height, h);
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  EXPECT_EQ(std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)), 0);
  if (ext != ".png") {
    EXPECT_EQ(std::memcmp(a.rgba.data(), img.rgba.data(), a.rgba.size() * sizeof(float)), 0);
  }
  fs::remove_all(dir);
}

TEST(TileWriter, ExrShuffledTilesEqualWholeImage) {
  expect_same_as_write_image(".exr", 130, 67, 32, 7, true);
  expect_same_as_write_image(".exr", 256, 128, 64, 3, true);
  expect_same_as_write_image(".exr", 100, 50, 8, 5, true);  // EXR takes any tile size
}
TEST(TileWriter, TiffShuffledTilesEqualWholeImage) {
  expect_same_as_write_image(".tif", 130, 67, 32, 7, true);
  expect_same_as_write_image(".tif", 256, 128, 64, 3, true);
  // libtiff wants tiles in multiples of 16: striped, through the band path.
  expect_same_as_write_image(".tif", 100, 50, 8, 5, false);
}
TEST(TileWriter, PngShuffledTilesEqualWholeImageByteForByte) {
  expect_same_as_write_image(".png", 130, 67, 32, 7, false);
  expect_same_as_write_image(".png", 256, 128, 64, 3, false);
  expect_same_as_write_image(".png", 100, 50, 8, 5, false);
}
TEST(TileWriter, OnePixelImage) {
  for (const char* ext : {".exr", ".tif", ".png"}) expect_same_as_write_image(ext, 1, 1, 64, 11, ext[1] != 'p');
}
TEST(TileWriter, ImageSmallerThanOneTileAndOneTileWide) {
  for (const char* ext : {".exr", ".tif", ".png"}) {
    expect_same_as_write_image(ext, 40, 90, 64, 2, ext[1] != 'p');
    expect_same_as_write_image(ext, 64, 200, 64, 4, ext[1] != 'p');
  }
}

TEST(TileWriter, PngHoldsOnlyOutOfOrderBands) {
  const fs::path dir = test::scratch_dir();
  const Image img = test_image(300, 200);
  const uint64_t band = 300 * 32 * 4;  // one row of 32-pixel tiles, 8-bit RGBA
  {
    ImageTileWriter w((dir / "rows.png").string(), {300, 200, 32});
    EXPECT_GE(w.buffer_bytes_estimate(), 2 * band);
    EXPECT_LT(w.buffer_bytes_estimate(), uint64_t(300) * 200 * 16 / 2) << "estimate should be far below an image";
    send_tiles(w, img, 32, 0);  // row-major: each band is written as soon as it is complete
    w.commit();
    EXPECT_EQ(w.peak_buffer_bytes(), band);
  }
  {
    ImageTileWriter w((dir / "exr.exr").string(), {300, 200, 32});
    send_tiles(w, img, 32, 9);
    w.commit();
    EXPECT_EQ(w.peak_buffer_bytes(), 0u) << "tiled formats go straight to disk";
  }
  fs::remove_all(dir);
}

TEST(TileWriter, DestroyedWithoutCommitLeavesNothing) {
  const fs::path dir = test::scratch_dir();
  const Image img = test_image(130, 67);
  for (const char* ext : {".exr", ".tif", ".png"}) {
    // Quietly: a render that fails prints its own one-line error, nothing else.
    testing::internal::CaptureStderr();
    {
      ImageTileWriter w((dir / (std::string("partial") + ext)).string(), {130, 67, 32});
      std::vector<TileRect> rects = tile_rects({130, 67, 32});
      for (size_t i = 0; i < rects.size() / 2; ++i) w.tile(rects[i], crop(img, rects[i]).data());
    }
    {
      ImageTileWriter w((dir / (std::string("complete") + ext)).string(), {130, 67, 32});
      send_tiles(w, img, 32, 1);
    }
    {
      ImageTileWriter w((dir / (std::string("empty") + ext)).string(), {130, 67, 32});
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << ext;
    EXPECT_EQ(entries(dir), 0u) << ext;
  }
  fs::remove_all(dir);
}

TEST(TileWriter, MissingTileIsAnErrorAtCommit) {
  const fs::path dir = test::scratch_dir();
  const Image img = test_image(130, 67);
  for (const char* ext : {".exr", ".tif", ".png"}) {
    const std::string path = (dir / (std::string("missing") + ext)).string();
    ImageTileWriter w(path, {130, 67, 32});
    std::vector<TileRect> rects = tile_rects({130, 67, 32});
    for (size_t i = 0; i + 1 < rects.size(); ++i) w.tile(rects[i], crop(img, rects[i]).data());
    try {
      w.commit();
      ADD_FAILURE() << ext << ": commit with a missing tile succeeded";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("1 of 15 tiles"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(path));
  }
  EXPECT_EQ(entries(dir), 0u);
  fs::remove_all(dir);
}

TEST(TileWriter, RejectsTilesOffTheGridAndRepeats) {
  const fs::path dir = test::scratch_dir();
  const std::vector<float> px(64 * 64 * 4, 0.5f);
  for (const char* ext : {".exr", ".png"}) {
    ImageTileWriter w((dir / (std::string("bad") + ext)).string(), {130, 67, 32});
    EXPECT_THROW(w.tile({16, 0, 48, 32}, px.data()), std::runtime_error);   // not on a tile corner
    EXPECT_THROW(w.tile({128, 64, 160, 96}, px.data()), std::runtime_error);  // past the image edge
    EXPECT_THROW(w.tile({0, 0, 16, 32}, px.data()), std::runtime_error);      // not the whole tile
    w.tile({128, 64, 130, 67}, px.data());                                     // the corner tile is fine
    EXPECT_THROW(w.tile({128, 64, 130, 67}, px.data()), std::runtime_error);  // but only once
  }
  EXPECT_EQ(entries(dir), 0u);
  fs::remove_all(dir);
}

TEST(TileWriter, UnwritableDirectoryThrowsNamingThePath) {
  const fs::path dir = test::scratch_dir();
  { std::ofstream(dir / "plainfile") << "x"; }
  for (const char* ext : {".exr", ".tif", ".png"}) {
    for (const fs::path& p : {dir / "no" / "such" / (std::string("out") + ext),
                              dir / "plainfile" / (std::string("out") + ext)}) {
      try {
        ImageTileWriter w(p.string(), {130, 67, 32});
        ADD_FAILURE() << p << ": opened";
      } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(p.string(), 0), 0u) << msg;  // starts with the path
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
      }
    }
  }
  EXPECT_EQ(entries(dir), 1u);  // just plainfile
  fs::remove_all(dir);
}

// A write that fails part way (the file-size limit stands in for a full
// disk): an error naming the file, from tile() or commit(), and no file.
TEST(TileWriter, FailingWriteLeavesNoFile) {
  const fs::path dir = test::scratch_dir();
  const Image img = test_image(512, 256, 5);  // random floats: barely compressible
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  auto old_handler = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of death
  for (const char* ext : {".exr", ".tif", ".png"}) {
    const std::string path = (dir / (std::string("big") + ext)).string();
    rlimit small = old;
    small.rlim_cur = 64 * 1024;
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
    std::string msg;
    try {
      ImageTileWriter w(path, {512, 256, 64});
      send_tiles(w, img, 64, 3);
      w.commit();
    } catch (const std::runtime_error& e) {
      msg = e.what();
    }
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &old), 0);
    RecordProperty(std::string("message") + ext, msg);
    EXPECT_FALSE(msg.empty()) << ext << ": a write past the file-size limit succeeded";
    EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(entries(dir), 0u) << ext;
  }
  std::signal(SIGXFSZ, old_handler);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace zs
