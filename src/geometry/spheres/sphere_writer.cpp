#include "geometry/spheres/sphere_writer.h"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <memory>

#include "geometry/spheres/sphere_binary.h"
#include "base/util/atomic_file.h"
#include "base/util/file_error.h"

namespace zs {

namespace {

// A value that is exactly a float32 (data from .sphb or the generators):
// the shortest text whose double rounds back to that float, checked, since
// the reader parses doubles and the binary writer rounds them to float. Any
// other double: the shortest text that reads back as exactly that double.
void append_number(std::string& out, double v) {
  char buf[40];
  const float f = float(v);
  if (double(f) == v) {
    const auto r = std::to_chars(buf, buf + sizeof buf, f);
    double back = 0;
    const auto p = std::from_chars(buf, r.ptr, back);
    if (p.ec == std::errc() && float(back) == f) {
      out.append(buf, r.ptr);
      return;
    }
  }
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

}  // namespace

std::string format_spheres_text(const SphereSet& s) {
  const unsigned fields = sphere_fields(s);
  std::string out = fields == 8 ? "# x y z r R G B A\n" : fields == 5 ? "# x y z r " + s.scalar_name + "\n" : "# x y z r\n";
  out.reserve(out.size() + s.size() * (fields * 10));
  for (size_t i = 0; i < s.size(); ++i) {
    const double v[8] = {s.centres[i].x, s.centres[i].y, s.centres[i].z, s.radii[i],
                         fields == 5 ? s.scalars[i] : fields == 8 ? s.rgba[i].r : 0.0,
                         fields == 8 ? s.rgba[i].g : 0.0, fields == 8 ? s.rgba[i].b : 0.0,
                         fields == 8 ? s.rgba[i].a : 0.0};
    for (unsigned k = 0; k < fields; ++k) {
      if (k) out += ' ';
      append_number(out, v[k]);
    }
    out += '\n';
  }
  return out;
}

void write_spheres_text(const std::string& path, const SphereSet& s) {
  AtomicFile out(path);
  out.check_writable();
  const std::string text = format_spheres_text(s);
  {
    std::FILE* f = std::fopen(out.temp_path().c_str(), "wb");
    if (!f) throw FileError(path, std::string("cannot write: ") + std::strerror(errno));
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    const int err = errno;
    if (std::fclose(f) != 0 || !ok) throw FileError(path, std::string("cannot write: ") + std::strerror(ok ? errno : err));
  }
  out.commit();
}

}  // namespace zs
