// The molecule reader through gemmi (src/geometry/spheres/molecule_reader.h):
// elements from the element columns or the atom name, Bondi radii, PDB and
// mmCIF (and their .gz) of one structure alike, models, alternate locations,
// waters and hydrogens, real files from Debian's pymol-data, and one-line
// errors for malformed and truncated files (issue 40, "Must show").
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "base/util/file_error.h"
#include "geometry/spheres/molecule_reader.h"
#include "support/file_error_of.h"
#include "support/test_paths.h"

namespace zs {
namespace {

namespace fs = std::filesystem;

using test::error_of;

// One ATOM/HETATM record in the PDB's fixed columns (80 wide with the element).
struct Rec {
  const char* rec = "ATOM";
  const char* name = " CA ";
  const char* res = "ALA";
  char chain = 'A';
  int seq = 1;
  double x = 0, y = 0, z = 0, b = 10;
  const char* element = "";
  char alt = ' ';
  double occ = 1.0;
};
std::string record(const Rec& r, int serial = 1) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%-6s%5d %-4s%c%3s %c%4d%c   %8.3f%8.3f%8.3f%6.2f%6.2f          %2s\n", r.rec,
                serial, r.name, r.alt, r.res, r.chain, r.seq, ' ', r.x, r.y, r.z, r.occ, r.b, r.element);
  return buf;
}
std::string records(const std::vector<Rec>& rs) {
  std::string s;
  int serial = 1;
  for (const Rec& r : rs) s += record(r, serial++);
  return s;
}

void write_file(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

bool have_command(const char* cmd) { return std::system((std::string("command -v ") + cmd + " >/dev/null 2>&1").c_str()) == 0; }

int run(const std::string& cmd) { return std::system((cmd + " >/dev/null 2>&1").c_str()); }

// The hand-made structure: two-letter elements in the element columns (FE,
// CL, ZN, SE), blank element columns with the atom-name convention (" CA "
// carbon alpha, "CA  " calcium, "FE  " iron, "1HB " and "HG21" hydrogens,
// " SD " sulfur), amino acids, a selenomethionine, ions, a heme iron, a
// water and a nucleotide in four chains.
std::string hand_made_pdb() {
  return "HEADER    TEST STRUCTURE\nCRYST1   40.000   40.000   40.000  90.00  90.00  90.00 P 1           1\n" +
         records({
             {"ATOM", " N  ", "ALA", 'A', 1, 1.5, -2.25, 3.0, 10.5, "N"},
             {"ATOM", " CA ", "ALA", 'A', 1, 2.5, -2.0, 3.5, 11.25, ""},
             {"ATOM", "1HB ", "ALA", 'A', 1, 3.0, -1.0, 4.0, 12.0, ""},
             {"ATOM", " SD ", "MET", 'A', 2, 4.0, 0.5, 2.0, 13.5, ""},
             {"ATOM", "HG21", "THR", 'A', 3, 5.0, 1.0, 1.0, 14.0, ""},
             {"HETATM", "SE  ", "MSE", 'A', 4, 6.0, 1.5, 0.5, 15.75, "SE"},
         }) +
         "TER\n" +
         records({
             {"HETATM", "CA  ", " CA", 'B', 101, -3.0, 2.0, 1.0, 20.0, ""},
             {"HETATM", "FE  ", "HEM", 'B', 102, -4.0, 3.0, 2.0, 21.5, ""},
             {"HETATM", "FE  ", "FE2", 'B', 103, -5.0, 4.0, 3.0, 22.0, "FE"},
             {"HETATM", "CL  ", " CL", 'B', 104, -6.0, 5.0, 4.0, 23.25, "CL"},
             {"HETATM", "ZN  ", " ZN", 'B', 105, -7.0, 6.0, 5.0, 24.0, "ZN"},
             {"HETATM", " O  ", "HOH", 'W', 201, 8.0, -6.0, 7.5, 30.0, "O"},
             {"ATOM", " P  ", " DA", 'C', 1, 9.0, 7.0, -8.0, 40.0, "P"},
         }) +
         "END\n";
}

TEST(MoleculeReader, TwoLetterElementsAndTheAtomNameConvention) {
  const SphereSet s = parse_pdb(hand_made_pdb(), "h.pdb");
  ASSERT_EQ(s.size(), 13u);
  //                                  N  C  H  S   H  Se  Ca  Fe  Fe  Cl  Zn  O  P
  EXPECT_EQ(s.element, (std::vector<uint8_t>{7, 6, 1, 16, 1, 34, 20, 26, 26, 17, 30, 8, 15}));
  // Bondi: N 1.55, C 1.70, H 1.20, S 1.80, Se 1.90, Cl 1.75, Zn 1.39, O 1.52,
  // P 1.80; Ca and Fe are not in Bondi's table: the default 1.8, counted.
  EXPECT_EQ(s.radii, (std::vector<double>{1.55, 1.70, 1.20, 1.80, 1.20, 1.90, 1.8, 1.8, 1.8, 1.75, 1.39, 1.52, 1.80}));
  EXPECT_EQ(s.centres[1], glm::dvec3(2.5, -2.0, 3.5));
  EXPECT_EQ(s.centres[12], glm::dvec3(9.0, 7.0, -8.0));
  EXPECT_EQ(s.scalar_name, "b_factor");
  EXPECT_EQ(s.scalars[1], 11.25);
  const MoleculeCounts& c = s.molecule;
  EXPECT_EQ(c.atoms, 13u);
  EXPECT_EQ(c.models, 1u);
  EXPECT_EQ(c.model, "1");
  EXPECT_EQ(c.chains, 4u);
  EXPECT_EQ(s.chain_names, (std::vector<std::string>{"A", "B", "W", "C"}));
  EXPECT_EQ(s.chain, (std::vector<uint16_t>{0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 2, 3}));
  EXPECT_EQ(c.residues, 11u);
  EXPECT_EQ(c.waters, 1u);
  EXPECT_EQ(c.hydrogens, 2u);
  EXPECT_EQ(c.unknown_elements, 3u);  // Ca, Fe, Fe
  EXPECT_EQ(c.elements_inferred, 6u);  // " CA ", "1HB ", " SD ", "HG21", "CA  ", "FE  "
  EXPECT_EQ(c.element_columns_cleared, 0u);
  EXPECT_EQ(c.charge_columns_cleared, 0u);
  EXPECT_EQ(c.altlocs_left_out, 0u);
  const std::map<std::string, size_t> elements(c.elements.begin(), c.elements.end());
  EXPECT_EQ(elements, (std::map<std::string, size_t>{{"C", 1}, {"Ca", 1}, {"Cl", 1}, {"Fe", 2}, {"H", 2}, {"N", 1},
                                                      {"O", 1}, {"P", 1}, {"S", 1}, {"Se", 1}, {"Zn", 1}}));
  ASSERT_FALSE(c.elements.empty());
  EXPECT_EQ(c.elements[0].second, 2u);  // most first
  using RC = ResidueClass;
  EXPECT_EQ(s.residue_class,
            (std::vector<RC>{RC::Hydrophobic, RC::Hydrophobic, RC::Hydrophobic, RC::Hydrophobic, RC::Polar,
                             RC::OtherAminoAcid, RC::Other, RC::Other, RC::Other, RC::Other, RC::Other, RC::Water,
                             RC::Nucleic}));
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_EQ(s.notes[0], "3 atoms of an element without a tabulated radius: 1.8 Å");
}

// The fields both formats give alike (the PDB-only column counts aside).
void expect_same_molecule(const SphereSet& a, const SphereSet& b, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(a.centres, b.centres);
  EXPECT_EQ(a.radii, b.radii);
  EXPECT_EQ(a.scalars, b.scalars);
  EXPECT_EQ(a.scalar_name, b.scalar_name);
  EXPECT_EQ(a.element, b.element);
  EXPECT_EQ(a.chain, b.chain);
  EXPECT_EQ(a.chain_names, b.chain_names);
  EXPECT_EQ(a.residue_class, b.residue_class);
  EXPECT_EQ(a.skipped, b.skipped);
  const MoleculeCounts &x = a.molecule, &y = b.molecule;
  EXPECT_EQ(x.atoms, y.atoms);
  EXPECT_EQ(x.models, y.models);
  EXPECT_EQ(x.model, y.model);
  EXPECT_EQ(x.chains, y.chains);
  EXPECT_EQ(x.residues, y.residues);
  EXPECT_EQ(x.waters, y.waters);
  EXPECT_EQ(x.hydrogens, y.hydrogens);
  EXPECT_EQ(x.waters_left_out, y.waters_left_out);
  EXPECT_EQ(x.hydrogens_left_out, y.hydrogens_left_out);
  EXPECT_EQ(x.altlocs_left_out, y.altlocs_left_out);
  EXPECT_EQ(x.unknown_elements, y.unknown_elements);
  EXPECT_EQ(x.elements, y.elements);
}

// gemmi's own writer turns the PDB into mmCIF (`gemmi convert`, Debian's
// gemmi); that mmCIF, and the .gz of both, read as the PDB does.
TEST(MoleculeReader, MmcifWrittenByGemmiAndGzipReadAsThePdb) {
  if (!have_command("gemmi")) GTEST_SKIP() << "no `gemmi` program (apt-get install gemmi) to write the mmCIF";
  const fs::path dir = test::scratch_dir();
  const std::string pdb = (dir / "h.pdb").string(), cif = (dir / "h.cif").string();
  write_file(pdb, hand_made_pdb());
  ASSERT_EQ(run("gemmi convert '" + pdb + "' '" + cif + "'"), 0);
  const SphereSet p = read_molecule(pdb);
  const SphereSet c = read_molecule(cif);
  expect_same_molecule(p, c, "h.cif");
  EXPECT_EQ(c.molecule.elements_inferred, 0u);  // mmCIF always names the element (type_symbol)
  EXPECT_EQ(p.notes, c.notes);
  if (!have_command("gzip")) GTEST_SKIP() << "no gzip";
  ASSERT_EQ(run("gzip -kf '" + pdb + "' '" + cif + "'"), 0);
  const SphereSet pz = read_molecule(pdb + ".gz");
  expect_same_molecule(p, pz, "h.pdb.gz");
  EXPECT_EQ(p.molecule.elements_inferred, pz.molecule.elements_inferred);
  EXPECT_EQ(p.notes, pz.notes);
  expect_same_molecule(p, read_molecule(cif + ".gz"), "h.cif.gz");
  // Upper-case names and .ent/.mmcif read by the same rule.
  fs::copy_file(pdb, dir / "H.ENT");
  fs::copy_file(cif, dir / "h.mmcif");
  expect_same_molecule(p, read_molecule((dir / "H.ENT").string()), "H.ENT");
  expect_same_molecule(p, read_molecule((dir / "h.mmcif").string()), "h.mmcif");
}

TEST(MoleculeReader, ModelsFirstByDefaultAnotherByNumber) {
  const std::string text = "MODEL        1\n" + records({{"ATOM", " N  ", "GLY", 'A', 1, 1, 1, 1, 5, "N"},
                                                      {"ATOM", " CA ", "GLY", 'A', 1, 2, 2, 2, 5, "C"}}) +
                           "ENDMDL\nMODEL        2\n" + records({{"ATOM", " N  ", "GLY", 'A', 1, 9, 9, 9, 6, "N"}}) +
                           "ENDMDL\nEND\n";
  const SphereSet first = parse_molecule(text, "m.pdb", MoleculeFormat::Pdb);
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first.centres[0], glm::dvec3(1, 1, 1));
  EXPECT_EQ(first.molecule.models, 2u);
  EXPECT_EQ(first.molecule.model, "1");
  EXPECT_EQ(first.notes.back(), "model 1 of 2");
  const SphereSet second = parse_molecule(text, "m.pdb", MoleculeFormat::Pdb, MoleculeOptions{.model = "2"});
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(second.centres[0], glm::dvec3(9, 9, 9));
  EXPECT_EQ(second.scalars[0], 6.0);
  EXPECT_EQ(second.molecule.model, "2");
  EXPECT_EQ(second.notes.back(), "model 2 of 2");
  EXPECT_EQ(error_of([&] { parse_molecule(text, "m.pdb", MoleculeFormat::Pdb, MoleculeOptions{.model = "3"}); }),
            "m.pdb: no model 3 (the file has 2 models: 1, 2)");
  // A file without MODEL records has one model, "1".
  const std::string one = records({{"ATOM", " N  ", "GLY", 'A', 1, 1, 1, 1, 5, "N"}});
  EXPECT_EQ(parse_molecule(one, "o.pdb", MoleculeFormat::Pdb, MoleculeOptions{.model = "1"}).size(), 1u);
  EXPECT_EQ(error_of([&] { parse_molecule(one, "o.pdb", MoleculeFormat::Pdb, MoleculeOptions{.model = "2"}); }),
            "o.pdb: no model 2 (the file has 1 model: 1)");
}

TEST(MoleculeReader, FirstAlternateLocationKeptOthersCounted) {
  Rec a{"ATOM", " CB ", "SER", 'A', 1, 2, 2, 2, 5, "C", 'A', 0.6};
  Rec b{"ATOM", " CB ", "SER", 'A', 1, 3, 3, 3, 5, "C", 'B', 0.4};
  Rec oa{"ATOM", " OG ", "SER", 'A', 1, 4, 4, 4, 5, "O", 'A', 0.6};
  Rec ob{"ATOM", " OG ", "SER", 'A', 1, 5, 5, 5, 5, "O", 'B', 0.4};
  const SphereSet s = parse_pdb(records({{"ATOM", " N  ", "SER", 'A', 1, 1, 1, 1, 5, "N"}, a, b, oa, ob}), "a.pdb");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.centres[1], glm::dvec3(2, 2, 2));
  EXPECT_EQ(s.centres[2], glm::dvec3(4, 4, 4));
  EXPECT_EQ(s.skipped, 2u);
  EXPECT_EQ(s.molecule.altlocs_left_out, 2u);
  EXPECT_EQ(s.molecule.atoms, 3u);
  ASSERT_FALSE(s.notes.empty());
  EXPECT_EQ(s.notes[0], "2 alternate locations skipped (kept 'A')");
}

// A serine with its hydrogens and two waters.
std::string with_waters_and_hydrogens() {
  return records({{"ATOM", " N  ", "SER", 'A', 1, 1, 1, 1, 5, "N"},
                  {"ATOM", " CA ", "SER", 'A', 1, 2, 1, 1, 5, "C"},
                  {"ATOM", " H  ", "SER", 'A', 1, 1, 2, 1, 5, "H"},
                  {"ATOM", " HA ", "SER", 'A', 1, 2, 2, 1, 5, ""},
                  {"HETATM", " O  ", "HOH", 'A', 101, 5, 5, 5, 30, "O"},
                  {"HETATM", " O  ", "HOH", 'A', 102, 6, 6, 6, 31, "O"}});
}

TEST(MoleculeReader, WatersAndHydrogensLeftOutOnRequest) {
  const std::string text = with_waters_and_hydrogens();
  const SphereSet all = parse_pdb(text, "w.pdb");
  EXPECT_EQ(all.size(), 6u);
  EXPECT_EQ(all.molecule.waters, 2u);
  EXPECT_EQ(all.molecule.hydrogens, 2u);
  EXPECT_EQ(all.molecule.residues, 3u);

  const SphereSet dry = parse_molecule(text, "w.pdb", MoleculeFormat::Pdb, MoleculeOptions{.waters = false});
  ASSERT_EQ(dry.size(), 4u);
  EXPECT_EQ(dry.molecule.waters, 0u);
  EXPECT_EQ(dry.molecule.waters_left_out, 2u);
  EXPECT_EQ(dry.molecule.residues, 1u);
  for (ResidueClass rc : dry.residue_class) EXPECT_NE(rc, ResidueClass::Water);
  EXPECT_EQ(dry.notes.back(), "2 water atoms left out");

  const SphereSet heavy = parse_molecule(text, "w.pdb", MoleculeFormat::Pdb, MoleculeOptions{.hydrogens = false});
  ASSERT_EQ(heavy.size(), 4u);
  EXPECT_EQ(heavy.molecule.hydrogens, 0u);
  EXPECT_EQ(heavy.molecule.hydrogens_left_out, 2u);
  for (uint8_t z : heavy.element) EXPECT_NE(z, 1);
  EXPECT_EQ(heavy.notes.back(), "2 hydrogens left out");

  const SphereSet both =
      parse_molecule(text, "w.pdb", MoleculeFormat::Pdb, MoleculeOptions{.waters = false, .hydrogens = false});
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both.element, (std::vector<uint8_t>{7, 6}));

  // A choice that leaves no atom is an error, not an empty picture.
  const std::string only_water = records({{"HETATM", " O  ", "HOH", 'A', 101, 5, 5, 5, 30, "O"}});
  EXPECT_EQ(error_of([&] { parse_molecule(only_water, "o.pdb", MoleculeFormat::Pdb, MoleculeOptions{.waters = false}); }),
            "o.pdb: no atoms left in model 1 once waters and hydrogens are left out");
  const std::string only_h = records({{"ATOM", " H  ", "SER", 'A', 1, 1, 2, 1, 5, "H"}});
  EXPECT_EQ(error_of([&] { parse_molecule(only_h, "o.pdb", MoleculeFormat::Pdb, MoleculeOptions{.hydrogens = false}); }),
            "o.pdb: no atoms left in model 1 once waters and hydrogens are left out");
}

// 1hpv (Debian's pymol-data): no element columns; columns 73-80 hold
// "1HPV 186" (segment id and line number). PyMOL reads 1,003 C, 263 N,
// 356 O and 9 S; so must we, at Bondi's radii.
TEST(MoleculeReader, Reads1hpvAsPymolDoes) {
  const std::string path = "/usr/share/pymol/data/tut/1hpv.pdb";
  if (!fs::exists(path)) GTEST_SKIP() << path << " not found (apt-get install pymol-data; scripts/setup-deps)";
  const SphereSet s = read_molecule(path);
  ASSERT_EQ(s.size(), 1631u);
  const MoleculeCounts& c = s.molecule;
  EXPECT_EQ(c.elements, (std::vector<std::pair<std::string, size_t>>{{"C", 1003}, {"O", 356}, {"N", 263}, {"S", 9}}));
  std::map<double, size_t> by_radius;
  std::map<int, size_t> by_number;
  for (size_t i = 0; i < s.size(); ++i) {
    ++by_radius[s.radii[i]];
    ++by_number[s.element[i]];
  }
  EXPECT_EQ(by_radius, (std::map<double, size_t>{{1.52, 356}, {1.55, 263}, {1.70, 1003}, {1.80, 9}}));
  EXPECT_EQ(by_number, (std::map<int, size_t>{{6, 1003}, {7, 263}, {8, 356}, {16, 9}}));
  EXPECT_EQ(c.unknown_elements, 0u);
  // Every record's columns 77-80 held line-number digits: no element, no charge.
  EXPECT_EQ(c.element_columns_cleared, 1631u);
  EXPECT_EQ(c.charge_columns_cleared, 1631u);
  EXPECT_EQ(c.elements_inferred, 1631u);
  EXPECT_EQ(c.models, 1u);
  EXPECT_EQ(c.altlocs_left_out, 0u);
  EXPECT_EQ(s.scalar_name, "b_factor");
  EXPECT_EQ(s.centres[0], glm::dvec3(13.120, 39.003, 5.159));
  EXPECT_EQ(s.scalars[0], 55.41);
}

// 1tii (pymol-data) has element columns: it reads as the hand-written reader
// before gemmi read it. The numbers are the pre-gemmi binary's (`zsweep mesh
// info`; its `spheres convert` .sph is byte-identical to today's, checked in
// cli.molecules): 5,684 spheres, radii 1.52-1.8 by the element columns
// (3,405 C, 956 N, 1,278 O, 45 S), B-factors 2.89-94.62.
TEST(MoleculeReader, Reads1tiiAsBeforeGemmi) {
  const std::string path = "/usr/share/pymol/data/demo/1tii.pdb";
  if (!fs::exists(path)) GTEST_SKIP() << path << " not found (apt-get install pymol-data; scripts/setup-deps)";
  const SphereSet s = read_molecule(path);
  ASSERT_EQ(s.size(), 5684u);
  EXPECT_EQ(s.skipped, 0u);
  EXPECT_EQ(s.invalid, 0u);
  glm::dvec3 lo(1e300), hi(-1e300);
  double rmin = 1e300, rmax = 0, bmin = 1e300, bmax = -1e300;
  std::map<double, size_t> by_radius;
  for (size_t i = 0; i < s.size(); ++i) {
    lo = glm::min(lo, s.centres[i]);
    hi = glm::max(hi, s.centres[i]);
    rmin = std::min(rmin, s.radii[i]);
    rmax = std::max(rmax, s.radii[i]);
    bmin = std::min(bmin, s.scalars[i]);
    bmax = std::max(bmax, s.scalars[i]);
    ++by_radius[s.radii[i]];
  }
  EXPECT_EQ(lo, glm::dvec3(11.59, -22.877, -28.27));
  EXPECT_EQ(hi, glm::dvec3(84.681, 40.101, 47.233));
  EXPECT_EQ(rmin, 1.52);
  EXPECT_EQ(rmax, 1.8);
  EXPECT_EQ(bmin, 2.89);
  EXPECT_EQ(bmax, 94.62);
  EXPECT_EQ(by_radius, (std::map<double, size_t>{{1.52, 1278}, {1.55, 956}, {1.70, 3405}, {1.80, 45}}));
  EXPECT_EQ(s.molecule.elements,
            (std::vector<std::pair<std::string, size_t>>{{"C", 3405}, {"O", 1278}, {"N", 956}, {"S", 45}}));
  EXPECT_EQ(s.molecule.element_columns_cleared, 0u);
  EXPECT_EQ(s.molecule.charge_columns_cleared, 0u);
  EXPECT_EQ(s.molecule.elements_inferred, 0u);
  EXPECT_EQ(s.molecule.waters, 215u);
  EXPECT_TRUE(s.notes.empty()) << s.notes.front();

  // The same file through the mmCIF path (gemmi's writer, then our reader):
  // the same spheres.
  if (!have_command("gemmi")) GTEST_SKIP() << "no `gemmi` program (apt-get install gemmi) for the mmCIF path";
  const fs::path dir = test::scratch_dir();
  const std::string cif = (dir / "1tii.cif").string();
  ASSERT_EQ(run("gemmi convert '" + path + "' '" + cif + "'"), 0);
  expect_same_molecule(s, read_molecule(cif), "1tii.cif");
}

// An error is one line that starts with the file's name.
void expect_one_line_error(const std::string& msg, const std::string& name) {
  EXPECT_FALSE(msg.empty()) << "no FileError for " << name;
  EXPECT_TRUE(msg.starts_with(name + ":")) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

std::string cif_error(const std::string& text) {
  return error_of([&] { parse_molecule(text, "b.cif", MoleculeFormat::Mmcif); });
}

TEST(MoleculeReader, MalformedMmcifIsOneLineNamingTheFile) {
  const std::string head =
      "data_x\nloop_\n_atom_site.group_PDB\n_atom_site.id\n_atom_site.type_symbol\n_atom_site.label_atom_id\n"
      "_atom_site.label_comp_id\n_atom_site.label_asym_id\n_atom_site.label_seq_id\n_atom_site.Cartn_x\n"
      "_atom_site.Cartn_y\n_atom_site.Cartn_z\n_atom_site.occupancy\n_atom_site.B_iso_or_equiv\n"
      "_atom_site.pdbx_PDB_model_num\n_atom_site.label_alt_id\n_atom_site.auth_seq_id\n";
  const std::string good = head + "ATOM 1 N N GLY A 1 1.0 2.0 3.0 1.0 5.0 1 . 1\n";
  const SphereSet s = parse_molecule(good, "g.cif", MoleculeFormat::Mmcif);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s.centres[0], glm::dvec3(1, 2, 3));
  EXPECT_EQ(s.radii[0], 1.55);

  // Not CIF at all, a bad token, an unterminated quoted value, a loop whose
  // values do not fill its rows, a loop without values, no data block.
  for (const std::string& text : std::vector<std::string>{
           "HEADER not a cif\n", "data_x\n_cell.length_a 10 11\n", "data_x\n_cell.length_a 'ten\n",
        head + "ATOM 1 N N GLY A 1 1.0 2.0\n", head + "ATOM 1 N N GLY A 1 1.0 2.0 3.0 1.0 5.0 1 . 1 extra\n",
        std::string("data_x\nloop_\n_atom_site.id\n_atom_site.Cartn_x\n"),
        std::string("_cell.length_a 10\n"), std::string("data_x\n;unterminated text field\n"),
        head + "ATOM 1 N N GLY A 1 abc 2.0 3.0 1.0 5.0 1 . 1\n"}) {
    SCOPED_TRACE(text);
    expect_one_line_error(cif_error(text), "b.cif");
  }
  // Where gemmi names the line, so do we.
  EXPECT_EQ(cif_error("data_x\n_cell.length_a 10\n_cell.length_b 'ten\n"), "b.cif:3:20: unterminated 'string'");
  EXPECT_EQ(cif_error("data_x\n_cell.length_a 10 11\n"), "b.cif:2:19: parse error");
  // A coordinate that is not a number (gemmi reads NaN) is an error, as in PDB.
  EXPECT_EQ(cif_error(head + "ATOM 1 N N GLY A 1 abc 2.0 3.0 1.0 5.0 1 . 1\n"),
            "b.cif: atom 1 (N of GLY 1, chain A): coordinate not a finite number");

  // An integer gemmi would overflow (scripts/fuzz, cif): an error first.
  const std::string big = head + "ATOM 1 N N GLY A 1 1.0 2.0 3.0 1.0 5.0 1 . 2555555555\n";
  EXPECT_EQ(cif_error(big), "b.cif: _atom_site.auth_seq_id 2555555555: integer out of range");
  EXPECT_EQ(cif_error("data_x\n_atom_site.pdbx_formal_charge -99999999999\n"),
            "b.cif:2: _atom_site.pdbx_formal_charge -99999999999: integer out of range");
  // gemmi reads the leading digits and stops at anything else: they decide.
  EXPECT_EQ(cif_error(head + "ATOM 2555555555#5 N N GLY A 1 1.0 2.0 3.0 1.0 5.0 1 . 1\n"),
            "b.cif: _atom_site.id 2555555555#5: integer out of range");
  EXPECT_EQ(parse_molecule(head + "ATOM 0000000000001 N N GLY A 1 1.0 2.0 3.0 1.0 5.0 1 . -999\n", "g.cif",
                           MoleculeFormat::Mmcif).size(), 1u);  // leading zeros, negative residue numbers: fine

  // Well-formed CIF without atoms, or whose _atom_site lacks a column gemmi
  // needs (here label_alt_id and auth_seq_id).
  const std::string no_atoms = "b.cif: no atoms (an _atom_site loop with id, type_symbol, label_alt_id, "
                               "label_asym_id, auth_seq_id, Cartn_x, Cartn_y, Cartn_z, occupancy and B_iso_or_equiv)";
  EXPECT_EQ(cif_error("data_x\n_cell.length_a 10\n"), no_atoms);
  EXPECT_EQ(cif_error("data_x\n"), no_atoms);
  EXPECT_EQ(cif_error("data_x\nloop_\n_atom_site.id\n_atom_site.type_symbol\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
                      "_atom_site.Cartn_z\n1 C 0 0 0\n"),
            no_atoms);
  // No data block at all (gemmi would index an empty list).
  EXPECT_EQ(cif_error(""), "b.cif: no data block (data_...)");
  EXPECT_EQ(cif_error("# only a comment\n"), "b.cif: no data block (data_...)");
  // Coordinates in a second block too: gemmi's two-line message, first line.
  EXPECT_EQ(cif_error(good + "data_y\n" + good.substr(7)), "b.cif: 2+ blocks are ok if only the first one has coordinates;");
}

TEST(MoleculeReader, MalformedPdbIsOneLineNamingFileAndLine) {
  const std::string ok = records({{"ATOM", " N  ", "GLY", 'A', 1, 1, 1, 1, 5, "N"}});
  // ANISOU must follow its atom; gemmi says "Problem in line N".
  const std::string anisou = "ANISOU    1  N   GLY A   1     1000   2000   3000      0      0      0       N\n";
  const std::string msg = error_of([&] { parse_pdb(anisou + ok, "a.pdb"); });
  expect_one_line_error(msg, "a.pdb");
  EXPECT_TRUE(msg.starts_with("a.pdb:1: ")) << msg;
  const std::string msg2 = error_of([&] { parse_pdb(ok + anisou + anisou, "a.pdb"); });
  expect_one_line_error(msg2, "a.pdb");
  EXPECT_TRUE(msg2.starts_with("a.pdb:3: ")) << msg2;
  // In its place it is read (and the atom drawn as before).
  EXPECT_EQ(parse_pdb(ok + anisou, "a.pdb").size(), 1u);
  // Garbage that is neither: no atoms.
  EXPECT_EQ(error_of([&] { parse_pdb(std::string("\x01\x02\x03 binary\n", 11), "g.pdb"); }),
            "g.pdb: no ATOM or HETATM records in model 1");
}

// Bytes above 127 in a residue name (scripts/fuzz found gemmi's residue
// look-ups shifting them as negative chars): read, of no known class.
TEST(MoleculeReader, NonAsciiResidueNameIsOther) {
  const SphereSet s = parse_pdb(records({{"ATOM", " CA ", "\xbe\xdf\xbe", 'A', 1, 1, 1, 1, 5, "C"},
                                         {"HETATM", " O  ", "HOH", 'A', 2, 2, 2, 2, 5, "O"}}),
                                "n.pdb");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.residue_class, (std::vector<ResidueClass>{ResidueClass::Other, ResidueClass::Water}));
  EXPECT_EQ(s.molecule.waters, 1u);
}

TEST(MoleculeReader, TruncatedOrBrokenGzipIsOneLineNamingTheFile) {
  if (!have_command("gzip")) GTEST_SKIP() << "no gzip";
  const fs::path dir = test::scratch_dir();
  const fs::path pdb = dir / "t.pdb";
  std::string text;
  for (int i = 0; i < 400; ++i) text += record({"ATOM", " CA ", "ALA", 'A', i + 1, i * 0.5, i * 0.25, -i * 0.125, 5, "C"}, i + 1);
  write_file(pdb, text);
  ASSERT_EQ(run("gzip -kf '" + pdb.string() + "'"), 0);
  const std::string gz = pdb.string() + ".gz";
  EXPECT_EQ(read_molecule(gz).size(), 400u);
  // Cut in half.
  const auto size = fs::file_size(gz);
  fs::resize_file(gz, size / 2);
  const std::string cut = error_of([&] { read_molecule(gz); });
  expect_one_line_error(cut, gz);
  EXPECT_EQ(cut.find(gz, 1), std::string::npos) << "the name once: " << cut;
  // Not gzip at all behind a .gz name, and a gzip header with nothing after it.
  const std::string fake = (dir / "f.cif.gz").string();
  write_file(fake, "\x1f\x8b\x08\x00garbage");
  const std::string not_gz = error_of([&] { read_molecule(fake); });
  expect_one_line_error(not_gz, fake);
  EXPECT_EQ(not_gz.find(fake, 1), std::string::npos) << "the name once: " << not_gz;
  const std::string empty = (dir / "e.pdb.gz").string();
  write_file(empty, "");
  expect_one_line_error(error_of([&] { read_molecule(empty); }), empty);
  const std::string missing = (dir / "none.cif.gz").string();
  EXPECT_EQ(error_of([&] { read_molecule(missing); }), missing + ": no such file");
  const std::string missing_cif = (dir / "none.cif").string();
  expect_one_line_error(error_of([&] { read_molecule(missing_cif); }), missing_cif);
}

}  // namespace
}  // namespace zs
