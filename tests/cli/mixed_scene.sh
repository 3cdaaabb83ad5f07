#!/usr/bin/env bash
# A volume with opaque geometry inside: spheres (flat), a triangle file (also
# cut by the clip plane: clip_geometry), an isosurface of the mesh's scalar
# with its (scaled) boundary (lit, exact shadows: the surfaces' reference),
# and spheres with a triangle file together, in a grid mesh with a clip plane. render and reference
# agree (float images, within 1e-5), --stats counts the rays the geometry
# stopped and carries the geometry's own stats; --mpi gives the same image;
# the geometry changes the image; translucent spheres in a volume are
# refused in one line.
set -u
zsweep=$1
src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
cd "$tmp" || exit 1
"$zsweep" mesh generate grid --cells 6 -o g.zsm >/dev/null || { echo "FAIL: generate"; exit 1; }
printf '# x y z r s\n0.1 0.05 0 0.4 0.9\n-0.5 0.4 0.3 0.2 0.1\n' > s.sph
common='"image": {"width": 64, "height": 48}, "camera": {"projection": "perspective", "eye": [2.5, 1.7, 4],
  "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 40}, "clip": [{"plane": [0, 0, 1, -0.3]}]'
printf '{"mesh": "%s", "spheres": {"path": "%s", "color": "scalar"}, "shading": {"model": "flat"}, %s}' \
  "$tmp/g.zsm" "$tmp/s.sph" "$common" > spheres.json
printf '{"mesh": "%s", "surfaces": [{"path": "%s", "transform": {"scale": 0.6, "translate": [-0.3, -0.3, -0.3]}}],
  "shadows": {"mode": "exact"}, %s}' \
  "$tmp/g.zsm" "$src/tests/data/surfaces/cube.off" "$common" > surfaces.json
printf '{"mesh": "%s", "surfaces": [{"isosurface": [0.35], "color": [0.9, 0.8, 0.2]}, {"boundary": true,
  "transform": {"scale": 1.2}}], "shadows": {"mode": "exact"}, %s}' "$tmp/g.zsm" "$common" > iso.json
printf '{"mesh": "%s", "surfaces": [{"path": "%s", "transform": {"scale": 0.6, "translate": [-0.3, -0.3, 0]}}],
  "shadows": {"mode": "exact"}, "clip_geometry": true, %s}' "$tmp/g.zsm" "$src/tests/data/surfaces/cube.off" "$common" \
  > cut.json
printf '{"mesh": "%s", "spheres": {"path": "%s", "color": "scalar"}, "surfaces": [{"path": "%s",
  "transform": {"scale": 0.6, "translate": [-0.3, -0.3, -0.3]}}], "shadows": {"mode": "exact"}, %s}' \
  "$tmp/g.zsm" "$tmp/s.sph" "$src/tests/data/surfaces/cube.off" "$common" > both.json
for s in spheres surfaces iso cut both; do
  "$zsweep" render $s.json -o $s.exr --stats $s.st.json >/dev/null || { echo "FAIL: render $s"; fail=1; continue; }
  "$zsweep" reference $s.json -o $s.ref.exr --stats $s.ref.json >/dev/null || { echo "FAIL: reference $s"; fail=1; continue; }
  max=$("$zsweep" compare $s.exr $s.ref.exr --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["max_abs"])')
  python3 -c "import sys; sys.exit(0 if $max <= 1e-5 else 1)" || { echo "FAIL: $s: render vs reference: max abs $max"; fail=1; }
  python3 - $s.st.json $s <<'PY' || fail=1
import json, sys
st = json.load(open(sys.argv[1]))
want = {"spheres": "spheres", "both": "spheres and surfaces"}.get(sys.argv[2], "surfaces")
if not (st["rays_stopped_by_geometry"] > 0 and st["geometry"]["renderer"] == want):
    print("FAIL:", sys.argv[2], "stats", st["rays_stopped_by_geometry"], st["geometry"].get("renderer")); sys.exit(1)
PY
done
if command -v mpirun >/dev/null; then  # sort-first across two ranks: the same image, bit for bit
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  # Open MPI's own allocations are not freed at exit: no leak check here (as cli.mpi, scripts/test-sanitize).
  ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
    timeout 300 mpirun -np 2 --oversubscribe --bind-to none "$zsweep" render surfaces.json --mpi -o mpi.exr \
    >/dev/null 2>&1 || { echo "FAIL: --mpi"; fail=1; }
  d=$("$zsweep" compare mpi.exr surfaces.exr --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["max_abs"])')
  [ "$d" = "0" ] || [ "$d" = "0.0" ] || { echo "FAIL: --mpi changed the mixed image (max abs $d)"; fail=1; }
fi
python3 - cut.st.json <<'PY' || fail=1
import json, sys
c = json.load(open(sys.argv[1]))["geometry"].get("clip", {})
if not (c.get("triangles_cut", 0) > 0):
    print("FAIL: clip_geometry cut no triangle:", c); sys.exit(1)
PY
cmp -s cut.exr surfaces.exr && { echo "FAIL: clip_geometry changed nothing"; fail=1; }
printf '{"mesh": "%s", "spheres": "%s", "clip_geometry": true, %s}' "$tmp/g.zsm" "$tmp/s.sph" "$common" > cs.json
"$zsweep" render cs.json -o cs.png >out.txt 2>err.txt; rc=$?
[ $rc -ne 0 ] && grep -q "clip_geometry cuts surfaces; spheres are not cut" err.txt \
  || { echo "FAIL: clip_geometry with spheres: exit $rc: $(cat err.txt)"; fail=1; }
printf '{"mesh": "%s", %s}' "$tmp/g.zsm" "$common" > volume.json
"$zsweep" render volume.json -o volume.exr >/dev/null || fail=1
cmp -s volume.exr spheres.exr && { echo "FAIL: the spheres changed nothing"; fail=1; }
printf '{"mesh": "%s", "spheres": "%s", "render": {"mode": "weighted"}, %s}' "$tmp/g.zsm" "$tmp/s.sph" "$common" > t.json
"$zsweep" render t.json -o t.png >out.txt 2>err.txt; rc=$?
[ $rc -ne 0 ] && [ "$(wc -l <err.txt)" -eq 1 ] && [ ! -e t.png ] && grep -q "spheres inside a volume are opaque" err.txt \
  || { echo "FAIL: translucent spheres in a volume: exit $rc: $(cat err.txt)"; fail=1; }
printf '{"mesh": "%s", "surfaces": [{"isosurface": [99]}], %s}' "$tmp/g.zsm" "$common" > noiso.json
"$zsweep" render noiso.json -o noiso.png >out.txt 2>err.txt; rc=$?
[ $rc -ne 0 ] && [ "$(wc -l <err.txt)" -eq 1 ] && [ ! -e noiso.png ] && grep -q "g.zsm: no isosurface: the scalar" err.txt \
  || { echo "FAIL: an isosurface the scalar never takes: exit $rc: $(cat err.txt)"; fail=1; }
printf '{"surfaces": [{"boundary": true}]}' > nomesh.json
"$zsweep" render nomesh.json -o nomesh.png >out.txt 2>err.txt; rc=$?
[ $rc -ne 0 ] && grep -q "surfaces\[0\].boundary is for a volume scene's mesh" err.txt \
  || { echo "FAIL: a boundary without a mesh: exit $rc: $(cat err.txt)"; fail=1; }
[ $fail -eq 0 ] && echo "mixed scenes: ok"
exit $fail
