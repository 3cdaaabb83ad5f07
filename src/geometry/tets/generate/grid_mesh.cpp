// make_grid_mesh: every point and every tet is written in parallel (TBB) at
// an index computed from its node or cell, and jitter comes from a hash of
// the node rather than a sequence, so neither the thread count nor the
// schedule changes the mesh.
#include "geometry/tets/generate/grid_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "base/util/bytes_str.h"
#include "base/util/memory.h"
#include "geometry/tets/hex_split.h"

namespace zs {

namespace {

constexpr uint32_t kMaxCells = UINT32_MAX - 1;  // per axis, so that NX + 1 points fit
constexpr uint32_t kBrick = 8;                  // cells per brick side: 9³ points, 4.5k tets

// "'2x' is not a number" etc., the wording of app/option_checks.h.
uint32_t parse_count(const std::string& s) {
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || std::isnan(x)) throw std::invalid_argument("'" + s + "' is not a number");
  if (std::isfinite(x) && x != std::floor(x)) throw std::invalid_argument("'" + s + "' is not a whole number");
  if (!(x >= 1 && x <= kMaxCells))
    throw std::invalid_argument(s + " is out of range: must be in [1, " + std::to_string(kMaxCells) + "]");
  return uint32_t(x);
}

// A count in a message: whole below 10^15, else 3 digits.
std::string count_str(double n) {
  char b[64];
  std::snprintf(b, sizeof b, n < 1e15 ? "%.0f" : "%.3g", n);
  return b;
}

// Refuses options the mesh cannot be built from, before allocating anything.
void check(const GridMeshOptions& o) {
  if (o.split != 5 && o.split != 6) throw std::invalid_argument("split must be 5 or 6, not " + std::to_string(o.split));
  if (!(o.jitter >= 0 && o.jitter <= kMaxGridJitter)) {
    char b[128];
    std::snprintf(b, sizeof b, "jitter must be in [0, %g], not %g", kMaxGridJitter, o.jitter);
    throw std::invalid_argument(b);
  }
  for (uint32_t n : o.cells)
    if (n < 1 || n > kMaxCells) throw std::invalid_argument("cells must be in [1, " + std::to_string(kMaxCells) + "]");
  const auto [nx, ny, nz] = o.cells;
  const std::string name =
      "grid " + std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz) + " cells";
  // In doubles: the products of three 32-bit counts overflow 64 bits.
  const double points = (nx + 1.0) * (ny + 1.0) * (nz + 1.0);
  const double tets = double(o.split) * nx * ny * nz;
  // Ids are uint32_t, UINT32_MAX (kNoTet) kept free: at most UINT32_MAX of each.
  if (points > UINT32_MAX)
    throw std::invalid_argument(name + ": " + count_str(points) + " points, over the " + std::to_string(UINT32_MAX) +
                                " that 32-bit point ids allow; use fewer cells");
  if (tets > UINT32_MAX)
    throw std::invalid_argument(name + ": " + count_str(tets) + " tets, over the " + std::to_string(UINT32_MAX) +
                                " that 32-bit tet ids allow; use fewer cells");
  const uint64_t bytes = uint64_t(points) * (sizeof(glm::dvec3) + sizeof(double)) + uint64_t(tets) * sizeof(Tet);
  const uint64_t budget = o.memory_budget ? o.memory_budget : default_memory_budget();
  if (bytes > budget)
    throw std::invalid_argument(name + ": " + count_str(points) + " points and " + count_str(tets) + " tets take " +
                                bytes_str(bytes) + ", over the memory budget of " + bytes_str(budget) +
                                (o.memory_budget ? "" : " (half of physical memory)") + "; use fewer cells");
}

// One cell's tets on its local corners 0..7 (hex_split.h's order), each made
// positive on a right-handed cube: hex_split's odd 5-split has two negative
// tets, kept so there for the meshes already built from it.
struct CellSplit {
  std::array<Tet, 6> tets;
  int n = 0;
};

std::array<CellSplit, 2> cell_splits(int split) {  // [parity of i+j+k]
  TetMesh cube;
  for (uint32_t c = 0; c < 8; ++c)
    cube.points.push_back({double(c == 1 || c == 2 || c == 5 || c == 6), double(c == 2 || c == 3 || c == 6 || c == 7),
                           double(c >= 4)});
  const HexCorners local{0, 1, 2, 3, 4, 5, 6, 7};
  std::array<CellSplit, 2> out;
  for (int odd = 0; odd < 2; ++odd) {
    std::vector<Tet> v;
    if (split == 5) append_hex_5tets(local, odd != 0, v);
    else append_hex_6tets(local, v);
    out[odd].n = int(v.size());
    for (size_t q = 0; q < v.size(); ++q) {
      if (signed_volume6(cube, v[q]) < 0) std::swap(v[q][2], v[q][3]);
      out[odd].tets[q] = v[q];
    }
  }
  return out;
}

// SplitMix64's finaliser: a well-mixed 64-bit hash.
uint64_t mix64(uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Uniform in [-1, 1) from (node, axis, seed).
double jitter_unit(uint64_t node, int axis, uint64_t seed_hash) {
  const uint64_t h = mix64(seed_hash ^ (3 * node + uint64_t(axis) + 0x9e3779b97f4a7c15ULL));
  return double(h >> 11) * 0x1p-52 - 1.0;
}

// Node coordinates along one axis of n cells: (2i - n) / nmax, so the
// longest axis's ends are exactly -1 and 1 and every axis is centred on 0.
std::vector<double> axis_coords(uint32_t n, uint32_t nmax) {
  std::vector<double> c(size_t(n) + 1);
  for (uint32_t i = 0; i <= n; ++i) c[i] = double(2 * int64_t(i) - int64_t(n)) / double(nmax);
  return c;
}

void fill_points(const GridMeshOptions& o, std::vector<glm::dvec3>& points) {
  const auto [nx, ny, nz] = o.cells;
  const uint32_t nmax = std::max({nx, ny, nz});
  const std::vector<double> xs = axis_coords(nx, nmax), ys = axis_coords(ny, nmax), zs = axis_coords(nz, nmax);
  const double amp = o.jitter * 2.0 / nmax;  // jitter × cell size
  const uint64_t seed_hash = mix64(o.seed);
  const uint64_t rows = uint64_t(ny + 1) * (nz + 1);
  tbb::parallel_for(tbb::blocked_range<uint64_t>(0, rows), [&](const tbb::blocked_range<uint64_t>& r) {
    for (uint64_t row = r.begin(); row < r.end(); ++row) {
      const uint32_t j = uint32_t(row % (ny + 1)), k = uint32_t(row / (ny + 1));
      const bool inner_row = j > 0 && j < ny && k > 0 && k < nz;
      const uint64_t first = row * (nx + 1);
      for (uint32_t i = 0; i <= nx; ++i) {
        glm::dvec3 p{xs[i], ys[j], zs[k]};
        if (amp > 0 && inner_row && i > 0 && i < nx)
          for (int a = 0; a < 3; ++a) p[a] += amp * jitter_unit(first + i, a, seed_hash);
        points[first + i] = p;
      }
    }
  });
}

// Cells in bricks of kBrick³, bricks in i-fastest order and cells i-fastest
// inside each; the cells before a brick are counted in closed form (the
// bricks on the last row, column and layer may be smaller), so each brick
// writes its own slice.
void fill_tets(const GridMeshOptions& o, std::vector<Tet>& tets) {
  const auto [nx, ny, nz] = o.cells;
  const std::array<CellSplit, 2> splits = cell_splits(o.split);
  const uint64_t per_cell = uint64_t(o.split);
  const uint64_t bx = (nx + kBrick - 1) / kBrick, by = (ny + kBrick - 1) / kBrick, bz = (nz + kBrick - 1) / kBrick;
  tbb::parallel_for(tbb::blocked_range<uint64_t>(0, bx * by * bz), [&](const tbb::blocked_range<uint64_t>& r) {
    for (uint64_t b = r.begin(); b < r.end(); ++b) {
      const uint32_t i0 = uint32_t(b % bx) * kBrick, j0 = uint32_t(b / bx % by) * kBrick,
                     k0 = uint32_t(b / (bx * by)) * kBrick;
      const uint32_t ti = std::min(kBrick, nx - i0), tj = std::min(kBrick, ny - j0), tk = std::min(kBrick, nz - k0);
      uint64_t cell = uint64_t(nx) * ny * k0 + uint64_t(nx) * j0 * tk + uint64_t(i0) * tj * tk;
      for (uint32_t k = k0; k < k0 + tk; ++k)
        for (uint32_t j = j0; j < j0 + tj; ++j)
          for (uint32_t i = i0; i < i0 + ti; ++i, ++cell) {
            const HexCorners c = grid_hex(i, j, k, nx + 1, ny + 1);
            const CellSplit& s = splits[(i + j + k) & 1];
            Tet* out = tets.data() + cell * per_cell;
            for (int q = 0; q < s.n; ++q)
              out[q] = {c[s.tets[q][0]], c[s.tets[q][1]], c[s.tets[q][2]], c[s.tets[q][3]]};
          }
    }
  });
}

}  // namespace

std::array<uint32_t, 3> parse_grid_cells(const std::string& text) {
  std::vector<std::string> parts(1);
  for (char ch : text) {
    if (ch == ',') parts.emplace_back();
    else parts.back() += ch;
  }
  if (parts.size() != 1 && parts.size() != 3)
    throw std::invalid_argument("'" + text + "' has " + std::to_string(parts.size()) +
                                " numbers: expected N or NX,NY,NZ");
  if (parts.size() == 1) {
    const uint32_t n = parse_count(parts[0]);
    return {n, n, n};
  }
  return {parse_count(parts[0]), parse_count(parts[1]), parse_count(parts[2])};
}

TetMesh make_grid_mesh(const GridMeshOptions& o) {
  check(o);
  const auto [nx, ny, nz] = o.cells;
  TetMesh m;
  m.points.resize(size_t(nx + 1) * (ny + 1) * (nz + 1));
  m.tets.resize(size_t(o.split) * nx * ny * nz);
  fill_points(o, m.points);
  fill_tets(o, m.tets);
  return m;
}

}  // namespace zs
