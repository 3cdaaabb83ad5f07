// Chemical elements by symbol, for the atomic numbers PDB atoms carry.
#pragma once

#include <string_view>

namespace zs {

// The atomic number (1-118) of an element symbol as PDB writes it
// (case-insensitive, surrounding spaces ignored: " C", "FE", "Cl"); hydrogen's
// isotopes D and T count as H. 0 for a blank or unknown symbol.
unsigned atomic_number(std::string_view symbol);

}  // namespace zs
