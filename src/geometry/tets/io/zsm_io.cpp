// The .zsm reader and writer. The header is checked whole (magic, version,
// checksum, then every count and section against the file's size) before
// anything is allocated; then each section is read straight into its array
// in blocks, each block hashed while it is still in cache.
#include "geometry/tets/io/zsm_io.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/util/atomic_file.h"
#include "base/util/checksum.h"
#include "base/util/file_error.h"
#include "base/util/input_file.h"

namespace zs {

// The sections are the arrays' bytes as they lie in memory.
static_assert(std::endian::native == std::endian::little, ".zsm is little-endian and read without conversion");
static_assert(sizeof(glm::dvec3) == 24 && sizeof(Tet) == 16);

namespace {

enum Sec { kPoints, kScalars, kTets, kStrings, kNumSec };
constexpr const char* kSecName[kNumSec] = {"points", "scalars", "tets", "strings"};
constexpr uint32_t kFlagScalars = 1;      // the scalars section: one per point
constexpr uint32_t kFlagCellScalars = 2;  // the scalars section: one per tet (cell data)
constexpr uint64_t kAlign = 64;
constexpr size_t kSecTable = 40, kReserved = 136, kHeaderSum = 184;  // header offsets (docs/mesh.md)
// Reads and writes go in blocks this large: few calls, and a block is still
// in the core's cache when it is hashed.
constexpr size_t kBlock = size_t(1) << 20;

uint32_t load_u32(const unsigned char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}
uint64_t load_u64(const unsigned char* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}
void store_u32(unsigned char* p, uint32_t v) { std::memcpy(p, &v, 4); }
void store_u64(unsigned char* p, uint64_t v) { std::memcpy(p, &v, 8); }

std::string num(uint64_t v) { return std::to_string(v); }

struct Section {
  uint64_t offset = 0, size = 0, sum = 0;
  uint64_t end() const { return offset + size; }  // checked not to overflow before use
};

struct Header {
  uint32_t flags = 0;
  uint64_t points = 0, tets = 0, notes = 0;
  Section sec[kNumSec];
};

// Copies n bytes from `offset` of the input to dst; throws FileError.
using ReadAt = std::function<void(uint64_t offset, char* dst, size_t n)>;

// The header, from the first `avail` bytes of the input: magic, length,
// version, checksum, then what version 1 leaves unused.
Header decode_header(const unsigned char* h, size_t avail, const std::string& name) {
  if (avail == 0)
    throw FileError(name, "empty file (a .zsm file starts with a " + num(kZsmHeaderBytes) + "-byte header)");
  if (std::memcmp(h, kZsmMagic, std::min(avail, sizeof kZsmMagic)) != 0)
    throw FileError(name, "not a .zsm file (bad magic)");
  if (avail < kZsmHeaderBytes)
    throw FileError(name, "truncated: " + num(avail) + " bytes, shorter than the " + num(kZsmHeaderBytes) +
                              "-byte header");
  // The version before the checksum: a newer version may lay its header out differently.
  const uint32_t version = load_u32(h + 8);
  if (version > kZsmVersion)
    throw FileError(name, "version " + num(version) + " is newer than this zsweep reads (" + num(kZsmVersion) + ")");
  if (version == 0) throw FileError(name, "version 0 in the header (versions start at 1)");
  if (checksum64(h, kHeaderSum) != load_u64(h + kHeaderSum)) throw FileError(name, "checksum mismatch in the header");
  Header hd;
  hd.flags = load_u32(h + 12);
  if ((hd.flags & ~(kFlagScalars | kFlagCellScalars)) || hd.flags == (kFlagScalars | kFlagCellScalars)) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%x", unsigned(hd.flags));
    throw FileError(name, std::string(hd.flags & ~(kFlagScalars | kFlagCellScalars) ? "unknown" : "contradictory") +
                              " flags " + hex + " in the header (version 1 defines 0x1, point scalars, or 0x2, "
                              "cell scalars)");
  }
  for (size_t i = kReserved; i < kHeaderSum; ++i)
    if (h[i] != 0) throw FileError(name, "reserved header byte " + num(i) + " is not zero");
  hd.points = load_u64(h + 16);
  hd.tets = load_u64(h + 24);
  hd.notes = load_u64(h + 32);
  for (int s = 0; s < kNumSec; ++s) {
    const unsigned char* e = h + kSecTable + 24 * s;
    hd.sec[s] = {load_u64(e), load_u64(e + 8), load_u64(e + 16)};
  }
  return hd;
}

void encode_header(unsigned char* h, const Header& hd) {
  std::memset(h, 0, kZsmHeaderBytes);
  std::memcpy(h, kZsmMagic, sizeof kZsmMagic);
  store_u32(h + 8, kZsmVersion);
  store_u32(h + 12, hd.flags);
  store_u64(h + 16, hd.points);
  store_u64(h + 24, hd.tets);
  store_u64(h + 32, hd.notes);
  for (int s = 0; s < kNumSec; ++s) {
    unsigned char* e = h + kSecTable + 24 * s;
    store_u64(e, hd.sec[s].offset);
    store_u64(e + 8, hd.sec[s].size);
    store_u64(e + 16, hd.sec[s].sum);
  }
  store_u64(h + kHeaderSum, checksum64(h, kHeaderSum));
}

// count * width bytes, which the `total`-byte file must be able to hold:
// a header that says more is refused before anything is allocated.
uint64_t bytes_for(uint64_t count, uint64_t width, const std::string& what, uint64_t total, const std::string& name) {
  uint64_t bytes = 0;
  const bool overflow = __builtin_mul_overflow(count, width, &bytes);
  if (overflow || bytes > total)
    throw FileError(name, "truncated: the header says " + num(count) + " " + what + " (" +
                              (overflow ? "over 2^64" : num(bytes)) + " bytes), the file has " + num(total) + " bytes");
  return bytes;
}

uint64_t align_up(uint64_t at) { return (at + kAlign - 1) / kAlign * kAlign; }

// The sections in their order, each of exactly the size its count implies
// and at the first multiple of 64 after the one before (the header for the
// first), inside the file, and nothing after the last one: every byte of a
// file has one place, so every byte is checked (checksums, zero padding).
void check_layout(const Header& h, uint64_t total, const std::string& name) {
  uint64_t want[kNumSec];
  want[kPoints] = bytes_for(h.points, 24, "points", total, name);
  want[kTets] = bytes_for(h.tets, 16, "tets", total, name);
  want[kScalars] = h.flags & kFlagScalars ? h.points * 8 : h.flags & kFlagCellScalars ? h.tets * 8 : 0;
  want[kStrings] = bytes_for(h.notes, 8, "notes", total, name) + 16;  // a length per string, at least
  uint64_t at = kZsmHeaderBytes;  // <= total throughout
  for (int s = 0; s < kNumSec; ++s) {
    const Section& c = h.sec[s];
    const std::string what = std::string("the ") + kSecName[s] + " section";
    const bool per_tet = s == kTets || (s == kScalars && (h.flags & kFlagCellScalars));
    const std::string count = per_tet ? num(h.tets) + " tets" : num(h.points) + " points";
    if (s != kStrings && c.size != want[s])
      throw FileError(name, what + " is " + num(c.size) + " bytes, " + count + " need " + num(want[s]));
    if (s == kStrings && c.size < want[s])
      throw FileError(name, what + " is " + num(c.size) + " bytes, too short for " + num(h.notes + 2) + " strings");
    if (c.offset != align_up(at))
      throw FileError(name, what + " starts at byte " + num(c.offset) + " (expected " + num(align_up(at)) + ")");
    if (c.offset > total || c.size > total - c.offset)
      throw FileError(name, "truncated: " + what + " needs " + num(c.size) + " bytes from byte " + num(c.offset) +
                                ", the file has " + num(total));
    at = c.end();
  }
  if (total != at)
    throw FileError(name, num(total - at) + " bytes after the last section, which ends at byte " + num(at));
}

// Reads section s into dst, hashing each block as it arrives, and the
// padding before it, which must be zero.
void read_section(const ReadAt& read_at, const Header& h, int s, char* dst, const std::string& name) {
  const Section& c = h.sec[s];
  const uint64_t before = s == 0 ? kZsmHeaderBytes : h.sec[s - 1].end();
  char pad[kAlign] = {};
  read_at(before, pad, size_t(c.offset - before));  // < 64 bytes (check_layout)
  for (uint64_t i = 0; i < c.offset - before; ++i)
    if (pad[i] != 0)
      throw FileError(name, std::string("the padding before the ") + kSecName[s] + " section is not zero");
  Checksum64 sum;
  for (uint64_t done = 0; done < c.size;) {
    const size_t n = size_t(std::min<uint64_t>(c.size - done, kBlock));
    read_at(c.offset + done, dst + done, n);
    sum.update(dst + done, n);
    done += n;
  }
  if (sum.digest() != c.sum) throw FileError(name, std::string("checksum mismatch in the ") + kSecName[s] + " section");
}

// Vertex indices < the point count, as the text readers require; `what`
// prefixes the message ("cannot write: " for the writer).
void check_indices(const TetMesh& m, const std::string& name, const std::string& what) {
  const uint32_t* idx = m.tets.empty() ? nullptr : m.tets[0].data();
  const size_t n = 4 * m.tets.size();
  uint32_t hi = 0;
  for (size_t i = 0; i < n; ++i) hi = std::max(hi, idx[i]);  // vectorized; the culprit is looked for only if needed
  if (n == 0 || hi < m.points.size()) return;
  size_t i = 0;
  while (idx[i] < m.points.size()) ++i;
  throw FileError(name, what + "tet " + num(i / 4) + ": vertex index " + num(idx[i]) + " out of range (mesh has " +
                            num(m.points.size()) + " vertices, indices are 0-based)");
}

// scalar_name, scalar_choice, then the notes: each a uint64 length and its bytes.
void parse_strings(const std::string& b, TetMesh& m, uint64_t notes, const std::string& name) {
  size_t at = 0;
  auto next = [&](uint64_t i) {
    if (b.size() - at < 8)
      throw FileError(name, "the strings section ends inside string " + num(i) + "'s length");
    const uint64_t len = load_u64(reinterpret_cast<const unsigned char*>(b.data() + at));
    at += 8;
    if (len > b.size() - at)
      throw FileError(name, "string " + num(i) + " of the strings section is " + num(len) + " bytes, past its end");
    std::string s = b.substr(at, len);
    at += len;
    return s;
  };
  m.scalar_name = next(0);
  m.scalar_choice = next(1);
  m.notes.resize(notes);  // notes <= section size / 8, checked
  for (uint64_t i = 0; i < notes; ++i) m.notes[i] = next(i + 2);
  if (at != b.size())
    throw FileError(name, "the strings section has " + num(b.size() - at) + " bytes after its last string");
}

TetMesh read_from(uint64_t total, const ReadAt& read_at, const std::string& name) {
  unsigned char head[kZsmHeaderBytes] = {};
  const size_t avail = size_t(std::min<uint64_t>(total, kZsmHeaderBytes));
  read_at(0, reinterpret_cast<char*>(head), avail);
  const Header h = decode_header(head, avail, name);
  check_layout(h, total, name);
  TetMesh m;
  m.points.resize(h.points);
  std::vector<double>& scalars = h.flags & kFlagCellScalars ? m.cell_scalars : m.scalars;
  if (h.flags & (kFlagScalars | kFlagCellScalars)) scalars.resize(h.flags & kFlagScalars ? h.points : h.tets);
  m.tets.resize(h.tets);
  std::string strings(h.sec[kStrings].size, '\0');
  read_section(read_at, h, kPoints, reinterpret_cast<char*>(m.points.data()), name);
  read_section(read_at, h, kScalars, reinterpret_cast<char*>(scalars.data()), name);
  read_section(read_at, h, kTets, reinterpret_cast<char*>(m.tets.data()), name);
  read_section(read_at, h, kStrings, strings.data(), name);
  check_indices(m, name, "");
  parse_strings(strings, m, h.notes, name);
  return m;
}

std::string strings_of(const TetMesh& m) {
  std::string b;
  auto put = [&](const std::string& s) {
    unsigned char len[8];
    store_u64(len, s.size());
    b.append(reinterpret_cast<const char*>(len), 8);
    b += s;
  };
  put(m.scalar_name);
  put(m.scalar_choice);
  for (const std::string& n : m.notes) put(n);
  return b;
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

TetMesh parse_zsm(std::string_view bytes, const std::string& name) {
  return read_from(bytes.size(), [&](uint64_t off, char* dst, size_t n) {
    if (n > 0) std::memcpy(dst, bytes.data() + off, n);  // never a null pointer, even for 0 bytes
  }, name);
}

TetMesh read_zsm(const std::string& path) {
  require_input_file(path, "a mesh file");
  const Fd file{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  const int fd = file.fd;
  if (fd < 0) throw FileError(path, std::string("cannot read: ") + std::strerror(errno));
  struct stat st;
  if (::fstat(fd, &st) != 0) throw FileError(path, std::string("cannot read: ") + std::strerror(errno));
  return read_from(uint64_t(st.st_size), [&](uint64_t off, char* dst, size_t n) {
    while (n > 0) {
      const ssize_t r = ::pread(fd, dst, n, off_t(off));
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) throw FileError(path, std::string("cannot read: ") + std::strerror(errno));
      if (r == 0) throw FileError(path, "cannot read: the file shrank while being read");
      dst += r, off += uint64_t(r), n -= size_t(r);
    }
  }, path);
}

void write_zsm(const std::string& path, const TetMesh& m) {
  if (m.has_scalars() && m.scalars.size() != m.points.size())
    throw FileError(path, "cannot write: " + num(m.scalars.size()) + " scalars for " + num(m.points.size()) +
                              " points");
  if (m.has_scalars() && m.has_cell_scalars()) throw FileError(path, "cannot write: both point and cell scalars");
  if (m.has_cell_scalars() && m.cell_scalars.size() != m.tets.size())
    throw FileError(path, "cannot write: " + num(m.cell_scalars.size()) + " cell scalars for " + num(m.tets.size()) +
                              " tets");
  check_indices(m, path, "cannot write: ");
  const std::string strings = strings_of(m);
  const std::vector<double>& scalars = m.scalar_values();
  const char* data[kNumSec] = {reinterpret_cast<const char*>(m.points.data()),
                               reinterpret_cast<const char*>(scalars.data()),
                               reinterpret_cast<const char*>(m.tets.data()), strings.data()};
  Header h;
  h.flags = m.has_scalars() ? kFlagScalars : m.has_cell_scalars() ? kFlagCellScalars : 0;
  h.points = m.points.size();
  h.tets = m.tets.size();
  h.notes = m.notes.size();
  const uint64_t size[kNumSec] = {24 * h.points, 8 * scalars.size(), 16 * h.tets, strings.size()};
  uint64_t at = kZsmHeaderBytes;
  for (int s = 0; s < kNumSec; ++s) {
    at = align_up(at);
    h.sec[s].offset = at;
    h.sec[s].size = size[s];
    at += size[s];
  }
  AtomicFile out(path);
  {
    File f(std::fopen(out.temp_path().c_str(), "wb"));
    if (!f) throw FileError(path, std::string("cannot write: ") + std::strerror(errno));
    // The header goes last, once the checksums are known; zeros hold its place and pad the sections.
    static const char zeros[kZsmHeaderBytes] = {};
    bool ok = std::fwrite(zeros, 1, kZsmHeaderBytes, f.get()) == kZsmHeaderBytes;
    uint64_t pos = kZsmHeaderBytes;
    for (int s = 0; ok && s < kNumSec; ++s) {
      const uint64_t pad = h.sec[s].offset - pos;
      ok = std::fwrite(zeros, 1, pad, f.get()) == pad;
      Checksum64 sum;
      for (uint64_t done = 0; ok && done < size[s];) {
        const size_t n = size_t(std::min<uint64_t>(size[s] - done, kBlock));
        sum.update(data[s] + done, n);
        ok = std::fwrite(data[s] + done, 1, n, f.get()) == n;
        done += n;
      }
      h.sec[s].sum = sum.digest();
      pos = h.sec[s].end();
    }
    unsigned char head[kZsmHeaderBytes];
    encode_header(head, h);
    ok = ok && std::fseek(f.get(), 0, SEEK_SET) == 0 && std::fwrite(head, 1, sizeof head, f.get()) == sizeof head;
    if (!ok || std::fflush(f.get()) != 0) throw FileError(path, std::string("cannot write: ") + std::strerror(errno));
    if (std::fclose(f.release()) != 0) throw FileError(path, std::string("cannot write: ") + std::strerror(errno));
  }
  out.commit();
}

}  // namespace zs
