#include "render/spheres/sphere_bins.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include "raster/sphere_span.h"
#include "render/spheres/sphere_visibility.h"

namespace zs {

namespace {

struct Box {
  uint32_t c0, c1, r0, r1;  // tile columns and rows; c0 > c1: no pixel centre of the image
};
struct Key {
  double z;     // nearest depth
  uint32_t id;  // sphere index: ties broken the same way whatever the culling
  uint32_t q;   // index into visible
  bool operator<(const Key& o) const { return z < o.z || (z == o.z && id < o.id); }
};

// Each visible sphere's nearest depth and tile box, in one parallel pass
// over the list (in the grid's memory order), then the keys sorted.
void boxes_and_order(const SphereGrid& g, const std::vector<uint32_t>& visible, const View& view,
                     const TileGrid& grid, int threads, std::vector<Box>& boxes, std::vector<Key>& key) {
  const CameraPlane cam = camera_plane(view);
  const Viewport image{0, 0, int(grid.width), int(grid.height)};
  const uint32_t size = grid.size;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, visible.size(), 4096), [&](const tbb::blocked_range<size_t>& br) {
      for (size_t q = br.begin(); q < br.end(); ++q) {
        const uint32_t e = visible[q];
        const glm::dvec3 c = to_camera(view, g.centre[e]);
        key[q] = {c.z - g.radius[e], g.ids[e], uint32_t(q)};
        const SphereSetup su = setup_sphere(cam, c.x, c.y, c.z, g.radius[e]);
        int i0, i1, j0, j1;
        if (!sphere_pixel_range(su, image, &i0, &i1, &j0, &j1)) {
          boxes[q] = {1, 0, 0, 0};
          continue;
        }
        boxes[q] = {uint32_t(i0) / size, uint32_t(i1) / size, uint32_t(j0) / size, uint32_t(j1) / size};
      }
    });
    // By nearest depth, then by sphere index: one order of the spheres
    // whatever the culling, grid or tiles. A tile's first spheres then
    // hide most of the rest, which its block test skips whole. The order
    // changes no pixel of the opaque and sorted modes (their depth tests
    // are order-independent), only the work; the weighted sum adds in it.
    tbb::parallel_sort(key.begin(), key.end());
  });
}

// Calls fn(tile) for each tile of the box.
template <class Fn>
void each_tile(const Box& b, uint32_t cols, Fn&& fn) {
  for (uint32_t r = b.r0; b.c0 <= b.c1 && r <= b.r1; ++r)
    for (uint32_t c = b.c0; c <= b.c1; ++c) fn(uint64_t(r) * cols + c);
}

}  // namespace

SphereBins bin_spheres(const SphereGrid& g, const std::vector<uint32_t>& visible, const View& view,
                       const TileGrid& grid, int threads, MemoryLedger& ledger) {
  std::vector<Box> boxes(visible.size());
  std::vector<Key> key(visible.size());
  ledger.add("the spheres' tile boxes and depth keys", boxes.size() * (sizeof(Box) + sizeof(key[0])));
  boxes_and_order(g, visible, view, grid, threads, boxes, key);
  // Counted (in any order), then filled in key order.
  const uint32_t cols = grid.cols();
  SphereBins bins;
  std::vector<uint64_t>& offset = bins.offset;
  offset.assign(uint64_t(grid.count()) + 1, 0);
  for (const Box& b : boxes) each_tile(b, cols, [&](uint64_t t) { ++offset[t + 1]; });
  for (uint64_t t = 0; t < grid.count(); ++t) offset[t + 1] += offset[t];
  ledger.add("the tile bins", offset.back() * 4 + offset.size() * 8);
  bins.ids.resize(offset.back());
  std::vector<uint64_t> next(offset.begin(), offset.end() - 1);
  for (const Key& k : key) {
    const uint32_t entry = visible[k.q];
    each_tile(boxes[k.q], cols, [&](uint64_t t) { bins.ids[next[t]++] = entry; });
  }
  return bins;
}

}  // namespace zs
