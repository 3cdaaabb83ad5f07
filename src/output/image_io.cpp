#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <vector>
#include <stdexcept>

#include "output/image_io.h"
#include "output/pixel_quantize.h"
#include "base/util/atomic_file.h"
#include "base/util/input_file.h"

namespace zs {

std::string output_compression(const std::string& format, const std::string& requested, const std::string& path) {
  static const std::vector<std::string> exr = {"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"};
  static const std::vector<std::string> tiff = {"none", "lzw", "zip", "packbits"};
  const std::vector<std::string>* names = format == "openexr" ? &exr : format == "tiff" ? &tiff : nullptr;
  if (requested.empty()) return format == "openexr" ? "rle" : "";
  if (!names) throw std::runtime_error(path + ": --compression applies to .exr and .tif outputs only");
  if (std::find(names->begin(), names->end(), requested) == names->end()) {
    std::string list;
    for (const auto& n : *names) list += (list.empty() ? "" : ", ") + n;
    throw std::runtime_error(path + ": unknown compression \"" + requested + "\" (" + format + ": " + list + ")");
  }
  return requested;
}

void write_image(const std::string& path, const Image& img, const std::string& compression) {
  auto file = OIIO::ImageOutput::create(path);
  if (!file) throw std::runtime_error(path + ": unsupported image format: " + OIIO::geterror());
  const std::string fmt = file->format_name();
  const std::string comp = output_compression(fmt, compression, path);
  AtomicFile out(path);
  const bool is_float = fmt == "openexr" || fmt == "tiff";
  OIIO::ImageSpec spec(int(img.width), int(img.height), 4, is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (!comp.empty()) spec.attribute("compression", comp);
  spec.attribute("oiio:ColorSpace", "Linear");
  // Store our values as they are (8-bit ones already straight,
  // pixel_quantize.h): OIIO would otherwise convert them itself.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  // Messages name the output, not its temporary, and say why.
  const auto fail = [&] {
    const int err = errno;
    std::string e = out.name_final(file->geterror());
    std::replace(e.begin(), e.end(), '\n', ' ');
    if (err != 0 && e.find(std::strerror(err)) == std::string::npos)
      e += (e.empty() ? "" : ": ") + std::string(std::strerror(err));
    throw std::runtime_error(path + ": cannot write: " + e);
  };
  errno = 0;
  if (!file->open(out.temp_path(), spec)) fail();
  bool ok;
  errno = 0;
  if (is_float) {
    ok = file->write_image(OIIO::TypeDesc::FLOAT, img.rgba.data());
  } else {
    // The float image with straight alpha, quantized; no gamma (scene spec).
    std::vector<uint8_t> q(img.rgba.size());
    for (size_t i = 0; i < q.size(); i += 4) quantize_straight(&img.rgba[i], &q[i]);
    ok = file->write_image(OIIO::TypeDesc::UINT8, q.data());
  }
  if (!ok || !file->close()) fail();
  out.commit();
}

Image read_image(const std::string& path) {
  require_input_file(path, "an image");
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // the stored values, unconverted
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw std::runtime_error(path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels < 1) throw std::runtime_error(path + ": image has no channels");
  Image img(uint32_t(spec.width), uint32_t(spec.height));
  std::vector<float> buf(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, buf.data()))
    throw std::runtime_error(path + ": cannot read image: " + in->geterror());
  // 8-bit formats hold straight alpha (as zsweep writes them); the float
  // ones premultiplied, like our images.
  const std::string fmt = in->format_name();
  const bool straight = spec.nchannels >= 4 && fmt != "openexr" && fmt != "tiff";
  for (size_t p = 0; p < size_t(spec.width) * spec.height; ++p) {
    for (int c = 0; c < 4; ++c)
      img.rgba[p * 4 + c] = c < spec.nchannels ? buf[p * spec.nchannels + c] : (c == 3 ? 1.f : 0.f);
    if (straight) premultiply(&img.rgba[p * 4]);
  }
  return img;
}

std::vector<float> read_depth_channel(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error(path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  int zc = -1;
  for (int c = 0; c < spec.nchannels; ++c)
    if (spec.channelnames[size_t(c)] == "Z") zc = c;
  if (zc < 0) return {};
  std::vector<float> z(size_t(spec.width) * spec.height);
  if (!in->read_image(0, 0, zc, zc + 1, OIIO::TypeDesc::FLOAT, z.data()))
    throw std::runtime_error(path + ": cannot read image: " + in->geterror());
  return z;
}

}  // namespace zs
