#!/usr/bin/env bash
# `zsweep mesh info` on triangle surfaces (OFF with the keyword, .obj, .ply,
# .stl) reports the surface: triangles, points, closed solids (and how many
# are wound inward), bounds, as text and JSON. `mesh convert` (and any other
# command that reads tet meshes) refuses a surface in one line saying so,
# leaving no output.
set -u
zsweep=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
py=/usr/bin/python3
d=$src/tests/data/surfaces

# The cube wound inward: every face's corners reversed.
awk 'NF == 5 && $1 == 4 { print 4, $5, $4, $3, $2; next } { print }' "$d/cube.off" >"$tmp/inward.off"
printf 'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' >"$tmp/tri.stl"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n2 0 0\n0 3 0\n3 0 1 2\n' >"$tmp/tri.ply"

info() {  # file expected-lines...
  local f=$1; shift
  "$zsweep" mesh info "$f" >"$tmp/out" 2>"$tmp/err" || { echo "FAIL info $f: $(cat "$tmp/err")"; fail=1; return; }
  for want in "$@"; do
    grep -q -- "$want" "$tmp/out" || { echo "FAIL info $f: no '$want' in: $(cat "$tmp/out")"; fail=1; }
  done
}
info "$d/cube.off" "^kind: *triangle surface" "^triangles: *12$" "^points: *8$" "^closed solids: *1 (0 wound inward" \
  "^bounds: *\[0, 0, 0\] - \[1, 1, 1\]"
info "$tmp/inward.off" "^closed solids: *1 (1 wound inward: turned outward when rendered)"
info "$d/pyramid.obj" "^triangles: *6$" "^polygons in file: *5 (1 with more than three corners"
info "$tmp/tri.stl" "^triangles: *1$" "^closed solids: *0" "^two-sided triangles: *1 "
info "$tmp/tri.ply" "^triangles: *1$" "^bounds: *\[0, 0, 0\] - \[2, 3, 0\]"

"$zsweep" mesh info "$tmp/inward.off" --json >"$tmp/j" 2>"$tmp/err" || { echo "FAIL json: $(cat "$tmp/err")"; fail=1; }
$py - "$tmp/j" <<'PY' || fail=1
import json, sys
j = json.load(open(sys.argv[1]))
ok = j["kind"] == "surface" and j["triangles"] == 12 and j["points"] == 8 and j["closed_solids"] == 1 \
     and j["closed_solids_wound_inward"] == 1 and j["polygons_split"] == 6 and j["bounds"] == [[0, 0, 0], [1, 1, 1]]
if not ok: print("FAIL json", j)
sys.exit(0 if ok else 1)
PY

# Commands that read tet meshes: one line naming the file and saying what it is.
for f in "$d/cube.off" "$d/pyramid.obj" "$tmp/tri.stl" "$tmp/tri.ply"; do
  out=$tmp/conv.vtu
  if "$zsweep" mesh convert "$f" "$out" >/dev/null 2>"$tmp/err"; then echo "FAIL convert $f: accepted"; fail=1; fi
  [[ -e "$out" ]] && { echo "FAIL convert $f: left $out"; fail=1; }
  [[ $(wc -l <"$tmp/err") -eq 1 ]] || { echo "FAIL convert $f: not one line: $(cat "$tmp/err")"; fail=1; }
  grep -q "^zsweep: error: $f: a triangle surface, not a tetrahedral mesh (this command takes tet meshes" "$tmp/err" \
    || { echo "FAIL convert $f: $(cat "$tmp/err")"; fail=1; }
done
exit $fail
