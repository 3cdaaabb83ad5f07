#include "output/tile_writer.h"

#include "output/image_io.h"
#include "output/pixel_quantize.h"

#include <OpenImageIO/imageio.h>

#include <OpenImageIO/filesystem.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <vector>

#include "base/util/atomic_file.h"

namespace zs {

namespace {

// OIIO may queue several messages; the CLI prints one line.
std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s.empty() ? std::string("unknown error") : s;
}

// Above this a classic TIFF's 32-bit offsets may overflow (compression
// cannot be counted on), so the file is written as BigTIFF.
constexpr uint64_t kBigTiffBytes = uint64_t(2) << 30;

// libpng refuses images wider or taller than this (its default user limit).
constexpr uint32_t kPngMaxSide = 1000000;

// How an output format takes the engine's tiles, decided before anything is
// opened, so the memory budget can be checked first.
struct Layout {
  std::string fmt;
  bool is_float = false;
  bool tiled = false;         // the file is tiled (tiles or whole bands of tiles go in)
  bool random_order = false;  // tiles go to disk as they arrive
  uint32_t channels = 4;      // in the file: the grid's for float formats (Z too), RGBA for 8-bit
  uint64_t pixel_bytes() const { return is_float ? 4 * channels : 4; }
};

Layout layout_for(OIIO::ImageOutput& file, const std::string& path, const TileGrid& grid) {
  if (grid.width == 0 || grid.height == 0 || grid.size == 0) throw std::runtime_error(path + ": cannot write an empty image");
  Layout L;
  L.fmt = file.format_name();
  // The formats and attributes write_image() uses, so both store the same values.
  L.is_float = L.fmt == "openexr" || L.fmt == "tiff";
  L.channels = L.is_float ? grid.channels : 4;
  if (L.fmt == "png" && (grid.width > kPngMaxSide || grid.height > kPngMaxSide))
    throw std::runtime_error(path + ": PNG is limited to " + std::to_string(kPngMaxSide) +
                             " pixels per side (libpng); write .exr or .tif");
  // libtiff refuses tile sizes that are not multiples of 16; such renders
  // go to a striped TIFF through the band path instead.
  L.tiled = L.is_float && file.supports("tiles") && (L.fmt != "tiff" || grid.size % 16 == 0);
  // OpenEXR says so only once open with line order randomY, which the
  // writer always sets; the writer asks the opened file again.
  L.random_order = L.tiled && (L.fmt == "openexr" || file.supports("random_access"));
  return L;
}

uint64_t estimate_bytes(const Layout& L, const TileGrid& grid) {
  const uint64_t n = grid.count();
  // The arrival bitmap, and the per-tile offset and size tables the file
  // library keeps until close.
  uint64_t bytes = n / 8 + 1 + n * 16;
  if (L.random_order) {
    // The library's padded copy of a tile and its compression scratch.
    bytes += 4 * uint64_t(grid.size) * grid.size * L.pixel_bytes();
  } else {
    // Tiles arrive roughly row-major from a few threads: the band being
    // filled, the next one, and one of slack for a slow tile.
    bytes += 3 * uint64_t(grid.width) * std::min(grid.size, grid.height) * L.pixel_bytes();
  }
  return bytes;
}

std::unique_ptr<OIIO::ImageOutput> create_output(const std::string& path) {
  auto file = OIIO::ImageOutput::create(path);
  if (!file) throw std::runtime_error(path + ": unsupported image format: " + one_line(OIIO::geterror()));
  return file;
}

// The file under a sequential (PNG) writer. OIIO's PNG writer ignores
// failed writes, so this remembers them; and an abandoned image is finished
// into the void (discard) so that nothing but the temporary is lost.
class CheckedFile : public OIIO::Filesystem::IOProxy {
 public:
  explicit CheckedFile(const std::string& path) : IOProxy(path, Write), f_(std::fopen(path.c_str(), "wb")) {
    if (!f_) {
      m_mode = Closed;
      errno_ = errno;
    }
  }
  ~CheckedFile() override {
    if (f_) std::fclose(f_);
  }
  const char* proxytype() const override { return "zsweep-checked-file"; }
  size_t write(const void* buf, size_t n) override {
    ++writes_;
    if (discard_) return n;
    const size_t w = f_ ? std::fwrite(buf, 1, n, f_) : 0;
    if (w != n) note_error();
    m_pos += int64_t(w);
    size_ = std::max(size_, uint64_t(m_pos));
    return w;
  }
  size_t pwrite(const void* buf, size_t n, int64_t offset) override {
    const int64_t at = m_pos;
    if (!seek(offset)) return 0;
    const size_t w = write(buf, n);
    seek(at);
    return w;
  }
  bool seek(int64_t offset) override {
    if (!discard_ && (!f_ || fseeko(f_, offset, SEEK_SET) != 0)) {
      note_error();
      return false;
    }
    m_pos = offset;
    return true;
  }
  size_t size() const override { return size_; }
  void flush() const override {
    if (f_ && !discard_) std::fflush(f_);
  }
  void discard() { discard_ = true; }
  uint64_t writes() const { return writes_; }
  bool failed() const { return errno_ != 0; }
  // Flushes and closes; the first error as text, empty when all went well.
  std::string finish() {
    if (f_ && !discard_ && (std::fflush(f_) != 0 || std::ferror(f_))) note_error();
    if (f_ && std::fclose(f_) != 0) note_error();
    f_ = nullptr;
    m_mode = Closed;
    return errno_ ? std::string(std::strerror(errno_)) : std::string();
  }
  int open_error() const { return f_ ? 0 : errno_; }

 private:
  void note_error() {
    if (!errno_) errno_ = errno ? errno : EIO;
  }
  FILE* f_;
  int errno_ = 0;
  uint64_t writes_ = 0, size_ = 0;
  bool discard_ = false;
};

}  // namespace

struct ImageTileWriter::Impl {
  // A row of tiles being assembled for an in-order format.
  struct Band {
    std::vector<uint8_t> data;  // width·rows pixels of layout.channels, row-major
    uint32_t tiles_left = 0;
  };

  std::string path;
  TileGrid grid;
  // Declared in this order so the image is closed, then its file, then the
  // temporary removed.
  AtomicFile out;
  std::unique_ptr<CheckedFile> proxy;  // sequential 8-bit formats only
  std::unique_ptr<OIIO::ImageOutput> file;
  uint64_t header_writes = 0;  // proxy writes before the first row
  Layout layout;
  std::vector<bool> received;
  uint32_t received_count = 0;
  std::map<uint32_t, Band> bands;  // by tile row, only for !layout.random_order
  uint32_t next_row = 0;           // first tile row not yet written
  uint64_t held = 0, peak = 0;
  bool committed = false;
  // A write failed: the file library may be left mid-call (OpenEXR keeps a
  // tile buffer's semaphore taken, and the next write_tiles waits on it
  // forever), so no further tile goes to it; later tiles get the first
  // error again (whichever thread's error the render reports, it is this).
  std::string failure;

  Impl(const std::string& p, const TileGrid& g, const std::string& compression, const std::vector<std::string>& names)
      : path(p), grid(g), out(p) {
    // OpenEXR compresses on a pool of one thread per core by default, next to
    // the render's own threads: with --threads 1 the file would quietly use
    // every core. Compress in the writing thread instead (the sink relay
    // lets the other render threads go on meanwhile), so --threads N means
    // N cores.
    OIIO::attribute("exr_threads", -1);
    file = create_output(path);
    layout = layout_for(*file, path, grid);
    const std::string& fmt = layout.fmt;
    const bool is_float = layout.is_float, tiled = layout.tiled;
    OIIO::ImageSpec spec(int(grid.width), int(grid.height), int(layout.channels),
                         is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    if (layout.channels >= 5) {
      // The view depth of the nearest surface, as EXR's depth channel, then
      // the renderer's own channels (surfaces: lit0, lit1, ...).
      spec.channelnames = {"R", "G", "B", "A", "Z"};
      for (uint32_t c = 5; c < layout.channels; ++c)
        spec.channelnames.push_back(c < names.size() ? names[c] : "C" + std::to_string(c));
      spec.z_channel = 4;
    }
    spec.attribute("oiio:ColorSpace", "Linear");
    spec.attribute("oiio:UnassociatedAlpha", 1);
    const std::string comp = output_compression(fmt, compression, path);
    if (!comp.empty()) spec.attribute("compression", comp);
    if (tiled) {
      spec.tile_width = spec.tile_height = int(grid.size);
      spec.tile_depth = 1;
      // Without randomY OpenEXR keeps every out-of-order tile in memory
      // until the ones before it arrive.
      if (fmt == "openexr") spec.attribute("openexr:lineOrder", "randomY");
    }
    if (fmt == "tiff" && uint64_t(grid.width) * grid.height * layout.pixel_bytes() >= kBigTiffBytes) spec.attribute("tiff:bigtiff", 1);
    if (!is_float && file->supports("ioproxy")) {
      proxy = std::make_unique<CheckedFile>(out.temp_path());
      if (proxy->open_error()) throw std::runtime_error(path + ": cannot write: " + std::strerror(proxy->open_error()));
      file->set_ioproxy(proxy.get());
    }
    errno = 0;
    if (!file->open(out.temp_path(), spec)) fail("cannot write");
    if (proxy) header_writes = proxy->writes();
    layout.random_order = tiled && file->supports("random_access");
    received.assign(grid.count(), false);
  }

  ~Impl() {
    if (!committed && file && proxy) abandon_quietly();
  }

  // Closing a PNG whose rows are missing makes libpng print "No IDATs
  // written into file" on stderr unless compressed data has gone out
  // already. Incompressible rows, discarded, get some out in a few rows.
  void abandon_quietly() {
    proxy->discard();
    std::vector<uint8_t> noise(size_t(grid.width) * 4);
    uint32_t x = 2463534242u;
    for (uint8_t& b : noise) {
      x ^= x << 13, x ^= x >> 17, x ^= x << 5;
      b = uint8_t(x);
    }
    for (uint32_t y = std::min(next_row * grid.size, grid.height); y < grid.height && proxy->writes() == header_writes;
         ++y)
      if (!file->write_scanline(int(y), 0, OIIO::TypeDesc::UINT8, noise.data())) break;
    file->close();
    file->geterror();  // nobody is listening
  }

  uint64_t pixel_bytes() const { return layout.pixel_bytes(); }

  // The library's message, naming the output rather than its temporary,
  // and the system's reason when the library gave none (libtiff says only
  // "Write error at scanline N"); callers clear errno before the call.
  [[noreturn]] void fail(const std::string& what) {
    const int err = errno;
    std::string e = file ? file->geterror() : std::string();
    e = e.empty() ? std::string() : out.name_final(one_line(e));
    if (err != 0 && e.find(std::strerror(err)) == std::string::npos)
      e += (e.empty() ? "" : ": ") + std::string(std::strerror(err));
    failure = path + ": " + what + (e.empty() ? "" : ": " + e);
    throw std::runtime_error(failure);
  }

  void check_rect(const TileRect& r) const {
    const uint32_t s = grid.size;
    const bool ok = r.x0 < grid.width && r.y0 < grid.height && r.x0 % s == 0 && r.y0 % s == 0 &&
                    r.x1 == std::min(r.x0 + s, grid.width) && r.y1 == std::min(r.y0 + s, grid.height);
    if (!ok)
      throw std::runtime_error(path + ": [" + std::to_string(r.x0) + "," + std::to_string(r.x1) + ")x[" +
                               std::to_string(r.y0) + "," + std::to_string(r.y1) + ") is not a tile of the " +
                               std::to_string(grid.width) + "x" + std::to_string(grid.height) + " image in tiles of " +
                               std::to_string(s));
  }

  void add_to_band(const TileRect& r, const float* rgba) {
    const uint32_t row = r.y0 / grid.size;
    auto it = bands.find(row);
    if (it == bands.end()) {
      Band b;
      b.data.resize(size_t(grid.width) * r.height() * pixel_bytes());
      b.tiles_left = grid.cols();
      held += b.data.size();
      peak = std::max(peak, held);
      it = bands.emplace(row, std::move(b)).first;
    }
    Band& b = it->second;
    const size_t w = r.width(), gc = grid.channels;
    for (uint32_t y = 0; y < r.height(); ++y) {
      const float* src = rgba + size_t(y) * w * gc;
      const size_t dst = size_t(y) * grid.width + r.x0;  // in pixels
      if (layout.is_float) {
        std::memcpy(b.data.data() + dst * pixel_bytes(), src, w * pixel_bytes());
      } else {
        uint8_t* d = b.data.data() + dst * 4;
        // Exactly write_image()'s pixels: straight alpha (pixel_quantize.h).
        for (size_t i = 0; i < w; ++i) quantize_straight(src + i * gc, d + i * 4);
      }
    }
    --b.tiles_left;
  }

  // Writes every complete band at the top, in order.
  void flush_bands() {
    const OIIO::TypeDesc type = layout.is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
    for (auto it = bands.find(next_row); it != bands.end() && it->second.tiles_left == 0;
         it = bands.find(next_row)) {
      const int y0 = int(next_row * grid.size), y1 = int(std::min(y0 + grid.size, grid.height));
      const void* data = it->second.data.data();
      errno = 0;
      const bool ok = layout.tiled ? file->write_tiles(0, int(grid.width), y0, y1, 0, 1, type, data)
                            : file->write_scanlines(y0, y1, 0, type, data);
      if (!ok) fail("cannot write");
      // Stop a long render at the first failed write (a full disk), not at commit.
      if (proxy && proxy->failed()) {
        failure = path + ": cannot write: " + proxy->finish();
        throw std::runtime_error(failure);
      }
      held -= it->second.data.size();
      bands.erase(it);
      ++next_row;
    }
  }

  void tile(const TileRect& r, const float* rgba) {
    if (committed) throw std::runtime_error(path + ": tile after commit");
    if (!failure.empty()) throw std::runtime_error(failure);
    check_rect(r);
    const uint32_t id = (r.y0 / grid.size) * grid.cols() + r.x0 / grid.size;
    if (received[id])
      throw std::runtime_error(path + ": tile at (" + std::to_string(r.x0) + ", " + std::to_string(r.y0) +
                               ") delivered twice");
    if (layout.random_order) {
      // write_tiles, unlike write_tile, takes an edge tile at its real size.
      errno = 0;
      if (!file->write_tiles(int(r.x0), int(r.x1), int(r.y0), int(r.y1), 0, 1, OIIO::TypeDesc::FLOAT, rgba))
        fail("cannot write");
    } else {
      add_to_band(r, rgba);
      flush_bands();
    }
    received[id] = true;
    ++received_count;
  }

  void commit() {
    if (committed) return;
    if (received_count != grid.count())
      throw std::runtime_error(path + ": " + std::to_string(grid.count() - received_count) + " of " +
                               std::to_string(grid.count()) + " tiles were never rendered; nothing written");
    errno = 0;
    if (!file->close()) fail("cannot write");
    file.reset();
    if (proxy) {
      const std::string e = proxy->finish();
      if (!e.empty()) throw std::runtime_error(path + ": cannot write: " + e);
    }
    out.commit();
    committed = true;
  }
};

ImageTileWriter::ImageTileWriter(const std::string& path, const TileGrid& grid, const std::string& compression,
                                 const std::vector<std::string>& channel_names)
    : impl_(std::make_unique<Impl>(path, grid, compression, channel_names)) {}

ImageTileWriter::~ImageTileWriter() = default;

void ImageTileWriter::tile(const TileRect& r, const float* rgba) { impl_->tile(r, rgba); }

uint64_t ImageTileWriter::buffer_bytes_estimate() const { return estimate_bytes(impl_->layout, impl_->grid); }

uint64_t ImageTileWriter::buffer_bytes_estimate(const std::string& path, const TileGrid& grid) {
  auto file = create_output(path);
  return estimate_bytes(layout_for(*file, path, grid), grid);
}

bool ImageTileWriter::keeps_extra_channels(const std::string& path) {
  auto file = create_output(path);
  const std::string fmt = file->format_name();
  return fmt == "openexr" || fmt == "tiff";  // layout_for's float formats
}

uint64_t ImageTileWriter::peak_buffer_bytes() const { return impl_->peak; }
bool ImageTileWriter::tiled() const { return impl_->layout.tiled; }
void ImageTileWriter::commit() { impl_->commit(); }

}  // namespace zs
