// read_plot3d: PLOT3D grid + solution -> tets.
//
// VTK reads the blocks and computes the requested function; the hex -> tet
// split and the duplicate-point merge are ours so both are predictable: each
// hex becomes 5 tets with the diagonal pattern alternating on (i+j+k) parity,
// which makes the face diagonals of neighbouring hexes agree.
#include <vtkDataArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkMultiBlockPLOT3DReader.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkStructuredGrid.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <string>
#include <vector>

#include "geometry/tets/io/vtk_capture.h"
#include "geometry/tets/io/vtk_io.h"
#include "geometry/tets/hex_split.h"
#include "base/util/file_error.h"

namespace zs {

namespace {

namespace fs = std::filesystem;

struct Function {
  const char* name;   // what users type (opt.scalar)
  int number;         // PLOT3D function number
  const char* array;  // array name vtkMultiBlockPLOT3DReader produces
};

// Numbers and array names as in vtkMultiBlockPLOT3DReader (VTK 9.1). VTK does
// not implement 140, so internal energy is computed here from the Q variables.
constexpr Function kFunctions[] = {
    {"density", 100, "Density"},
    {"pressure", 110, "Pressure"},
    {"pressure-coefficient", 111, "PressureCoefficient"},
    {"mach", 112, "MachNumber"},
    {"sound-speed", 113, "SoundSpeed"},
    {"temperature", 120, "Temperature"},
    {"enthalpy", 130, "Enthalpy"},
    {"internal-energy", 140, "InternalEnergy"},
    {"kinetic-energy", 144, "KineticEnergy"},
    {"velocity-magnitude", 153, "VelocityMagnitude"},
    {"stagnation-energy", 163, "StagnationEnergy"},
    {"entropy", 170, "Entropy"},
    {"swirl", 184, "Swirl"},
    {"vorticity-magnitude", 211, "VorticityMagnitude"},
};

const Function& find_function(const std::string& path, const std::string& want) {
  const std::string key = want.empty() ? "density" : want;
  for (const Function& f : kFunctions)
    if (key == f.name || key == f.array || key == std::to_string(f.number)) return f;
  std::string names;
  for (const Function& f : kFunctions) names += (names.empty() ? "" : ", ") + std::string(f.name);
  throw FileError(path, "unknown PLOT3D function '" + want + "'; valid: " + names);
}

void require_file(const std::string& path, const char* role) {
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw FileError(path, std::string("no such file (PLOT3D ") + role + ")");
  if (fs::is_directory(path, ec)) throw FileError(path, "is a directory, not a PLOT3D file");
  if (!std::ifstream(path, std::ios::binary)) throw FileError(path, "cannot open file");
  if (fs::file_size(path, ec) == 0)
    throw FileError(path, std::string("empty PLOT3D ") + role + " file");
}

// True if the grid file's size matches its header under some binary PLOT3D
// layout (either byte order, with/without Fortran byte counts, single or
// multi-grid, float or double, with/without IBLANK). VTK's own auto-detection
// lets some garbage through and then crashes reading it, so this gate runs
// first.
bool plausible_xyz(const std::string& path) {
  std::error_code ec;
  const uint64_t size = fs::file_size(path, ec);
  if (ec) return false;
  std::ifstream f(path, std::ios::binary);
  std::string head(static_cast<size_t>(std::min<uint64_t>(size, 1 << 20)), '\0');
  f.read(head.data(), static_cast<std::streamsize>(head.size()));
  for (int be = 0; be < 2; ++be)
    for (int counts = 0; counts < 2; ++counts)
      for (int multi = 0; multi < 2; ++multi) {
        size_t pos = 0;
        bool ok = true;
        auto next = [&]() -> int64_t {  // one 32-bit int, or -1 past the buffer
          if (pos + 4 > head.size()) {
            ok = false;
            return -1;
          }
          const auto* b = reinterpret_cast<const unsigned char*>(head.data() + pos);
          pos += 4;
          const uint32_t v =
              be ? (uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | b[3])
                 : (uint32_t(b[3]) << 24 | uint32_t(b[2]) << 16 | uint32_t(b[1]) << 8 | b[0]);
          return static_cast<int32_t>(v);
        };
        int64_t blocks = 1;
        if (multi) {
          if (counts && next() != 4) continue;
          blocks = next();
          if (counts && next() != 4) continue;
          if (!ok || blocks < 1 || blocks > 100000) continue;
        }
        if (counts && next() != 12 * blocks) continue;
        std::vector<uint64_t> points;
        for (int64_t b = 0; b < blocks && ok; ++b) {
          uint64_t n = 1;
          for (int d = 0; d < 3; ++d) {
            const int64_t v = next();
            if (v < 1 || v > (1 << 20)) ok = false;
            n *= static_cast<uint64_t>(std::max<int64_t>(v, 1));
          }
          if (n > (uint64_t(1) << 36)) ok = false;
          points.push_back(n);
        }
        if (counts && next() != 12 * blocks) continue;
        if (!ok) continue;
        for (uint64_t prec : {4, 8})
          for (uint64_t iblank : {0, 4}) {
            uint64_t total = pos;
            for (uint64_t n : points) total += n * (3 * prec + iblank) + (counts ? 8 : 0);
            if (total == size) return true;
          }
      }
  return false;
}

// Runs the VTK reader; returns the output or nullptr (errors captured).
vtkSmartPointer<vtkMultiBlockDataSet> run_reader(const std::string& xyz, const std::string& q,
                                                 const std::vector<const Function*>& fns,
                                                 detail::VtkMessageCapture& capture) {
  auto r = vtkSmartPointer<vtkMultiBlockPLOT3DReader>::New();
  capture.watch(r);
  r->SetXYZFileName(xyz.c_str());
  r->SetQFileName(q.c_str());
  // Detects byte order, precision, byte counts, multi-grid, IBLANK and 2-D by
  // matching the file size against the header. Always on: with fixed settings
  // VTK trusts the header's dimensions and crashes on garbage input.
  r->AutoDetectFormatOn();
  // Density and stagnation energy are read as they are; internal energy is ours.
  for (const Function* fn : fns)
    if (fn->number != 100 && fn->number != 163 && fn->number != 140) r->AddFunction(fn->number);
  r->Update();
  if (capture.has_error()) return nullptr;
  return r->GetOutput();
}

// A function's values in one block: its array, or (140) the Q variables it is
// computed from; null arrays when the reader did not produce them.
struct FunctionArrays {
  const Function* fn = nullptr;
  vtkDataArray *f = nullptr, *rho = nullptr, *mom = nullptr, *energy = nullptr;
  bool ok() const { return fn->number == 140 ? rho && mom && energy : f != nullptr; }
  double at(vtkIdType i) const {
    if (fn->number != 140) return f->GetComponent(i, 0);
    // Specific internal energy e = E/rho - |m|^2 / (2 rho^2).
    const double r = rho->GetComponent(i, 0);
    double mm = 0;
    for (int c = 0; c < 3; ++c) mm += mom->GetComponent(i, c) * mom->GetComponent(i, c);
    return energy->GetComponent(i, 0) / r - 0.5 * mm / (r * r);
  }
};

FunctionArrays arrays_of(vtkPointData* pd, const Function& fn) {
  return {&fn, fn.number == 140 ? nullptr : pd->GetArray(fn.array), pd->GetArray("Density"), pd->GetArray("Momentum"),
          pd->GetArray("StagnationEnergy")};
}

// The finite range of `fn` over every block; lo > hi when it has no finite value.
void function_range(vtkMultiBlockDataSet* mb, const Function& fn, bool* produced, double* lo, double* hi) {
  *lo = INFINITY, *hi = -INFINITY, *produced = true;
  for (unsigned b = 0; b < mb->GetNumberOfBlocks(); ++b) {
    auto* sg = vtkStructuredGrid::SafeDownCast(mb->GetBlock(b));
    if (!sg || sg->GetNumberOfPoints() == 0) continue;
    const FunctionArrays a = arrays_of(sg->GetPointData(), fn);
    if (!a.ok()) {
      *produced = false;
      return;
    }
    for (vtkIdType i = 0; i < sg->GetNumberOfPoints(); ++i) {
      const double v = a.at(i);
      if (std::isfinite(v)) *lo = std::min(*lo, v), *hi = std::max(*hi, v);
    }
  }
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// Key for exact coordinate equality: bit patterns (a total order, safe with
// NaN), with -0.0 folded onto +0.0 since they are the same position.
std::array<uint64_t, 3> coord_key(const glm::dvec3& p) {
  auto bits = [](double v) { return std::bit_cast<uint64_t>(v == 0.0 ? 0.0 : v); };
  return {bits(p.x), bits(p.y), bits(p.z)};
}

// Merges points with identical coordinates; the first occurrence keeps its
// scalar. Returns how many points were removed.
size_t merge_duplicates(TetMesh& m) {
  const size_t n = m.points.size();
  std::vector<std::array<uint64_t, 3>> keys(n);
  for (size_t i = 0; i < n; ++i) keys[i] = coord_key(m.points[i]);
  std::vector<uint32_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = static_cast<uint32_t>(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  std::vector<uint32_t> rep(n);  // representative (first occurrence) of each point
  for (size_t s = 0; s < n;) {
    size_t e = s + 1;
    while (e < n && keys[order[e]] == keys[order[s]]) ++e;
    for (size_t k = s; k < e; ++k) rep[order[k]] = order[s];
    s = e;
  }
  std::vector<uint32_t> newid(n, UINT32_MAX);
  uint32_t next = 0;
  for (size_t i = 0; i < n; ++i)
    if (rep[i] == i) {
      newid[i] = next;
      m.points[next] = m.points[i];
      if (!m.scalars.empty()) m.scalars[next] = m.scalars[i];
      ++next;
    }
  for (size_t i = 0; i < n; ++i) newid[i] = newid[rep[i]];
  m.points.resize(next);
  if (!m.scalars.empty()) m.scalars.resize(next);
  for (Tet& t : m.tets)
    for (uint32_t& v : t) v = newid[v];
  return n - next;
}

std::string count(size_t n) {
  // 187395 -> "187,395": notes are read by people.
  const std::string digits = std::to_string(n);
  std::string s;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) s.push_back(',');
    s.push_back(digits[i]);
  }
  return s;
}

}  // namespace

TetMesh read_plot3d(const std::string& xyz_path, const ReadOptions& opt) {
  require_file(xyz_path, "grid");
  if (opt.q_path.empty())
    throw FileError(xyz_path, "PLOT3D grid needs its solution file (--q FILE)");
  require_file(opt.q_path, "solution");
  if (opt.association == ScalarAssociation::Cell)
    throw FileError(opt.q_path, "PLOT3D functions are point data, and association is 'cell'");
  const Function& fn0 = find_function(xyz_path, opt.scalar);

  if (!plausible_xyz(xyz_path))
    throw FileError(xyz_path, "not a binary 3-D PLOT3D grid (file size does not match its header)");

  detail::VtkMessageCapture capture;
  vtkSmartPointer<vtkMultiBlockDataSet> mb;
  auto read = [&](const std::vector<const Function*>& fns) {
    try {
      mb = run_reader(xyz_path, opt.q_path, fns, capture);
    } catch (const std::bad_alloc&) {
      throw FileError(xyz_path, "PLOT3D reader ran out of memory (corrupt header?)");
    }
    if (!mb)
      throw FileError(xyz_path,
                      "PLOT3D reader: " + capture.first_error() + " (q file " + opt.q_path + ")");
  };
  read({&fn0});

  TetMesh m;
  // No function named and density constant (a uniform free stream, as in
  // the oxygen post): the first function that varies, so the default
  // render shows the flow rather than a flat disc.
  const Function* chosen = &fn0;
  bool produced = true;
  double lo = 0, hi = 0;
  if (opt.scalar.empty()) function_range(mb, fn0, &produced, &lo, &hi);
  if (opt.scalar.empty() && produced && !(lo < hi)) {
    std::vector<const Function*> all;
    for (const Function& f : kFunctions) all.push_back(&f);
    const vtkSmartPointer<vtkMultiBlockDataSet> first = mb;
    bool read_all = true;
    try {
      read(all);
    } catch (const FileError&) {
      read_all = false;  // a function VTK cannot compute here: keep density
    }
    for (const Function& f : kFunctions) {
      double flo, fhi;
      bool fp;
      if (!read_all) break;
      function_range(mb, f, &fp, &flo, &fhi);
      if (fp && flo < fhi) {
        chosen = &f;
        m.scalar_choice = std::string("'") + fn0.array + "' is constant (" + num(lo) + ")";
        break;
      }
    }
    if (chosen == &fn0) mb = first;
  }
  const Function& fn = *chosen;
  m.scalar_name = fn.array;
  size_t hexes = 0, blanked = 0, fringe = 0, blocks = 0;
  bool has_iblank = false;
  for (unsigned b = 0; b < mb->GetNumberOfBlocks(); ++b) {
    auto* sg = vtkStructuredGrid::SafeDownCast(mb->GetBlock(b));
    if (!sg || sg->GetNumberOfPoints() == 0) continue;
    int d[3];
    sg->GetDimensions(d);
    if (d[0] < 2 || d[1] < 2 || d[2] < 2)
      throw FileError(xyz_path, "block " + std::to_string(b) + " is not a 3-D grid (" +
                                    std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
                                    std::to_string(d[2]) + ")");
    vtkPointData* pd = sg->GetPointData();
    const FunctionArrays values = arrays_of(pd, fn);
    if (!values.ok())
      throw FileError(xyz_path, std::string("PLOT3D reader produced no '") + fn.array +
                                    "' array (does the q file match the grid?)");
    vtkDataArray* iblank = pd->GetArray("IBlank");
    has_iblank = has_iblank || iblank;

    const size_t base = m.points.size();
    const vtkIdType np = sg->GetNumberOfPoints();
    double p[3];
    for (vtkIdType i = 0; i < np; ++i) {
      sg->GetPoint(i, p);
      m.points.emplace_back(p[0], p[1], p[2]);
      m.scalars.push_back(values.at(i));
      if (iblank && iblank->GetComponent(i, 0) < 0) ++fringe;
    }

    // IBLANK 0 = hole point; hexes touching one are not part of the flow.
    auto id = [&](int i, int j, int k) {
      return static_cast<vtkIdType>(i + d[0] * (j + d[1] * k));
    };
    for (int k = 0; k + 1 < d[2]; ++k)
      for (int j = 0; j + 1 < d[1]; ++j)
        for (int i = 0; i + 1 < d[0]; ++i) {
          const vtkIdType c[8] = {
              id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
              id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
          ++hexes;
          if (iblank) {
            bool hole = false;
            for (vtkIdType v : c) hole = hole || iblank->GetComponent(v, 0) == 0;
            if (hole) {
              ++blanked;
              continue;
            }
          }
          HexCorners hc;
          for (int q = 0; q < 8; ++q) hc[q] = static_cast<uint32_t>(base + c[q]);
          const size_t first = m.tets.size();
          append_hex_5tets(hc, ((i + j + k) & 1) != 0, m.tets);
          // Left-handed grids would give negative tets: orient each one.
          for (size_t q = first; q < m.tets.size(); ++q)
            if (signed_volume6(m, m.tets[q]) < 0) std::swap(m.tets[q][2], m.tets[q][3]);
        }
    ++blocks;
  }
  if (m.tets.empty()) throw FileError(xyz_path, "PLOT3D grid has no (unblanked) cells");

  const size_t before = m.points.size();
  const size_t merged = merge_duplicates(m);
  size_t degenerate = 0, nonfinite = 0;
  for (const Tet& t : m.tets)
    if (t[0] == t[1] || t[0] == t[2] || t[0] == t[3] || t[1] == t[2] || t[1] == t[3] ||
        t[2] == t[3] || signed_volume6(m, t) == 0.0)
      ++degenerate;
  for (double s : m.scalars) nonfinite += !std::isfinite(s);

  if (blocks > 1) m.notes.push_back("PLOT3D: " + std::to_string(blocks) + " blocks concatenated");
  m.notes.push_back("PLOT3D: " + count(hexes - blanked) + " hexes → " + count(m.tets.size()) +
                    " tets (5 per hex, alternating parity)");
  m.notes.push_back("merged " + count(merged) + " duplicate points (" + count(before) + " → " +
                    count(m.points.size()) + ")");
  if (has_iblank)
    m.notes.push_back("IBLANK skipped " + count(blanked) + " hexes (" + count(fringe) +
                      " fringe points with IBLANK < 0 kept)");
  if (degenerate > 0)
    m.notes.push_back(
        count(degenerate) +
        " tets are degenerate: zero volume or a vertex repeated (collapsed grid cells)");
  m.notes.push_back("scalar: PLOT3D function " + std::to_string(fn.number) + " (" + fn.name + ")" +
                    (fn.number == 140 ? ", computed as E/rho - |V|^2/2" : "") +
                    (m.scalar_choice.empty() ? "" : ", the first that varies: " + m.scalar_choice));
  if (nonfinite > 0)
    m.notes.push_back(count(nonfinite) +
                      " scalar values are not finite (function undefined "
                      "for this solution)");
  return m;
}

}  // namespace zs
