#!/usr/bin/env bash
# `zsweep render` on triangle surfaces (docs/shadows.md): a bare mesh renders
# over a ground plane with one light; EXR/TIFF carry Z and lit0..; map and
# exact shadows agree away from shadow edges; threads and tiles change no
# pixel; --stats counts culling; bad meshes and scenes fail in one line
# naming the file and leave no output.
set -u
zsweep=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
py=/usr/bin/python3
same() {  # a b what: pixel- and depth-identical
  "$zsweep" compare "$1" "$2" --json >"$tmp/cmp" 2>&1
  grep -q '"max_abs": 0.0,' "$tmp/cmp" || { echo "FAIL $3: $(tr -d '\n' <"$tmp/cmp")"; fail=1; }
}
d=$src/tests/data/surfaces

# A bare mesh: framed automatically over a ground plane, one light.
for f in "$d/cube.off" "$d/pyramid.obj"; do
  n=$(basename "$f")
  "$zsweep" render "$f" -o "$tmp/$n.png" --width 96 --height 72 --stats "$tmp/$n.json" >"$tmp/out" 2>"$tmp/err" \
    || { echo "FAIL render $n: $(cat "$tmp/err")"; fail=1; continue; }
  [[ -s "$tmp/$n.png" ]] || { echo "FAIL $n: no image"; fail=1; }
  grep -q "triangles drawn" "$tmp/out" || { echo "FAIL $n: $(cat "$tmp/out")"; fail=1; }
  $py - "$tmp/$n.json" "$n" <<'PY' || fail=1
import json, sys
j = json.load(open(sys.argv[1])); t = j["triangles"]
ok = j["renderer"] == "surfaces" and t["back_face_culled"] > 0 and j["rendered_pixels"] > 0 \
     and j["lights"] == 1 and j["shadows"]["levels"] == 2 and t["polygons_split_on_read"] >= 1
if not ok: print("FAIL stats", sys.argv[2], j)
sys.exit(0 if ok else 1)
PY
done

# A scene with two lights, map and exact, EXR channels.
mesh=$d/pyramid.obj
[[ -f /usr/share/doc/libcgal-dev/data.tar.gz ]] && tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$tmp" \
  data/meshes/elephant.off 2>/dev/null && mesh=$tmp/data/meshes/elephant.off
for mode in map exact; do
  cat >"$tmp/$mode.json" <<S
{"surfaces": [{"path": "$mesh", "color": [0.8, 0.6, 0.5], "transform": {"scale": 2, "rotate_deg": [0, 30, 0]}}],
 "ground": {"color": [0.9, 0.9, 0.9]},
 "image": {"width": 160, "height": 120, "background": [0.2, 0.3, 0.4, 1]},
 "lights": [{"type": "directional", "direction": [-1, -2, -1]},
            {"type": "spot", "position": [2, 4, 3], "target": [0, 0, 0], "fov_deg": 60}],
 "shading": {"model": "phong", "ambient": 0.15},
 "shadows": {"mode": "$mode", "map_size": 1024}}
S
  "$zsweep" render "$tmp/$mode.json" -o "$tmp/$mode.exr" --threads 2 >/dev/null 2>"$tmp/err" \
    || { echo "FAIL render $mode: $(cat "$tmp/err")"; fail=1; }
done
# An 8-bit output: the frames carry R, G, B, A only, the same colours as the EXR's.
"$zsweep" render "$tmp/map.json" -o "$tmp/map.png" --threads 2 >/dev/null 2>"$tmp/err" \
  || { echo "FAIL render png: $(cat "$tmp/err")"; fail=1; }
$py - "$tmp/map.exr" "$tmp/map.png" <<'PY' || fail=1
import sys
import numpy as np, OpenImageIO as oiio
e = oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT)[:, :, :4]
p = oiio.ImageBuf(sys.argv[2]).get_pixels(oiio.UINT8).astype(np.float64)
d = np.abs(p - np.clip(e, 0, 1) * 255).max()
ok = p.shape == e.shape and d <= 0.5 + 1e-3
if not ok: print("FAIL png vs exr colours", p.shape, e.shape, d)
sys.exit(0 if ok else 1)
PY
$py - "$tmp/map.exr" "$tmp/exact.exr" <<'PY' || fail=1
import sys
import numpy as np, OpenImageIO as oiio
a, b = oiio.ImageBuf(sys.argv[1]), oiio.ImageBuf(sys.argv[2])
names = a.spec().channelnames
A, B = a.get_pixels(oiio.FLOAT), b.get_pixels(oiio.FLOAT)
ok = names == ("R", "G", "B", "A", "Z", "lit0", "lit1")
hit = np.isfinite(A[:, :, 4])
ok = ok and np.array_equal(A[:, :, 4], B[:, :, 4]) and np.isfinite(A[:, :, 4][hit]).all() and np.isinf(A[:, :, 4][~hit]).all()
for c in (5, 6):
    la, lb = A[:, :, c][hit], B[:, :, c][hit]
    ok = ok and set(np.unique(la)) <= {0.0, 1.0} and set(np.unique(lb)) <= {0.0, 1.0}
    ok = ok and (la != lb).sum() <= 0.02 * hit.sum() and 0 < lb.mean() < 1
if not ok:
    print("FAIL map vs exact:", names, np.array_equal(A[:, :, 4], B[:, :, 4]),
          [((A[:, :, c] != B[:, :, c]) & hit).sum() for c in (5, 6)], [B[:, :, c][hit].mean() for c in (5, 6)],
          [np.unique(A[:, :, c][hit]) for c in (5, 6)], hit.sum())
sys.exit(0 if ok else 1)
PY

# Threads and tile size change no pixel (n-SM, PCF, both lights), TIFF too.
sed 's/"mode": "map", "map_size": 1024/"mode": "map", "map_size": 512, "depths": 3, "pcf": 9/' "$tmp/map.json" >"$tmp/msm.json"
"$zsweep" render "$tmp/msm.json" -o "$tmp/t1.tif" --threads 1 --tile-size 16 >/dev/null 2>&1 || { echo "FAIL t1"; fail=1; }
"$zsweep" render "$tmp/msm.json" -o "$tmp/t2.tif" --threads 2 --tile-size 64 >/dev/null 2>&1 || { echo "FAIL t2"; fail=1; }
same "$tmp/t1.tif" "$tmp/t2.tif" "threads/tiles"

# `zsweep reference` on a surface is its exact mode: the same image as a
# render with shadows.mode exact.
printf '{"surfaces": ["%s"], "ground": true, "shadows": {"mode": "exact"}}\n' "$d/pyramid.obj" >"$tmp/ex.json"
"$zsweep" reference "$d/pyramid.obj" -o "$tmp/ref.exr" --width 80 --height 60 >/dev/null 2>&1 || { echo "FAIL reference"; fail=1; }
"$zsweep" render "$tmp/ex.json" -o "$tmp/ex.exr" --width 80 --height 60 >/dev/null 2>&1 || { echo "FAIL exact render"; fail=1; }
same "$tmp/ref.exr" "$tmp/ex.exr" "reference = exact mode"

# Bad meshes and scenes: one line naming the file, non-zero exit, no output.
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n' >"$tmp/range.off"
printf 'v 0 0 0\nv 1 0 0\n' >"$tmp/noface.obj"
: >"$tmp/empty.stl"
bad_scene() {  # name json
  printf '%s\n' "$2" >"$tmp/$1.json"
}
bad_scene unknown '{"surfaces": ["'"$d"'/cube.off"], "shadows": {"bias": 0.1, "blur": 2}}'
bad_scene pcf '{"surfaces": ["'"$d"'/cube.off"], "shadows": {"pcf": 3}}'
bad_scene depths '{"surfaces": ["'"$d"'/cube.off"], "shadows": {"depths": 0}}'
bad_scene select '{"surfaces": ["'"$d"'/cube.off"], "shadows": {"select": "avg"}}'
bad_scene light '{"surfaces": ["'"$d"'/cube.off"], "lights": [{"type": "directional"}]}'
bad_scene spot '{"surfaces": ["'"$d"'/cube.off"], "lights": [{"type": "spot", "position": [0,1,0], "target": [0,1,0]}]}'
bad_scene both '{"surfaces": ["'"$d"'/cube.off"], "spheres": "x.sph"}'
bad_scene missing '{"surfaces": ["nope.obj"]}'
bad_scene mesh '{"surfaces": ["range.off"]}'
for f in range.off noface.obj empty.stl unknown.json pcf.json depths.json select.json light.json spot.json both.json \
         missing.json mesh.json; do
  out=$tmp/out-$f.png
  if "$zsweep" render "$tmp/$f" -o "$out" --width 32 --height 32 >/dev/null 2>"$tmp/err"; then
    echo "FAIL $f: accepted"; fail=1
  fi
  [[ -e "$out" ]] && { echo "FAIL $f: left $out"; fail=1; }
  [[ $(wc -l <"$tmp/err") -eq 1 ]] || { echo "FAIL $f: not one line: $(cat "$tmp/err")"; fail=1; }
  want=$f; [[ $f == mesh.json ]] && want=range.off; [[ $f == missing.json ]] && want=nope.obj
  grep -q "$want" "$tmp/err" || { echo "FAIL $f: error does not name $want: $(cat "$tmp/err")"; fail=1; }
done
exit $fail
