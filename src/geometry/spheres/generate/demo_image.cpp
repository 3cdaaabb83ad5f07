#include "geometry/spheres/generate/demo_image.h"

#include <cstring>
#include <cstdlib>
#include <map>
#include <memory>

#include <zlib.h>

#include "base/util/file_error.h"

namespace zs {

namespace {

struct GzCloser {
  void operator()(gzFile f) const { gzclose(f); }
};

size_t octal(const char* p, size_t n) {
  size_t v = 0;
  for (size_t i = 0; i < n && p[i] >= '0' && p[i] <= '7'; ++i) v = v * 8 + size_t(p[i] - '0');
  return v;
}

}  // namespace

std::string read_tar_gz_member(const std::string& tarball, const std::string& member) {
  std::unique_ptr<gzFile_s, GzCloser> gz(gzopen(tarball.c_str(), "rb"));
  if (!gz) throw FileError(tarball, "cannot read (install Debian's libcgal-demo for its data.tar.gz)");
  gzbuffer(gz.get(), 1 << 20);
  char h[512];
  while (gzread(gz.get(), h, 512) == 512) {
    if (h[0] == 0) break;  // the end-of-archive blocks
    std::string name(h, strnlen(h, 100));
    if (std::memcmp(h + 257, "ustar", 5) == 0 && h[345]) name = std::string(h + 345, strnlen(h + 345, 155)) + "/" + name;
    const size_t size = octal(h + 124, 12), padded = (size + 511) / 512 * 512;
    if (name == member || name == "./" + member) {
      std::string data(size, '\0');
      if (size && gzread(gz.get(), data.data(), unsigned(size)) != int(size))
        throw FileError(tarball, "truncated member " + member);
      return data;
    }
    if (gzseek(gz.get(), z_off_t(padded), SEEK_CUR) < 0) break;
  }
  throw FileError(tarball, "no member " + member);
}

ScalarImage parse_inr(const std::string& bytes, const std::string& name) {
  if (bytes.rfind("#INRIMAGE-4#{", 0) != 0) throw FileError(name, "not an INRIMAGE-4 file");
  const size_t end = bytes.find("##}\n");
  if (end == std::string::npos) throw FileError(name, "INR header without its closing \"##}\"");
  const size_t header = (end + 4 + 255) / 256 * 256;
  std::map<std::string, std::string> kv;
  for (size_t p = bytes.find('\n') + 1; p < end;) {
    size_t nl = bytes.find('\n', p);
    const std::string line = bytes.substr(p, nl - p);
    p = nl + 1;
    const size_t eq = line.find('=');
    if (eq != std::string::npos) kv[line.substr(0, eq)] = line.substr(eq + 1);
  }
  auto num = [&](const char* k, double dflt) { return kv.count(k) ? std::atof(kv[k].c_str()) : dflt; };
  ScalarImage img;
  img.nx = size_t(num("XDIM", 0)), img.ny = size_t(num("YDIM", 0)), img.nz = size_t(num("ZDIM", 0));
  img.spacing = {num("VX", 1), num("VY", 1), num("VZ", 1)};
  const int bits = std::atoi(kv["PIXSIZE"].c_str());
  const std::string type = kv["TYPE"], cpu = kv.count("CPU") ? kv["CPU"] : "decm";
  if (num("VDIM", 1) != 1) throw FileError(name, "INR image with VDIM other than 1 (not scalar)");
  const bool is_float = type == "float" && (bits == 32 || bits == 64);
  const bool is_uint = type == "unsigned fixed" && (bits == 8 || bits == 16);
  if (!is_float && !is_uint) throw FileError(name, "INR voxel type '" + type + "' of " + std::to_string(bits) + " bits not supported");
  const bool big = cpu == "sun" || cpu == "sgi";
  const size_t n = img.nx * img.ny * img.nz, bpv = size_t(bits) / 8;
  if (n == 0 || bytes.size() < header + n * bpv) throw FileError(name, "INR image truncated or empty");
  img.values.resize(n);
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + header;
  for (size_t i = 0; i < n; ++i, p += bpv) {
    unsigned char b[8];
    for (size_t k = 0; k < bpv; ++k) b[k] = big ? p[bpv - 1 - k] : p[k];  // to little-endian
    if (bits == 8) img.values[i] = b[0];
    else if (bits == 16) img.values[i] = float(b[0] | b[1] << 8);
    else if (bits == 32) { float f; std::memcpy(&f, b, 4); img.values[i] = f; }
    else { double d; std::memcpy(&d, b, 8); img.values[i] = float(d); }
  }
  return img;
}

}  // namespace zs
