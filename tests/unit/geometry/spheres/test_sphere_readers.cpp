// The sphere readers: .sph lists and PDB atoms (src/geometry/spheres/).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "base/util/file_error.h"
#include "geometry/spheres/molecule_reader.h"
#include "geometry/spheres/sphere_colors.h"
#include "geometry/spheres/sphere_io.h"
#include "geometry/spheres/sphere_reader.h"
#include "support/file_error_of.h"
#include "support/test_paths.h"

namespace zs {
namespace {

using test::error_of;

std::string sph_error(const std::string& text) {
  return error_of([&] { parse_spheres(text, "s.sph"); });
}
std::string pdb_error(const std::string& text) {
  return error_of([&] { parse_pdb(text, "p.pdb"); });
}

// One ATOM/HETATM record in the PDB's fixed columns (80 wide with the element).
std::string atom(const char* rec, const char* name, char alt, double x, double y, double z, double b,
                 const char* element) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%-6s%5d %-4s%c%3s %c%4d%c   %8.3f%8.3f%8.3f%6.2f%6.2f          %2s\n", rec, 1,
                name, alt, "ALA", 'A', 1, ' ', x, y, z, 1.0, b, element);
  return buf;
}

TEST(SphereReader, ReadsSpheresCommentsAndScalars) {
  const SphereSet s = parse_spheres("# x y z r s\n\n1 2 3 0.5 7\n  -1e3 +2 0 2.25 -1\r\n# end\n", "s.sph");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.centres[0], glm::dvec3(1, 2, 3));
  EXPECT_EQ(s.centres[1], glm::dvec3(-1000, 2, 0));
  EXPECT_EQ(s.radii[1], 2.25);
  ASSERT_TRUE(s.has_scalars());
  EXPECT_EQ(s.scalars[0], 7.0);
  EXPECT_EQ(s.scalars[1], -1.0);
  EXPECT_EQ(s.degenerate, 0u);
}

TEST(SphereReader, InvalidSpheresAreSkippedAndCountedNonFiniteScalarKept) {
  const SphereSet s = parse_spheres("0 0 0 0\n1 1 1 1\n2 2 2 -0\n3 3 3 -0.5\n4 4 4 inf\n5 5 5 nan\n"
                                    "nan 6 6 1\n7 -inf 7 1\n8 8 8 2\n", "s.sph");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.invalid, 7u);
  EXPECT_EQ(s.degenerate, 0u);
  EXPECT_EQ(s.centres[1], glm::dvec3(8, 8, 8));
  EXPECT_EQ(s.radii[1], 2.0);
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_EQ(s.notes[0], "7 spheres skipped: zero, negative or non-finite radius, or non-finite centre");
  const SphereSet t = parse_spheres("0 0 0 1 nan\n1 1 1 1 1\n2 2 2 -1 5\n", "s.sph");
  EXPECT_EQ(t.size(), 2u);
  EXPECT_EQ(t.degenerate, 1u);
  EXPECT_EQ(t.invalid, 1u);
  ASSERT_EQ(t.scalars.size(), 2u);
  EXPECT_TRUE(std::isnan(t.scalars[0]));
}

TEST(SphereReader, ReadsRgbaSpheres) {
  const SphereSet s = parse_spheres("# x y z r R G B A\n1 2 3 0.5 1 0 0.25 0.5\n0 0 0 1 0 1 1 1\n", "s.sph");
  ASSERT_EQ(s.size(), 2u);
  ASSERT_TRUE(s.has_rgba());
  EXPECT_FALSE(s.has_scalars());
  EXPECT_EQ(s.rgba[0], glm::vec4(1, 0, 0.25f, 0.5f));
  EXPECT_EQ(s.rgba[1], glm::vec4(0, 1, 1, 1));
  // A colour out of range is an error even on a sphere that would be skipped.
  EXPECT_EQ(sph_error("0 0 0 1 0 0 0 1\n0 0 0 0 0 0 0 1.5\n"), "s.sph:2: A '1.5' is not in [0, 1]");
  EXPECT_EQ(sph_error("0 0 0 1 -0.1 0 0 1\n"), "s.sph:1: R '-0.1' is not in [0, 1]");
  EXPECT_EQ(sph_error("0 0 0 1 0 nan 0 1\n"), "s.sph:1: G 'nan' is not in [0, 1]");
  EXPECT_EQ(sph_error("0 0 0 1 0 0 inf 1\n"), "s.sph:1: B 'inf' is not in [0, 1]");
}

TEST(SphereReader, ErrorsNameFileAndLine) {
  const std::string forms = "expected 'x y z r', 'x y z r scalar' or 'x y z r R G B A' (4, 5 or 8 numbers), found ";
  EXPECT_EQ(sph_error("1 2 3\n"), "s.sph:1: " + forms + "3 fields");
  EXPECT_EQ(sph_error("# c\n1 2 3 4 5 6 7\n"), "s.sph:2: " + forms + "7 fields");
  EXPECT_EQ(sph_error("# c\n1 2 3 4 5 6\n"), "s.sph:2: " + forms + "6 fields");
  EXPECT_EQ(sph_error("\n\n1 2 3 4 5 6 7 8 9\n"), "s.sph:3: " + forms + "9+ fields");
  EXPECT_EQ(sph_error("1 2 3 4\n1 2 3 4 5\n"), "s.sph:2: expected 4 numbers like line 1, found 5");
  EXPECT_EQ(sph_error("1 2 3 4 0 0 0 1\n\n1 2 3 4 5\n"), "s.sph:3: expected 8 numbers like line 1, found 5");
  EXPECT_EQ(sph_error("1 2 3 4\n1 two 3 4\n"), "s.sph:2: expected a number, found 'two'");
  EXPECT_EQ(sph_error("# only a comment\n\n"), "s.sph: no spheres (expected lines 'x y z r [scalar | R G B A]')");
  EXPECT_EQ(sph_error(""), "s.sph: no spheres (expected lines 'x y z r [scalar | R G B A]')");
  EXPECT_EQ(sph_error("1 2 3 -1\n1 2 3 0\n"),
            "s.sph: no drawable spheres: all 2 have a zero, negative or non-finite radius or a non-finite centre");
}

TEST(PdbReader, ReadsAtomsAndHetatmsByColumn) {
  const std::string text = "HEADER    TEST\nREMARK   1 nothing\n" + atom("ATOM", " N  ", ' ', 1.5, -2.25, 3, 10.5, "N") +
                           atom("ATOM", " CA ", ' ', -10.125, 20, 30.5, 11, "C") +
                           atom("HETATM", "FE  ", ' ', 0, 0, 0, 12, "FE") + "TER\nCONECT    1    2\nEND\n";
  const SphereSet s = parse_pdb(text, "p.pdb");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.centres[0], glm::dvec3(1.5, -2.25, 3));
  EXPECT_EQ(s.centres[1], glm::dvec3(-10.125, 20, 30.5));
  EXPECT_EQ(s.radii[0], 1.55);  // Bondi's N
  EXPECT_EQ(s.radii[1], 1.70);  // C
  EXPECT_EQ(s.radii[2], 1.8);   // Fe: no tabulated radius, the default
  ASSERT_TRUE(s.has_scalars());
  EXPECT_EQ(s.scalar_name, "b_factor");
  EXPECT_EQ(s.scalars[2], 12.0);
  EXPECT_EQ(s.skipped, 0u);
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_EQ(s.notes[0], "1 atoms of an element without a tabulated radius: 1.8 Å");
  ASSERT_TRUE(s.has_elements());
  EXPECT_EQ(s.element, (std::vector<uint8_t>{7, 6, 26}));  // N, C, Fe
}

TEST(PdbReader, ElementNumbersFromElementFieldOrAtomName) {
  const std::string text = atom("ATOM", " CA ", ' ', 0, 0, 0, 1, "") + atom("HETATM", "CA  ", ' ', 0, 0, 0, 1, "CA") +
                           atom("ATOM", "1HB ", ' ', 0, 0, 0, 1, "") + atom("ATOM", " SD ", ' ', 0, 0, 0, 1, "S") +
                           atom("HETATM", "ZN  ", ' ', 0, 0, 0, 1, "Zn") + atom("ATOM", " XX ", ' ', 0, 0, 0, 1, "Xx") +
                           atom("ATOM", " D1 ", ' ', 0, 0, 0, 1, "D");
  const SphereSet s = parse_pdb(text, "p.pdb");
  EXPECT_EQ(s.element, (std::vector<uint8_t>{6, 20, 1, 16, 30, 0, 1}));
  EXPECT_EQ(default_color_mode(s), SphereColorMode::Element);
  const auto colours = sphere_colors(s, SphereColorMode::Element, TransferFunction{});
  EXPECT_EQ(colours[3], element_color(16));   // sulfur: yellow
  EXPECT_NE(colours[3], element_color(0));
  EXPECT_EQ(colours[5], element_color(0));    // unknown: grey
}

TEST(PdbReader, BlankElementFallsBackToAtomName) {
  const std::string text = atom("ATOM", " CA ", ' ', 0, 0, 0, 1, "") + atom("HETATM", "CL  ", ' ', 0, 0, 0, 1, "") +
                           atom("ATOM", "1HB ", ' ', 0, 0, 0, 1, "") + atom("ATOM", " OG ", ' ', 0, 0, 0, 1, "  ");
  const SphereSet s = parse_pdb(text, "p.pdb");
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s.radii[0], 1.70);  // " CA " is carbon alpha, not calcium
  EXPECT_EQ(s.radii[1], 1.75);  // "CL  " is chlorine
  EXPECT_EQ(s.radii[2], 1.20);  // "1HB " is hydrogen
  EXPECT_EQ(s.radii[3], 1.52);
}

TEST(PdbReader, FirstModelOnlyAndFirstAlternateLocation) {
  const std::string text = "MODEL        1\n" + atom("ATOM", " N  ", ' ', 1, 1, 1, 1, "N") +
                           atom("ATOM", " CB ", 'A', 2, 2, 2, 1, "C") + atom("ATOM", " CB ", 'B', 3, 3, 3, 1, "C") +
                           "ENDMDL\nMODEL        2\n" + atom("ATOM", " N  ", ' ', 9, 9, 9, 1, "N") + "ENDMDL\n";
  const SphereSet s = parse_pdb(text, "p.pdb");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.centres[1], glm::dvec3(2, 2, 2));
  EXPECT_EQ(s.skipped, 1u);
  ASSERT_EQ(s.notes.size(), 2u);
  EXPECT_EQ(s.notes[0], "1 alternate locations skipped (kept 'A')");
  EXPECT_EQ(s.notes[1], "model 1 of 2");
  EXPECT_EQ(s.molecule.models, 2u);
  EXPECT_EQ(s.molecule.altlocs_left_out, 1u);
}

TEST(PdbReader, NoScalarWhenAnAtomLacksItsBFactor) {
  std::string short_b = atom("ATOM", " N  ", ' ', 1, 1, 1, 1, "N").substr(0, 54) + "\r\n";
  const SphereSet s = parse_pdb(atom("ATOM", " N  ", ' ', 0, 0, 0, 5, "N") + short_b, "p.pdb");
  EXPECT_EQ(s.size(), 2u);
  EXPECT_FALSE(s.has_scalars());
  EXPECT_EQ(s.radii[1], 1.55);  // no element columns: from the atom name " N  "
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_EQ(s.notes[0], "no B-factor (columns 61-66) on line 2: no scalar");
}

TEST(PdbReader, ErrorsNameFileAndLine) {
  const std::string ok = atom("ATOM", " N  ", ' ', 1, 1, 1, 1, "N");
  EXPECT_EQ(pdb_error(ok + "ATOM      2  CA  ALA A   1      11.104   6.134\n"),
            "p.pdb:2: ATOM record too short: 46 columns, coordinates need columns 31-54");
  std::string bad = ok;
  bad.replace(38, 8, "   abc  ");
  EXPECT_EQ(pdb_error(ok + bad), "p.pdb:2: ATOM: y coordinate 'abc' is not a number (columns 39-46)");
  bad = atom("HETATM", "ZN  ", ' ', 1, 1, 1, 1, "ZN");
  bad.replace(46, 8, "     nan");
  EXPECT_EQ(pdb_error(bad), "p.pdb:1: HETATM: non-finite z coordinate 'nan' (columns 47-54)");
  bad.replace(30, 8, "        ");
  EXPECT_EQ(pdb_error(bad), "p.pdb:1: HETATM: x coordinate '' is not a number (columns 31-38)");
  EXPECT_EQ(pdb_error("HEADER    EMPTY\nEND\n"), "p.pdb: no ATOM or HETATM records in model 1");
  // A stray ENDMDL before the first atom ends no model (gemmi reads on).
  EXPECT_EQ(parse_pdb("ENDMDL\n" + ok, "p.pdb").size(), 1u);
}

TEST(SphereIo, ReadsFilesByExtension) {
  const auto dir = test::scratch_dir();
  const std::string sph = (dir / "a.SPH").string(), pdb = (dir / "b.pdb").string();
  std::ofstream(sph) << "0 0 0 1\n";
  std::ofstream(pdb) << atom("ATOM", " O  ", ' ', 1, 2, 3, 4, "O");
  EXPECT_TRUE(is_sphere_file(sph));
  EXPECT_FALSE(is_sphere_file((dir / "m.off").string()));
  EXPECT_EQ(read_sphere_file(sph).size(), 1u);
  EXPECT_EQ(read_sphere_file(pdb).radii[0], 1.52);
  const std::string missing = (dir / "none.pdb").string();
  EXPECT_EQ(error_of([&] { read_sphere_file(missing); }), missing + ": no such file");
  std::ofstream(sph) << "0 0 0 1\n0 0 0\n";
  EXPECT_EQ(error_of([&] { read_sphere_file(sph); }),
            sph + ":2: expected 'x y z r', 'x y z r scalar' or 'x y z r R G B A' (4, 5 or 8 numbers), found 3 fields");
}

// A real PDB file from Debian's pymol-data: the atom count must match an
// independent count of model 1's ATOM/HETATM lines.
TEST(PdbReader, ReadsPymolDataFile) {
  const char* const candidates[] = {"/usr/share/pymol/data/demo/1tii.pdb", "/usr/share/pymol/data/tut/1hpv.pdb",
                                    "/usr/share/pymol/data/demo/pept.pdb"};
  std::string path;
  for (const char* c : candidates)
    if (std::ifstream(c)) {
      path = c;
      break;
    }
  if (path.empty()) GTEST_SKIP() << "no PDB file from pymol-data (apt-get install pymol-data; scripts/setup-deps)";
  std::ifstream in(path);
  std::string line;
  size_t atoms = 0, other_alt = 0;
  char first_alt = ' ';
  double x0 = NAN;
  while (std::getline(in, line)) {
    if (line.rfind("ENDMDL", 0) == 0) break;
    if (line.rfind("ATOM", 0) != 0 && line.rfind("HETATM", 0) != 0) continue;
    if (atoms++ == 0) x0 = std::stod(line.substr(30, 8));
    const char alt = line[16];
    if (alt != ' ' && first_alt == ' ') first_alt = alt;
    if (alt != ' ' && alt != first_alt) ++other_alt;
  }
  const SphereSet s = read_molecule(path);
  ASSERT_GT(atoms, 10u) << path;
  EXPECT_EQ(s.size() + s.skipped, atoms) << path;
  EXPECT_EQ(s.skipped, other_alt) << path;
  EXPECT_EQ(s.centres[0].x, x0) << path;
  for (double r : s.radii) EXPECT_TRUE(r >= 1.2 && r <= 2.75) << r;
  // Proteins are mostly C, N, O (and S): every atom gets an element here.
  ASSERT_EQ(s.element.size(), s.size());
  size_t cno = 0;
  for (uint8_t z : s.element) cno += (z == 6 || z == 7 || z == 8);
  EXPECT_GT(cno, s.size() * 9 / 10) << path;
}

}  // namespace
}  // namespace zs
