// Molecules through gemmi (molecule_reader.h). gemmi is header-only here
// (Debian's gemmi-dev 0.5.7): this file alone includes it, so only it pays
// for its templates. PDB text is checked and cleaned by its fixed columns
// first (pdb_columns.h); mmCIF goes to gemmi as it is.
#include "geometry/spheres/molecule_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>

#include <gemmi/gz.hpp>
#include <gemmi/cif.hpp>
#include <gemmi/mmcif.hpp>
#include <gemmi/pdb.hpp>

#include "base/util/file_error.h"
#include "base/util/text_lines.h"
#include "geometry/spheres/elements.h"
#include "geometry/spheres/pdb_columns.h"
#include "geometry/spheres/vdw_radii.h"

namespace zs {

namespace {

// (C++17 here: see src/geometry/CMakeLists.txt.)
bool starts_with(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// The extension that says the format, below a ".gz".
std::string format_extension(const std::string& path) {
  std::string p = lower(path);
  if (p.size() > 3 && ends_with(p, ".gz")) p.resize(p.size() - 3);
  return std::filesystem::path(p).extension().string();
}

// gemmi's "Problem in line N: what" as FileError(name, N, what); other
// messages whole.
[[noreturn]] void rethrow_gemmi(const std::string& name, const std::string& msg) {
  const std::string head = "Problem in line ";
  if (starts_with(msg, head)) {
    size_t end = head.size(), line = 0;
    while (end < msg.size() && std::isdigit(static_cast<unsigned char>(msg[end]))) line = line * 10 + (msg[end++] - '0');
    if (line && msg.compare(end, 2, ": ") == 0) throw FileError(name, line, msg.substr(end + 2));
  }
  std::string m = msg;
  if (starts_with(m, name + ":")) m = m.substr(name.size() + 1);  // PEGTL: "name:line:col: ..."
  for (const char* before : {" of ", ": "})  // gzip: "... size of NAME", "fseek() failed (empty file?): NAME: ..."
    for (size_t at; (at = m.find(before + name)) != std::string::npos;) m.erase(at, std::strlen(before) + name.size());
  size_t p = 0;  // "line:col: what" as "name:line:col: what"
  while (p < m.size() && std::isdigit(static_cast<unsigned char>(m[p]))) ++p;
  if (p && m[p] == ':') {
    const size_t nl = m.find('\n');
    throw FileError(name + ":" + (nl == std::string::npos ? m : m.substr(0, nl)));
  }
  while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
  const size_t nl = m.find('\n');
  throw FileError(name, nl == std::string::npos ? m : m.substr(0, nl));
}

// gemmi reads residue numbers, ids and charges with string_to_int, which
// overflows int (undefined) on 10+ digits (found by scripts/fuzz, cif). Such
// a value in a tag gemmi may read as an integer is an error here first.
void check_integers(const gemmi::cif::Block& block, const std::string& name) {
  const auto integer_tag = [](std::string t) {
    t = lower(t);
    return ends_with(t, "id") || ends_with(t, "num") || ends_with(t, "number") || ends_with(t, "charge") ||
           ends_with(t, "z_pdb");
  };
  const auto check = [&](const std::string& tag, const std::string& v, int at) {
    // string_to_int reads the leading digits and stops at anything else
    // ("2555555555#5" overflows too), so the leading run decides.
    size_t i = (!v.empty() && (v[0] == '-' || v[0] == '+')) ? 1 : 0;
    while (i + 1 < v.size() && v[i] == '0') ++i;
    size_t end = i;
    while (end < v.size() && v[end] >= '0' && v[end] <= '9') ++end;
    if (end - i < 10) return;
    if (!integer_tag(tag)) return;
    const std::string what = tag + " " + v.substr(0, 24) + (v.size() > 24 ? "..." : "") + ": integer out of range";
    if (at > 0) throw FileError(name, size_t(at), what);
    throw FileError(name, what);
  };
  for (const gemmi::cif::Item& item : block.items) {
    if (item.type == gemmi::cif::ItemType::Pair) {
      check(item.pair[0], item.pair[1], item.line_number);
    } else if (item.type == gemmi::cif::ItemType::Loop && !item.loop.tags.empty()) {
      const size_t w = item.loop.tags.size();
      for (size_t k = 0; k < item.loop.values.size(); ++k) check(item.loop.tags[k % w], item.loop.values[k], -1);
    }
  }
}

// gemmi's residue look-ups (is_water, find_tabulated_residue) shift the
// name's chars as int: a byte above 127 is a negative char, undefined
// behaviour (found by scripts/fuzz, pdb). No residue gemmi knows has one.
bool plain_name(const std::string& s) {
  return std::all_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 128; });
}
bool is_water(const gemmi::Residue& r) { return plain_name(r.name) && r.is_water(); }

// Residue classes of the twenty standard amino acids by side chain
// (docs/spheres.md, "Colours"); other residues by gemmi's residue table.
ResidueClass residue_class(const gemmi::Residue& r) {
  static const std::map<std::string, ResidueClass> kAmino = {
      {"ALA", ResidueClass::Hydrophobic}, {"VAL", ResidueClass::Hydrophobic}, {"LEU", ResidueClass::Hydrophobic},
      {"ILE", ResidueClass::Hydrophobic}, {"MET", ResidueClass::Hydrophobic}, {"PHE", ResidueClass::Hydrophobic},
      {"TRP", ResidueClass::Hydrophobic}, {"PRO", ResidueClass::Hydrophobic}, {"GLY", ResidueClass::Hydrophobic},
      {"SER", ResidueClass::Polar},       {"THR", ResidueClass::Polar},       {"ASN", ResidueClass::Polar},
      {"GLN", ResidueClass::Polar},       {"CYS", ResidueClass::Polar},       {"TYR", ResidueClass::Polar},
      {"ASP", ResidueClass::Acidic},      {"GLU", ResidueClass::Acidic},      {"LYS", ResidueClass::Basic},
      {"ARG", ResidueClass::Basic},       {"HIS", ResidueClass::Basic}};
  if (!plain_name(r.name)) return ResidueClass::Other;
  if (auto it = kAmino.find(r.name); it != kAmino.end()) return it->second;
  if (r.is_water()) return ResidueClass::Water;
  const gemmi::ResidueInfo info = gemmi::find_tabulated_residue(r.name);
  if (info.is_amino_acid()) return ResidueClass::OtherAminoAcid;
  if (info.is_nucleic_acid()) return ResidueClass::Nucleic;
  return ResidueClass::Other;
}

// gemmi keeps B-factors as float; the double a user wrote ("7.69") is the
// shortest decimal that gives that float back, read as a double, so B-factor
// colours are the ones the text says (and PDB and mmCIF of one structure agree).
double written_value(float f) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, f);
  double d = f;
  std::from_chars(buf, r.ptr, d);
  return d;
}

std::string count_note(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

const gemmi::Model& choose_model(const gemmi::Structure& st, const MoleculeOptions& opt, const std::string& name) {
  if (st.models.empty())  // mmCIF: gemmi reads _atom_site only with all these columns
    throw FileError(name, "no atoms (an _atom_site loop with id, type_symbol, label_alt_id, label_asym_id, "
                          "auth_seq_id, Cartn_x, Cartn_y, Cartn_z, occupancy and B_iso_or_equiv)");
  if (opt.model.empty()) return st.models.front();
  for (const gemmi::Model& m : st.models)
    if (m.name == opt.model) return m;
  std::string have;
  for (size_t i = 0; i < st.models.size() && i < 8; ++i) have += (i ? ", " : "") + st.models[i].name;
  if (st.models.size() > 8) have += ", ...";
  throw FileError(name, "no model " + opt.model + " (the file has " + count_note(st.models.size(), "model", "models") +
                            ": " + have + ")");
}

// The chosen model's atoms as spheres, with the counts mesh info prints.
SphereSet spheres_of(const gemmi::Structure& st, const MoleculeOptions& opt, const std::string& name) {
  const gemmi::Model& model = choose_model(st, opt, name);
  SphereSet s;
  MoleculeCounts& c = s.molecule;
  c.models = st.models.size();
  c.model = model.name;
  std::map<std::string, size_t> by_element;
  char first_alt = 0;
  for (const gemmi::Chain& ch : model.chains) {
    uint16_t chain_id = 0;
    bool chain_used = false;
    for (const gemmi::Residue& res : ch.residues) {
      const ResidueClass rc = residue_class(res);
      bool residue_used = false;
      for (const gemmi::Atom& a : res.atoms) {
        if (!std::isfinite(a.pos.x) || !std::isfinite(a.pos.y) || !std::isfinite(a.pos.z))  // mmCIF: "abc" reads as NaN
          throw FileError(name, "atom " + std::to_string(a.serial) + " (" + a.name + " of " + res.name + " " +
                                    res.seqid.str() + ", chain " + ch.name + "): coordinate not a finite number");
        if (a.altloc) {  // the first alternate location the file names, as before gemmi
          if (!first_alt) first_alt = a.altloc;
          if (a.altloc != first_alt) {
            ++s.skipped;
            continue;
          }
        }
        if (is_water(res) && !opt.waters) {
          ++c.waters_left_out;
          continue;
        }
        if (a.is_hydrogen() && !opt.hydrogens) {
          ++c.hydrogens_left_out;
          continue;
        }
        if (!chain_used) {
          chain_used = true;
          auto it = std::find(s.chain_names.begin(), s.chain_names.end(), ch.name);
          chain_id = uint16_t(std::min<size_t>(it - s.chain_names.begin(), 65535));
          if (it == s.chain_names.end()) s.chain_names.push_back(ch.name);
        }
        residue_used = true;
        const std::string symbol = a.element == gemmi::El::X ? "" : a.element.name();
        double radius = kDefaultVdwRadius;
        if (!vdw_radius(symbol, radius)) ++c.unknown_elements;
        s.centres.push_back({a.pos.x, a.pos.y, a.pos.z});
        s.radii.push_back(radius);
        s.scalars.push_back(written_value(a.b_iso));
        s.element.push_back(static_cast<uint8_t>(atomic_number(symbol)));
        s.chain.push_back(chain_id);
        s.residue_class.push_back(rc);
        ++by_element[symbol.empty() ? "?" : symbol];
        if (is_water(res)) ++c.waters;
        if (a.is_hydrogen()) ++c.hydrogens;
      }
      if (residue_used) ++c.residues;
    }
  }
  c.atoms = s.size();
  c.chains = s.chain_names.size();
  c.altlocs_left_out = s.skipped;
  c.elements.assign(by_element.begin(), by_element.end());
  std::stable_sort(c.elements.begin(), c.elements.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  if (s.skipped)
    s.notes.push_back(std::to_string(s.skipped) + " alternate locations skipped (kept '" + std::string(1, first_alt) +
                      "')");
  return s;
}

}  // namespace

bool is_molecule_file(const std::string& path) {
  const std::string e = format_extension(path);
  return e == ".pdb" || e == ".ent" || e == ".cif" || e == ".mmcif";
}

SphereSet parse_molecule(std::string_view text, const std::string& name, MoleculeFormat format,
                         const MoleculeOptions& opt) {
  gemmi::Structure st;
  PdbText pdb;
  if (format == MoleculeFormat::Pdb) {
    pdb = prepare_pdb_text(text, name);
    if (!pdb.atoms) throw FileError(name, "no ATOM or HETATM records in model 1");
    try {
      st = gemmi::read_pdb_string(pdb.text, name);
    } catch (const std::exception& e) {
      rethrow_gemmi(name, e.what());
    }
  } else {
    try {  // std::exception: gemmi's checks throw runtime_error, its container accesses out_of_range
      const gemmi::cif::Document doc = gemmi::cif::read_memory(text.data(), text.size(), name.c_str());
      if (doc.blocks.empty()) throw FileError(name, "no data block (data_...)");
      check_integers(doc.blocks[0], name);
      st = gemmi::make_structure(doc);
    } catch (const FileError&) {
      throw;
    } catch (const std::exception& e) {
      rethrow_gemmi(name, e.what());
    }
  }
  SphereSet s = spheres_of(st, opt, name);
  if (s.centres.empty()) {
    if (opt.model.empty() && !s.molecule.waters_left_out && !s.molecule.hydrogens_left_out)
      throw FileError(name, format == MoleculeFormat::Pdb ? "no ATOM or HETATM records in model 1"
                                                          : "no atoms in the first model");
    throw FileError(name, "no atoms left in model " + s.molecule.model +
                              (s.molecule.waters_left_out || s.molecule.hydrogens_left_out
                                   ? " once waters and hydrogens are left out" : ""));
  }
  // Notes, in the order the tests and `mesh info` read them: B-factor,
  // radius, alternate locations (spheres_of), then what gemmi inferred.
  std::vector<std::string> notes;
  if (format == MoleculeFormat::Pdb && pdb.line_without_b) {
    s.scalars.clear();
    notes.push_back("no B-factor (columns 61-66) on line " + std::to_string(pdb.line_without_b) + ": no scalar");
  } else {
    s.scalar_name = "b_factor";
    for (double v : s.scalars)
      if (!std::isfinite(v)) ++s.degenerate;
  }
  if (s.molecule.unknown_elements) {
    char r[32];
    std::snprintf(r, sizeof r, "%g", kDefaultVdwRadius);
    notes.push_back(std::to_string(s.molecule.unknown_elements) + " atoms of an element without a tabulated radius: " +
                    r + " Å");
  }
  notes.insert(notes.end(), s.notes.begin(), s.notes.end());
  if (format == MoleculeFormat::Pdb) {
    s.molecule.element_columns_cleared = pdb.element_cleared;
    s.molecule.charge_columns_cleared = pdb.charge_cleared;
    s.molecule.elements_inferred = pdb.element_blank;
    if (pdb.element_cleared || pdb.charge_cleared)
      notes.push_back(count_note(std::max(pdb.element_cleared, pdb.charge_cleared), "record", "records") +
                      " with no element and charge in columns 77-80 (they held other text, e.g. a segment id and "
                      "line number): elements from the atom names");
  }
  if (s.molecule.waters_left_out) notes.push_back(count_note(s.molecule.waters_left_out, "water atom", "water atoms") + " left out");
  if (s.molecule.hydrogens_left_out) notes.push_back(count_note(s.molecule.hydrogens_left_out, "hydrogen", "hydrogens") + " left out");
  if (s.molecule.models > 1)
    notes.push_back("model " + s.molecule.model + " of " + std::to_string(s.molecule.models));
  s.notes = std::move(notes);
  return s;
}

SphereSet read_molecule(const std::string& path, const MoleculeOptions& opt) {
  const std::string e = format_extension(path);
  const MoleculeFormat format = (e == ".cif" || e == ".mmcif") ? MoleculeFormat::Mmcif : MoleculeFormat::Pdb;
  if (ends_with(lower(path), ".gz")) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw FileError(path, "no such file");
    gemmi::CharArray mem;
    try {
      mem = gemmi::MaybeGzipped(path).uncompress_into_buffer();
    } catch (const std::exception& err) {
      rethrow_gemmi(path, err.what());
    }
    return parse_molecule(std::string_view(mem.data(), mem.size()), path, format, opt);
  }
  return parse_molecule(read_text_file(path), path, format, opt);
}

}  // namespace zs
