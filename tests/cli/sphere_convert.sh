#!/usr/bin/env bash
# `zsweep spheres convert` and `zsweep spheres generate` (small counts):
# .sph -> .sphb -> .sph keeps every number, generation is deterministic by
# seed, bad inputs and unwritable outputs fail with one line and leave no file.
set -u
zsweep=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0
ok() { if "$@"; then ((pass++)); else echo "FAIL: $*"; ((fail++)); fi; }
# A command that must fail with exactly this one-line error and write nothing.
fails_with() {  # expected-stderr, command...
  local want=$1; shift
  "$@" >"$tmp/out" 2>"$tmp/err"; local rc=$?
  if [[ $rc -ne 0 && "$(cat "$tmp/err")" == "$want" && ! -s "$tmp/out" ]]; then ((pass++)); else
    echo "FAIL: $* -> exit $rc, stderr '$(cat "$tmp/err")', want '$want'"; ((fail++)); fi
}

# Text -> binary -> text: same numbers (the invalid sphere is dropped).
"$zsweep" spheres convert "$src/tests/data/spheres/small.sph" "$tmp/a.sphb" >/dev/null || { echo "FAIL convert"; ((fail++)); }
ok test "$(stat -c %s "$tmp/a.sphb")" -eq $((24 + 3 * 5 * 4))
"$zsweep" spheres convert "$tmp/a.sphb" "$tmp/b.sph" >/dev/null
ok test "$(grep -v '^#' "$tmp/b.sph")" == $'0 0 0 1 0.5\n2 0 0 0.5 1.5\n1 1 1 0.25 nan'
# A PDB converts (scalar: its B-factor).
"$zsweep" spheres convert "$src/tests/data/spheres/small.pdb" "$tmp/p.sphb" >"$tmp/out"
ok grep -qx "wrote $tmp/p.sphb: 4 spheres (0 invalid skipped)" "$tmp/out"

# Generators: counts, determinism, seeds, .sph and .sphb agree.
for set in c1 c3 c4; do
  "$zsweep" spheres generate $set --count 1000 --seed 7 -o "$tmp/$set.sphb" >/dev/null
  "$zsweep" spheres generate $set --count 1000 --seed 7 -o "$tmp/$set-again.sphb" >/dev/null
  "$zsweep" spheres generate $set --count 1000 --seed 8 -o "$tmp/$set-other.sphb" >/dev/null
  "$zsweep" spheres generate $set --count 1000 --seed 7 -o "$tmp/$set.sph" >/dev/null
  ok test "$(stat -c %s "$tmp/$set.sphb")" -eq $((24 + 1000 * 32))
  ok cmp -s "$tmp/$set.sphb" "$tmp/$set-again.sphb"
  ok test -n "$(cmp "$tmp/$set.sphb" "$tmp/$set-other.sphb")"
  "$zsweep" spheres convert "$tmp/$set.sph" "$tmp/$set-text.sphb" >/dev/null
  ok cmp -s "$tmp/$set.sphb" "$tmp/$set-text.sphb"
  ok test "$(grep -vc '^#' "$tmp/$set.sph")" -eq 1000
done
"$zsweep" mesh info "$tmp/c4.sphb" >"$tmp/out"
ok grep -qx "spheres:                    1000" "$tmp/out"
ok grep -qx "colours:                    rgba" "$tmp/out"
if [[ -f /usr/share/doc/libcgal-dev/data.tar.gz ]]; then
  "$zsweep" spheres generate c2 --count 500 -o "$tmp/c2.sphb" >"$tmp/out"
  ok test "$(stat -c %s "$tmp/c2.sphb")" -eq $((24 + 500 * 32))
else
  echo "note: no libcgal-demo data, c2 not tried"
fi

# Failures: one line, exit 1, no file left behind (not even a temporary).
fails_with "zsweep: error: $tmp/none/x.sphb: cannot write: No such file or directory" \
  "$zsweep" spheres generate c4 --count 1000 -o "$tmp/none/x.sphb"
fails_with "zsweep: error: $tmp/x.txt: unknown sphere output format (expected .sph or .sphb)" \
  "$zsweep" spheres convert "$src/tests/data/spheres/small.sph" "$tmp/x.txt"
fails_with "zsweep: error: $src/tests/data/spheres/bad/rgba_range.sph:2: G '1.5' is not in [0, 1]" \
  "$zsweep" spheres convert "$src/tests/data/spheres/bad/rgba_range.sph" "$tmp/y.sphb"
fails_with "zsweep: error: unknown sphere test set 'c5' (expected c1, c2, c3 or c4)" \
  "$zsweep" spheres generate c5 -o "$tmp/z.sphb"
mkdir "$tmp/ro"; chmod 555 "$tmp/ro"
if [[ ! -w "$tmp/ro" ]]; then  # root can write anyway
  fails_with "zsweep: error: $tmp/ro/z.sph: cannot write: Permission denied" "$zsweep" spheres generate c1 --count 10 -o "$tmp/ro/z.sph"
fi
ok test -z "$(ls -A "$tmp/ro")"
ok test ! -e "$tmp/x.txt" -a ! -e "$tmp/y.sphb" -a ! -e "$tmp/z.sphb"
echo "sphere convert/generate: $pass passed, $fail failed"
[[ $fail -eq 0 && $pass -ge 26 ]]
