#!/usr/bin/env bash
# What `zsweep bench scan` and `bench accuracy` take and write, checked before
# any work: sphere and surface inputs are refused (they crashed accuracy, and
# gave all-zero CSVs), every input is checked before the first is measured,
# output paths are checked before the measuring, and two inputs sharing a stem
# give two sets of rows.
set -u
zsweep=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
cd "$tmp" || exit 1

# Tiny inputs of every kind the benchmarks do not measure.
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > tet4.off
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > tri.obj
printf 'ATOM      1  N   ALA A   1       0.000   0.000   0.000  1.00  0.00           N\nATOM      2  CA  ALA A   1       1.458   0.000   0.000  1.00  0.00           C\nEND\n' > two.pdb
printf '# x y z r scalar\n0 0 0 1 0.5\n2 0 0 0.5 1.5\n' > two.sph
echo '{"spheres": {"path": "two.sph"}}' > sph.json
echo '{"surfaces": [{"path": "tet4.off"}]}' > surf.json
"$zsweep" mesh generate blob --tets 300 --seed 3 -o blob.off >/dev/null || fail "generate"
echo '{"mesh": "blob.off"}' > blob.json
echo '{"mesh": "tet4.off"}' > vol_surface.json

# expect_refused WHAT-IN-MESSAGE BENCH ARGS...: exit 1, one stderr line naming
# the file and what it is, nothing measured (no progress lines), no CSV.
expect_refused() {
  local want=$1; shift
  rm -f out.csv
  local csv=(--csv out.csv); case " $* " in *" --csv "*) csv=() ;; esac
  "$zsweep" bench "$@" --sizes 32 "${csv[@]}" >out.txt 2>err.txt; local rc=$?
  [ $rc -eq 1 ] || fail "bench $*: exit $rc (stderr: $(cat err.txt))"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "bench $*: expected one stderr line, got: $(cat err.txt)"
  grep -q -- "^zsweep: error: $want" err.txt || fail "bench $*: message '$(cat err.txt)', wanted '$want'"
  [ ! -e out.csv ] || fail "bench $*: CSV written"
}
for b in scan accuracy; do
  takes="; bench $b measures tet meshes (volume scenes)"
  expect_refused "tet4.off: a surface mesh$takes" $b tet4.off
  expect_refused "tri.obj: a surface mesh$takes" $b tri.obj
  expect_refused "two.pdb: a sphere set$takes" $b two.pdb
  expect_refused "two.sph: a sphere set$takes" $b two.sph
  expect_refused "sph.json: a sphere scene$takes" $b sph.json
  expect_refused "surf.json: a surface scene$takes" $b surf.json
  expect_refused "vol_surface.json: its mesh .*tet4.off is a surface mesh$takes" $b vol_surface.json
  # Every input before the first is measured: the good one first.
  expect_refused "two.pdb: a sphere set$takes" $b blob.off two.pdb
  expect_refused "nope.off: no such file" $b blob.off nope.off
  # Outputs before the work: a CSV in a missing directory, plots in place of a file.
  expect_refused "nodir/x.csv: cannot write" $b blob.off --csv nodir/x.csv
  touch afile
  expect_refused "afile: cannot write plots: not a directory" $b blob.off --plots afile
  expect_refused "afile/sub: cannot create the plots directory: afile is not a directory" $b blob.off --plots afile/sub
done
"$zsweep" bench report /dev/null --plots afile >/dev/null 2>err.txt && fail "bench report wrote plots into a file"
grep -q "afile: cannot write plots: not a directory" err.txt || fail "bench report --plots afile: $(cat err.txt)"

# Two inputs sharing a stem, and one file twice: one set of rows each, named apart.
"$zsweep" bench scan blob.json blob.off blob.off --sizes 32 --strategies bbox --csv s.csv --plots sp >/dev/null 2>&1 \
  || fail "bench scan on blob.json blob.off blob.off"
[ "$(cut -d, -f1 s.csv | tail -n +2 | tr '\n' ' ')" = "blob.json blob.off blob.off-2 " ] \
  || fail "bench scan row names: $(cut -d, -f1 s.csv | tr '\n' ' ')"
for f in blob.json-time.png blob.off-time.png blob.off-2-time.png; do [ -s "sp/$f" ] || fail "missing sp/$f"; done
"$zsweep" bench accuracy blob.json blob.off --sizes 32 --groups integrator --csv a.csv --plots ap >/dev/null 2>&1 \
  || fail "bench accuracy on blob.json blob.off"
python3 - a.csv <<'PY' || fail "bench accuracy rows per input"
import collections, csv, sys
n = collections.Counter(r["scene"] for r in csv.DictReader(open(sys.argv[1])))
assert n == {"blob.json": 5, "blob.off": 5}, n
PY
for f in accuracy-blob.json-32.png accuracy-blob.off-32.png; do [ -s "ap/$f" ] || fail "missing ap/$f"; done
# A lone input keeps its stem, as before.
"$zsweep" bench scan blob.off --sizes 32 --strategies bbox --csv one.csv >/dev/null 2>&1 || fail "bench scan blob.off"
[ "$(tail -1 one.csv | cut -d, -f1)" = "blob" ] || fail "lone input row name: $(tail -1 one.csv | cut -d, -f1)"
echo "bench inputs: ok"
