#!/usr/bin/env bash
# `zsweep reference` on sphere files: writes an image of the requested size
# with the spheres on a transparent background (one thread and all).
set -u
zsweep=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
for f in small.sph small.pdb; do
  for t in 1 2; do
    out=$("$zsweep" reference "$src/tests/data/spheres/$f" -o "$tmp/$f.$t.exr" --width 96 --height 64 --threads $t) \
      || { echo "FAIL $f: exit $?"; fail=1; continue; }
    [[ -s "$tmp/$f.$t.exr" ]] || { echo "FAIL $f: no image"; fail=1; }
    grep -q "96x64" <<<"$out" || { echo "FAIL $f: $out"; fail=1; }
    hits=$(sed -n 's/.* \([0-9]*\) pixels hit.*/\1/p' <<<"$out")
    [[ -n "$hits" && "$hits" -gt 500 && "$hits" -lt 6144 ]] || { echo "FAIL $f: $hits pixels hit"; fail=1; }
  done
  # Same pixels whatever the thread count (the files differ in their time stamps).
  "$zsweep" compare "$tmp/$f.1.exr" "$tmp/$f.2.exr" --json >"$tmp/cmp" 2>&1
  grep -q '"max_abs": 0.0,' "$tmp/cmp" || { echo "FAIL $f: 1 and 2 threads differ: $(cat "$tmp/cmp")"; fail=1; }
done
exit $fail
