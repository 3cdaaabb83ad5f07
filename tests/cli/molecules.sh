#!/usr/bin/env bash
# Molecules through gemmi (issue 40): one hand-made structure as .pdb,
# .pdb.gz, and as mmCIF written by gemmi (.cif, .cif.gz) renders the same
# image (max abs 0, depth too); 1tii (pymol-data, element columns) converts to
# the very .sph the hand-written reader before gemmi gave; 1hpv (no element
# columns) reads as PyMOL does; malformed molecule files fail in one line
# naming the file and leave no output. Parts skip, saying so, without gemmi's
# program or pymol-data.
set -u
zsweep=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/same_image.sh"  # same A B WHAT: pixel- and depth-identical
atom() {  # record name residue chain seq x y z b element
  printf '%-6s%5d %-4s %3s %s%4d    %8.3f%8.3f%8.3f%6.2f%6.2f          %2s\n' "$1" $((++serial)) "$2" "$3" "$4" "$5" \
    "$6" "$7" "$8" 1.0 "$9" "${10}"
}
serial=0
{
  echo "HEADER    TEST STRUCTURE"
  atom ATOM " N  " ALA A 1 1.5 -2.25 3.0 10.5 N
  atom ATOM " CA " ALA A 1 2.5 -2.0 3.5 11.25 ""
  atom ATOM "1HB " ALA A 1 3.0 -1.0 4.0 12.0 ""
  atom ATOM " SD " MET A 2 4.0 0.5 2.0 13.5 ""
  atom ATOM "HG21" THR A 3 5.0 1.0 1.0 14.0 ""
  atom HETATM "SE  " MSE A 4 6.0 1.5 0.5 15.75 SE
  echo "TER"
  atom HETATM "CA  " " CA" B 101 -3.0 2.0 1.0 20.0 ""
  atom HETATM "FE  " HEM B 102 -4.0 3.0 2.0 21.5 ""
  atom HETATM "CL  " " CL" B 104 -6.0 5.0 4.0 23.25 CL
  atom HETATM "ZN  " " ZN" B 105 -7.0 6.0 5.0 24.0 ZN
  atom HETATM " O  " HOH W 201 8.0 -6.0 7.5 30.0 O
  echo "END"
} >"$tmp/m.pdb"

render() {  # input output
  "$zsweep" render "$1" -o "$2" --width 96 --height 72 >/dev/null 2>"$tmp/err" \
    || { echo "FAIL render $(basename "$1"): $(cat "$tmp/err")"; fail=1; }
}
render "$tmp/m.pdb" "$tmp/m.pdb.exr"
gzip -k "$tmp/m.pdb"
render "$tmp/m.pdb.gz" "$tmp/m.pdb.gz.exr"
same "$tmp/m.pdb.exr" "$tmp/m.pdb.gz.exr" "m.pdb.gz vs m.pdb"
if command -v gemmi >/dev/null; then
  gemmi convert "$tmp/m.pdb" "$tmp/m.cif" || { echo "FAIL gemmi convert"; fail=1; }
  gzip -k "$tmp/m.cif"
  for f in m.cif m.cif.gz; do
    render "$tmp/$f" "$tmp/$f.exr"
    same "$tmp/m.pdb.exr" "$tmp/$f.exr" "$f vs m.pdb"
  done
  "$zsweep" mesh info "$tmp/m.pdb" | grep -v '^file:' >"$tmp/info.pdb"
  "$zsweep" mesh info "$tmp/m.cif" | grep -v '^file:' >"$tmp/info.cif"
  # The same spheres, bounds, radii and B-factors (notes may differ: PDB
  # columns are a PDB matter).
  for key in spheres: "centre bounds:" "radius range:" scalar:; do
    [[ "$(grep "^$key" "$tmp/info.pdb")" == "$(grep "^$key" "$tmp/info.cif")" && -n "$(grep "^$key" "$tmp/info.pdb")" ]] \
      || { echo "FAIL mesh info $key: .pdb and .cif differ"; diff "$tmp/info.pdb" "$tmp/info.cif"; fail=1; }
  done
else
  echo "skip: no gemmi program (apt-get install gemmi): .cif not compared"
fi

# Malformed and truncated molecule files: exit 1, one line naming the file, no output.
printf 'data_x\n_cell.length_a 10\n_cell.length_b '"'"'ten\n' >"$tmp/bad.cif"
printf 'data_x\nloop_\n_atom_site.id\n_atom_site.Cartn_x\n1\n' >"$tmp/loop.cif"
printf 'data_x\n_cell.length_a 10\n' >"$tmp/no_atoms.cif"
head -c 40 "$tmp/m.pdb.gz" >"$tmp/cut.pdb.gz"
{ printf 'ANISOU    1  N   GLY A   1     1000   2000   3000      0      0      0       N\n'; cat "$tmp/m.pdb"; } \
  >"$tmp/anisou.pdb"
for f in bad.cif loop.cif no_atoms.cif cut.pdb.gz anisou.pdb; do
  for cmd in render info; do
    rm -f "$tmp/out.png"
    if [[ $cmd == render ]]; then
      "$zsweep" render "$tmp/$f" -o "$tmp/out.png" >"$tmp/out" 2>"$tmp/err"; rc=$?
    else
      "$zsweep" mesh info "$tmp/$f" >"$tmp/out" 2>"$tmp/err"; rc=$?
    fi
    if [[ $rc -ne 1 ]]; then echo "FAIL $cmd $f: exit $rc, want 1"; fail=1; continue; fi
    if [[ $(wc -l <"$tmp/err") -ne 1 ]] || ! grep -q "^zsweep: error: $tmp/$f:" "$tmp/err"; then
      echo "FAIL $cmd $f: want one line 'zsweep: error: $tmp/$f: ...', got:"; cat "$tmp/err"; fail=1
    fi
    [[ -e "$tmp/out.png" ]] && { echo "FAIL $cmd $f: wrote an image"; fail=1; }
    [[ -s "$tmp/out" ]] && { echo "FAIL $cmd $f: printed to stdout"; fail=1; }
  done
done
"$zsweep" mesh info "$tmp/bad.cif" 2>&1 | grep -q "bad.cif:3:" || { echo "FAIL bad.cif: no line number"; fail=1; }
"$zsweep" mesh info "$tmp/anisou.pdb" 2>&1 | grep -q "anisou.pdb:1: ANISOU" || { echo "FAIL anisou.pdb: no line number"; fail=1; }

# Real files from Debian's pymol-data.
hpv=/usr/share/pymol/data/tut/1hpv.pdb
if [[ -f $hpv ]]; then
  "$zsweep" mesh info "$hpv" >"$tmp/out" 2>"$tmp/err" || { echo "FAIL mesh info 1hpv: $(cat "$tmp/err")"; fail=1; }
  grep -qxF "spheres:                    1631" "$tmp/out" || { echo "FAIL 1hpv spheres:"; cat "$tmp/out"; fail=1; }
  grep -qxF "radius range:               [1.52, 1.8]" "$tmp/out" || { echo "FAIL 1hpv radii:"; cat "$tmp/out"; fail=1; }
else
  echo "skip: $hpv not found (apt-get install pymol-data)"
fi
tii=/usr/share/pymol/data/demo/1tii.pdb
if [[ -f $tii ]]; then
  # sha256 of `zsweep spheres convert 1tii.pdb 1tii.sph` by the binary before
  # gemmi (hand-written reader): every centre, radius and B-factor unchanged.
  want=1f8d0670365106b177b3521a37bba481f7526b1a41db40dc8300d0818082fd4e
  "$zsweep" spheres convert "$tii" "$tmp/1tii.sph" >/dev/null 2>"$tmp/err" || { echo "FAIL convert 1tii: $(cat "$tmp/err")"; fail=1; }
  got=$(sha256sum "$tmp/1tii.sph" | cut -d' ' -f1)
  [[ $got == "$want" ]] || { echo "FAIL 1tii.sph differs from the pre-gemmi reader's ($got)"; fail=1; }
else
  echo "skip: $tii not found (apt-get install pymol-data)"
fi
[[ $fail -eq 0 ]] && echo "molecules: ok"
exit $fail
