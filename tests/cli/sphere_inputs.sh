#!/usr/bin/env bash
# `zsweep mesh info` on sphere files (.pdb, .sph, .sphb): the report for two small
# good files, and for every file in tests/data/spheres/bad exactly the
# one-line error listed in its EXPECTED, exit code 1, nothing on stdout.
set -u
zsweep=$1; src=$2
cd "$src/tests/data/spheres" || exit 1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0
expect_line() {  # file, the exact report line
  if grep -qxF -- "$2" "$tmp/out"; then ((pass++)); else echo "FAIL $1: no line '$2' in:"; cat "$tmp/out"; ((fail++)); fi
}
"$zsweep" mesh info small.pdb >"$tmp/out" 2>"$tmp/err" || { echo "FAIL small.pdb: $(cat "$tmp/err")"; ((fail++)); }
expect_line small.pdb "spheres:                    4"
expect_line small.pdb "skipped records:            1"
expect_line small.pdb "centre bounds:              [-1.5, 0, 0] - [2, 4.25, 3]"
expect_line small.pdb "radius range:               [1.39, 1.7]"
expect_line small.pdb "scalar:                     b_factor, range [5, 20]"
"$zsweep" mesh info small.sph --json >"$tmp/out" 2>"$tmp/err" || { echo "FAIL small.sph: $(cat "$tmp/err")"; ((fail++)); }
expect_line small.sph '  "spheres": 3'
expect_line small.sph '  "degenerate": 1,'
expect_line small.sph '  "invalid": 1,'
"$zsweep" mesh info invalid.sph >"$tmp/out" 2>"$tmp/err" || { echo "FAIL invalid.sph: $(cat "$tmp/err")"; ((fail++)); }
expect_line invalid.sph "spheres:                    2"
expect_line invalid.sph "invalid (skipped):          3 (zero, negative or non-finite radius, non-finite centre)"

listed=()
while IFS=$'\t' read -r file expected; do
  [[ -z "$file" || "$file" == \#* ]] && continue
  listed+=("$file")
  "$zsweep" mesh info "bad/$file" >"$tmp/out" 2>"$tmp/err"; rc=$?
  want="zsweep: error: bad/$expected"
  if [[ $rc -ne 1 ]]; then echo "FAIL $file: exit $rc, want 1"; ((fail++)); continue; fi
  if [[ "$(cat "$tmp/err")" != "$want" ]]; then
    echo "FAIL $file:"; echo "  got:  $(cat "$tmp/err")"; echo "  want: $want"; ((fail++)); continue
  fi
  if [[ -s "$tmp/out" ]]; then echo "FAIL $file: printed to stdout"; ((fail++)); continue; fi
  ((pass++))
done < bad/EXPECTED
for f in bad/*; do
  f=${f#bad/}
  [[ "$f" == EXPECTED ]] && continue
  if [[ ! " ${listed[*]} " == *" $f "* ]]; then echo "FAIL $f: not listed in EXPECTED"; ((fail++)); fi
done
"$zsweep" mesh info missing.pdb >/dev/null 2>"$tmp/err"
if [[ "$(cat "$tmp/err")" == "zsweep: error: missing.pdb: no such file" ]]; then ((pass++)); else echo "FAIL missing.pdb: $(cat "$tmp/err")"; ((fail++)); fi
echo "sphere inputs: $pass passed, $fail failed"
[[ $fail -eq 0 && $pass -ge 24 ]]
