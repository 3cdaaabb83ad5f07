// The .sphb reader and writer: fixed header, then float32 records converted
// chunk by chunk so a 27-million-sphere file never sits in memory whole.
#include "geometry/spheres/sphere_binary.h"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <vector>

#include "geometry/spheres/sphere_validity.h"
#include "base/util/atomic_file.h"
#include "base/util/file_error.h"
#include "base/util/input_file.h"

namespace zs {

namespace {

static_assert(std::endian::native == std::endian::little || std::endian::native == std::endian::big);
constexpr bool kSwap = std::endian::native == std::endian::big;  // the file is little-endian

uint32_t load_u32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
uint64_t load_u64(const unsigned char* p) { return uint64_t(load_u32(p)) | uint64_t(load_u32(p + 4)) << 32; }
void store_u32(unsigned char* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void store_u64(unsigned char* p, uint64_t v) {
  store_u32(p, uint32_t(v));
  store_u32(p + 4, uint32_t(v >> 32));
}

void fix_endian(float* f, size_t n) {
  if constexpr (kSwap) {
    for (size_t i = 0; i < n; ++i) {
      uint32_t u;
      std::memcpy(&u, &f[i], 4);
      u = __builtin_bswap32(u);
      std::memcpy(&f[i], &u, 4);
    }
  }
}

struct Header {
  uint32_t fields = 0;
  uint64_t count = 0;
};

// Checks the header against the total size in bytes; throws FileError.
Header check_header(const unsigned char* h, size_t avail, uint64_t total, const std::string& name) {
  if (avail < 8 || std::memcmp(h, kSphbMagic, 8) != 0)
    throw FileError(name, "not a .sphb file (it does not start with \"ZSSPHB1\\n\")");
  if (avail < kSphbHeaderBytes)
    throw FileError(name, "truncated: " + std::to_string(avail) + " bytes, shorter than the 24-byte header");
  Header hd;
  hd.fields = load_u32(h + 8);
  if (hd.fields != 4 && hd.fields != 5 && hd.fields != 8)
    throw FileError(name, "field count " + std::to_string(hd.fields) + " in the header (expected 4, 5 or 8)");
  if (const uint32_t r = load_u32(h + 12); r != 0)
    throw FileError(name, "reserved header field is " + std::to_string(r) + " (expected 0)");
  hd.count = load_u64(h + 16);
  if (hd.count == 0) throw FileError(name, "no spheres (the header's count is 0)");
  const uint64_t per = uint64_t(hd.fields) * 4;
  const uint64_t body = total - kSphbHeaderBytes;
  if (hd.count > body / per)
    throw FileError(name, "truncated: the header says " + std::to_string(hd.count) + " spheres of " +
                              std::to_string(hd.fields) + " floats (" + std::to_string(kSphbHeaderBytes + hd.count * per) +
                              " bytes), the file has " + std::to_string(total) + " bytes");
  if (body != hd.count * per)
    throw FileError(name, std::to_string(body - hd.count * per) + " bytes after the " + std::to_string(hd.count) +
                              " spheres the header announces");
  return hd;
}

// Appends the spheres of n records (fields floats each), the first being
// sphere number `first` of the file.
void decode(const float* f, size_t n, uint32_t fields, uint64_t first, SphereSet& s, const std::string& name) {
  for (size_t i = 0; i < n; ++i, f += fields) {
    if (fields == 8)
      for (int k = 4; k < 8; ++k)
        if (!valid_rgba_component(f[k])) {
          char v[32];
          std::snprintf(v, sizeof v, "%.9g", double(f[k]));
          throw FileError(name, "sphere " + std::to_string(first + i) + ": " + std::string(1, "RGBA"[k - 4]) + " " + v +
                                    " is not in [0, 1]");
        }
    if (!drawable_sphere(f[0], f[1], f[2], f[3])) {
      ++s.invalid;
      continue;
    }
    s.centres.push_back({f[0], f[1], f[2]});
    s.radii.push_back(f[3]);
    if (fields == 5) {
      s.scalars.push_back(f[4]);
      if (!std::isfinite(f[4])) ++s.degenerate;
    }
    if (fields == 8) s.rgba.push_back({f[4], f[5], f[6], f[7]});
  }
}

void start(SphereSet& s, const Header& h) {
  s.centres.reserve(h.count);
  s.radii.reserve(h.count);
  if (h.fields == 5) s.scalars.reserve(h.count), s.scalar_name = "scalar";
  if (h.fields == 8) s.rgba.reserve(h.count);
}

void finish(SphereSet& s, const std::string& name) {
  if (s.centres.empty())
    throw FileError(name, "no drawable spheres: all " + std::to_string(s.invalid) +
                              " have a zero, negative or non-finite radius or a non-finite centre");
  if (s.invalid)
    s.notes.push_back(std::to_string(s.invalid) + " spheres skipped: zero, negative or non-finite radius, or non-finite centre");
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

constexpr size_t kChunkSpheres = 1 << 16;  // 2 MB of 8-field records

}  // namespace

unsigned sphere_fields(const SphereSet& s) { return s.has_rgba() ? 8 : s.has_scalars() ? 5 : 4; }

SphereSet parse_spheres_binary(std::string_view bytes, const std::string& name) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  const Header h = check_header(p, bytes.size(), bytes.size(), name);
  SphereSet s;
  start(s, h);
  std::vector<float> buf(size_t(std::min<uint64_t>(h.count, kChunkSpheres)) * h.fields);
  for (uint64_t done = 0; done < h.count;) {
    const size_t n = size_t(std::min<uint64_t>(h.count - done, kChunkSpheres));
    std::memcpy(buf.data(), p + kSphbHeaderBytes + done * h.fields * 4, n * h.fields * 4);  // alignment-safe
    fix_endian(buf.data(), n * h.fields);
    decode(buf.data(), n, h.fields, done, s, name);
    done += n;
  }
  finish(s, name);
  return s;
}

SphereSet read_spheres_binary(const std::string& path) {
  require_input_file(path, "a sphere file");
  std::error_code ec;
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) throw FileError(path, std::string("cannot read: ") + std::strerror(errno));
  const auto total = std::filesystem::file_size(path, ec);
  if (ec) throw FileError(path, "cannot read: " + ec.message());
  unsigned char head[kSphbHeaderBytes] = {};
  const size_t got = std::fread(head, 1, kSphbHeaderBytes, f.get());
  const Header h = check_header(head, got, total, path);
  SphereSet s;
  start(s, h);
  std::vector<float> buf(size_t(std::min<uint64_t>(h.count, kChunkSpheres)) * h.fields);
  for (uint64_t done = 0; done < h.count;) {
    const size_t n = size_t(std::min<uint64_t>(h.count - done, kChunkSpheres));
    if (std::fread(buf.data(), 4 * h.fields, n, f.get()) != n)
      throw FileError(path, "cannot read: " + std::string(std::ferror(f.get()) ? std::strerror(errno) : "file shrank while reading"));
    fix_endian(buf.data(), n * h.fields);
    decode(buf.data(), n, h.fields, done, s, path);
    done += n;
  }
  finish(s, path);
  return s;
}

void write_spheres_binary(const std::string& path, const SphereSet& s) {
  const unsigned fields = sphere_fields(s);
  constexpr double kMaxF = std::numeric_limits<float>::max();
  auto fits = [&](double v) { return std::isfinite(v) && std::fabs(v) <= kMaxF; };
  AtomicFile out(path);
  out.check_writable();
  {
    File f(std::fopen(out.temp_path().c_str(), "wb"));
    if (!f) throw FileError(path, std::string("cannot write: ") + std::strerror(errno));
    unsigned char head[kSphbHeaderBytes];
    std::memcpy(head, kSphbMagic, 8);
    store_u32(head + 8, fields);
    store_u32(head + 12, 0);
    store_u64(head + 16, s.size());
    bool ok = std::fwrite(head, 1, sizeof head, f.get()) == sizeof head;
    std::vector<float> buf(size_t(std::min<size_t>(s.size(), kChunkSpheres)) * fields);
    for (size_t done = 0; ok && done < s.size();) {
      const size_t n = std::min<size_t>(s.size() - done, kChunkSpheres);
      float* o = buf.data();
      for (size_t i = done; i < done + n; ++i, o += fields) {
        const glm::dvec3& c = s.centres[i];
        if (!fits(c.x) || !fits(c.y) || !fits(c.z) || !fits(s.radii[i]))
          throw FileError(path, "cannot write sphere " + std::to_string(i) +
                                    ": centre or radius is not finite or beyond float32's range");
        o[0] = float(c.x), o[1] = float(c.y), o[2] = float(c.z), o[3] = float(s.radii[i]);
        if (fields == 5) o[4] = float(s.scalars[i]);
        if (fields == 8) o[4] = s.rgba[i].r, o[5] = s.rgba[i].g, o[6] = s.rgba[i].b, o[7] = s.rgba[i].a;
      }
      fix_endian(buf.data(), n * fields);
      ok = std::fwrite(buf.data(), 4 * fields, n, f.get()) == n;
      done += n;
    }
    if (!ok || std::fflush(f.get()) != 0) throw FileError(path, std::string("cannot write: ") + std::strerror(errno));
    if (std::fclose(f.release()) != 0) throw FileError(path, std::string("cannot write: ") + std::strerror(errno));
  }
  out.commit();
}

}  // namespace zs
