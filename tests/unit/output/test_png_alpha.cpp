// 8-bit outputs hold straight alpha (PNG's definition), both writers alike;
// reading them back premultiplies again. See output/pixel_quantize.h.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "output/image_io.h"
#include "output/pixel_quantize.h"
#include "output/tile_writer.h"
#include "support/test_paths.h"

namespace zs {
namespace {

namespace fs = std::filesystem;

// Straight colours and alphas chosen per pixel; the image holds them
// premultiplied, as every renderer hands them over.
struct Px {
  float r, g, b, a;
};
const std::vector<Px> kPixels = {
    {0.49f, 0.53f, 0.80f, 0.2f},  // the kiefer pixel: (25, 27, 41, 51) premultiplied
    {1.f, 0.5f, 0.25f, 0.5f},     {0.2f, 0.9f, 0.4f, 0.05f}, {0.3f, 0.6f, 0.9f, 1.f},
    {0.7f, 0.7f, 0.7f, 0.f},      {0.1f, 1.f, 0.f, 0.999f},
};

Image premultiplied_image() {
  Image img(uint32_t(kPixels.size()), 3);
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) {
      const Px& p = kPixels[x];
      float* o = img.at(x, y);
      o[0] = p.r * p.a, o[1] = p.g * p.a, o[2] = p.b * p.a, o[3] = p.a;
    }
  return img;
}

std::vector<uint8_t> raw_bytes(const std::string& path) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // the bytes as stored
  auto in = OIIO::ImageInput::open(path, &config);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return {};
  std::vector<uint8_t> b(size_t(in->spec().width) * in->spec().height * 4);
  EXPECT_EQ(in->spec().nchannels, 4);
  EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, b.data()));
  return b;
}

void expect_straight(const std::string& path) {
  const std::vector<uint8_t> b = raw_bytes(path);
  ASSERT_EQ(b.size(), kPixels.size() * 3 * 4);
  for (size_t i = 0; i < b.size() / 4; ++i) {
    const Px& p = kPixels[i % kPixels.size()];
    SCOPED_TRACE("pixel " + std::to_string(i));
    EXPECT_EQ(b[i * 4 + 3], uint8_t(p.a * 255.f + 0.5f));
    if (p.a == 0.f) {
      EXPECT_EQ(b[i * 4 + 0] | b[i * 4 + 1] | b[i * 4 + 2], 0);  // undefined colour stored as 0
      continue;
    }
    const float want[3] = {p.r, p.g, p.b};
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[i * 4 + c], want[c] * 255.f, 0.51f) << "channel " << c;
  }
  // read_image gives premultiplied values back, within the 8-bit rounding
  // of colour and alpha.
  const Image back = read_image(path), orig = premultiplied_image();
  for (size_t i = 0; i < orig.rgba.size(); ++i) EXPECT_NEAR(back.rgba[i], orig.rgba[i], 1.01f / 255.f) << i;
}

TEST(PngAlpha, WriteImageStoresStraightAlpha) {
  const fs::path dir = test::scratch_dir();
  write_image((dir / "a.png").string(), premultiplied_image());
  expect_straight((dir / "a.png").string());
  fs::remove_all(dir);
}

TEST(PngAlpha, TileWriterStoresStraightAlpha) {
  const fs::path dir = test::scratch_dir();
  const Image img = premultiplied_image();
  ImageTileWriter w((dir / "t.png").string(), {img.width, img.height, 4});
  for (uint32_t y = 0; y < img.height; y += 4)
    for (uint32_t x = 0; x < img.width; x += 4) {
      const TileRect r{x, y, std::min(x + 4, img.width), std::min(y + 4, img.height)};
      std::vector<float> t;
      for (uint32_t yy = r.y0; yy < r.y1; ++yy) t.insert(t.end(), img.at(r.x0, yy), img.at(r.x1 - 1, yy) + 4);
      w.tile(r, t.data());
    }
  w.commit();
  expect_straight((dir / "t.png").string());
  fs::remove_all(dir);
}

TEST(PngAlpha, FloatFormatsStayPremultiplied) {
  const fs::path dir = test::scratch_dir();
  const Image img = premultiplied_image();
  for (const char* ext : {".exr", ".tif"}) {
    const std::string p = (dir / (std::string("f") + ext)).string();
    write_image(p, img);
    const Image back = read_image(p);
    EXPECT_EQ(back.rgba, img.rgba) << ext;
  }
  fs::remove_all(dir);
}

TEST(PngAlpha, OpaquePixelsQuantizeAsBefore) {
  // α = 1 must give exactly the old premultiplied bytes: opaque renders'
  // PNGs are unchanged.
  for (int k = 0; k <= 255; ++k) {
    const float v = (float(k) + 0.5f) / 255.f, px[4] = {v, 1.f - v, v * 0.5f, 1.f};
    uint8_t out[4];
    quantize_straight(px, out);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(out[c], quantize_unit(px[c]));
  }
}

}  // namespace
}  // namespace zs
