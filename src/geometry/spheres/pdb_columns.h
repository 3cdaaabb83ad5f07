// The PDB text as gemmi is given it (molecule_reader.h): every ATOM/HETATM
// record checked by the format's fixed columns first, so that an error names
// the file, the line and the columns (coordinates 31-38, 39-46, 47-54), and
// columns 77-80 cleared where they hold no element and charge. Many files
// written before 2007, and many programs since, put a segment id and a line
// number in columns 73-80 (1hpv: "1HPV 186"): columns 77-78 then read " 1"
// and 79-80 "86", which gemmi would take for a charge ("Wrong format for
// charge"). Cleared element columns make the element come from the atom
// name, as every molecular program reads such files.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace zs {

struct PdbText {
  std::string text;                 // the records, columns 77-80 cleared where junk
  size_t atoms = 0;                 // ATOM and HETATM records (every model)
  size_t element_cleared = 0;       // records whose columns 77-78 held no element symbol
  size_t charge_cleared = 0;        // records whose columns 79-80 held no charge
  size_t element_blank = 0;         // records without an element (then from the atom name), cleared ones too
  size_t line_without_b = 0;        // first record without a B-factor (columns 61-66), 0: none
  size_t line_of_first_atom = 0;
};

// Throws FileError naming `name` and the line for a record too short for its
// coordinates and a coordinate that is not a finite number.
PdbText prepare_pdb_text(std::string_view text, const std::string& name);

}  // namespace zs
