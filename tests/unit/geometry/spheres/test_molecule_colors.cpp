// Colouring molecules by chain and by residue type (sphere_colors.h): the
// chain palette cycles by chain index, each residue class has its colour, and
// the modes refuse sets that are not molecules.
#include <cstdio>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/spheres/molecule_reader.h"
#include "geometry/spheres/sphere_colors.h"

namespace zs {
namespace {

// One ATOM/HETATM record in the PDB's fixed columns, with its residue and chain.
std::string record(const char* rec, int serial, const char* name, const char* res, char chain, int seq,
                   const char* element) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%-6s%5d %-4s%c%3s %c%4d%c   %8.3f%8.3f%8.3f%6.2f%6.2f          %2s\n", rec, serial,
                name, ' ', res, chain, seq, ' ', serial * 2.0, 0.0, 0.0, 1.0, 10.0 + serial, element);
  return buf;
}

std::tuple<float, float, float, float> key(const glm::vec4& c) { return {c.r, c.g, c.b, c.a}; }

TEST(MoleculeColors, ModesParseAndPrint) {
  for (const char* name : {"element", "rgba", "scalar", "chain", "residue"}) {
    SphereColorMode m = SphereColorMode::Element;
    ASSERT_TRUE(parse_sphere_color_mode(name, &m)) << name;
    EXPECT_EQ(std::string(to_string(m)), name);
  }
  SphereColorMode m;
  EXPECT_FALSE(parse_sphere_color_mode("bfactor", &m));
}

TEST(MoleculeColors, ChainPaletteCyclesByChainIndex) {
  std::set<std::tuple<float, float, float, float>> distinct;
  for (unsigned i = 0; i < kChainColors; ++i) {
    const glm::vec4 c = chain_color(i);
    EXPECT_EQ(c.a, 1.f);
    EXPECT_EQ(chain_color(i + kChainColors), c);
    distinct.insert(key(c));
  }
  EXPECT_EQ(distinct.size(), size_t(kChainColors));
  EXPECT_EQ(distinct.count(key(glm::vec4(1, 1, 1, 1))), 0u);  // never the usual white background

  // Chains in the order the file names them: A, B, then A again after B (one chain A).
  const std::string text = record("ATOM", 1, " N  ", "ALA", 'A', 1, "N") + record("ATOM", 2, " CA ", "ALA", 'A', 1, "C") +
                           "TER\n" + record("ATOM", 3, " N  ", "GLY", 'B', 1, "N") + "TER\n" +
                           record("HETATM", 4, " O  ", "HOH", 'A', 101, "O") + "END\n";
  const SphereSet s = parse_pdb(text, "chains.pdb");
  ASSERT_EQ(s.size(), 4u);
  ASSERT_EQ(s.chain_names, (std::vector<std::string>{"A", "B"}));
  const std::vector<glm::vec4> c = sphere_colors(s, SphereColorMode::Chain, TransferFunction{});
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0], chain_color(0));
  EXPECT_EQ(c[1], chain_color(0));
  EXPECT_EQ(c[2], chain_color(1));
  EXPECT_EQ(c[3], chain_color(0));
  EXPECT_NE(c[0], c[2]);
}

TEST(MoleculeColors, OneColourPerResidueClass) {
  std::set<std::tuple<float, float, float, float>> distinct;
  for (int i = 0; i < kResidueClasses; ++i) distinct.insert(key(residue_color(ResidueClass(i))));
  EXPECT_EQ(distinct.size(), size_t(kResidueClasses));

  // One residue of each class: hydrophobic, polar, acidic, basic, another
  // amino acid (selenomethionine), nucleic (DNA adenine), water, other (a ligand).
  struct Case {
    const char* res;
    const char* atom;
    const char* element;
    ResidueClass want;
  };
  const Case cases[] = {
      {"LEU", " CA ", "C", ResidueClass::Hydrophobic}, {"SER", " OG ", "O", ResidueClass::Polar},
      {"ASP", " OD1", "O", ResidueClass::Acidic},      {"LYS", " NZ ", "N", ResidueClass::Basic},
      {"MSE", "SE  ", "SE", ResidueClass::OtherAminoAcid}, {" DA", " P  ", "P", ResidueClass::Nucleic},
      {"HOH", " O  ", "O", ResidueClass::Water},       {"HEM", "FE  ", "FE", ResidueClass::Other},
  };
  std::string text;
  int n = 0;
  for (const Case& k : cases) {
    ++n;
    text += record(n <= 4 ? "ATOM" : "HETATM", n, k.atom, k.res, 'A', n, k.element);
  }
  text += "END\n";
  const SphereSet s = parse_pdb(text, "residues.pdb");
  ASSERT_EQ(s.size(), std::size(cases));
  const std::vector<glm::vec4> c = sphere_colors(s, SphereColorMode::Residue, TransferFunction{});
  for (size_t i = 0; i < std::size(cases); ++i) {
    EXPECT_EQ(s.residue_class[i], cases[i].want) << cases[i].res;
    EXPECT_EQ(c[i], residue_color(cases[i].want)) << cases[i].res;
  }
}

TEST(MoleculeColors, DefaultStaysElementAndOtherSetsAreRefused) {
  const SphereSet mol = parse_pdb(record("ATOM", 1, " CA ", "ALA", 'A', 1, "C") + "END\n", "one.pdb");
  EXPECT_EQ(default_color_mode(mol), SphereColorMode::Element);

  SphereSet plain;  // a .sph list: no chains, no residues
  plain.centres = {{0, 0, 0}};
  plain.radii = {1};
  for (SphereColorMode m : {SphereColorMode::Chain, SphereColorMode::Residue}) {
    try {
      sphere_colors(plain, m, TransferFunction{});
      ADD_FAILURE() << to_string(m) << " coloured a set that is not a molecule";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("not a molecule"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(to_string(m)), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace zs
