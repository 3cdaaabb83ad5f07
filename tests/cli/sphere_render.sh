#!/usr/bin/env bash
# `zsweep render` on sphere scenes and files: the image and its Z channel equal
# the Embree reference's (same camera, colours and shading; both projections);
# threads, tile size and --no-culling change no pixel; a sphere scene's keys
# are checked; bad scenes fail in one line and leave no output.
set -u
zsweep=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/same_image.sh"  # same A B WHAT: pixel- and depth-identical
close() {  # a b what: within 1e-5 in colour, depth within 1e-6 relative, at most 3 grazing pixels
  "$zsweep" compare "$1" "$2" --json >"$tmp/cmp" 2>&1
  python3 - "$tmp/cmp" "$3" <<'PY' || fail=1
import json, sys
j = json.load(open(sys.argv[1]))
ok = j["max_abs"] <= 1e-5 and "z" in j and j["z"]["coverage_mismatches"] <= 3 and j["z"]["max_rel"] <= 1e-6
if not ok:
    print("FAIL", sys.argv[2], j)
sys.exit(0 if ok else 1)
PY
}

# Render against the reference: a real protein (when pymol-data is there)
# and the small test files.
inputs=("$src/tests/data/spheres/small.pdb" "$src/tests/data/spheres/small.sph")
[[ -f /usr/share/pymol/data/demo/1tii.pdb ]] && inputs+=(/usr/share/pymol/data/demo/1tii.pdb)
for f in "${inputs[@]}"; do
  for p in orthographic perspective; do
    n=$(basename "$f").$p
    "$zsweep" render "$f" -o "$tmp/$n.exr" --width 120 --height 90 --projection $p >/dev/null 2>"$tmp/err" \
      || { echo "FAIL render $n: $(cat "$tmp/err")"; fail=1; continue; }
    "$zsweep" reference "$f" -o "$tmp/$n.ref.exr" --width 120 --height 90 --projection $p >/dev/null 2>"$tmp/err" \
      || { echo "FAIL reference $n: $(cat "$tmp/err")"; fail=1; continue; }
    close "$tmp/$n.exr" "$tmp/$n.ref.exr" "$n vs reference"
  done
done

# A scene: per-sphere RGBA, flat shading, perspective, a camera close in.
cat >"$tmp/set.sph" <<'S'
0 0 0 1 1 0 0 1
1.2 0 0.3 0.8 0 1 0 0.5
-0.9 0.7 -0.4 0.6 0 0 1 1
0.2 -1.1 0.8 0.5 1 1 0 1
S
cat >"$tmp/scene.json" <<'S'
{ "spheres": {"path": "set.sph", "color": "rgba", "radius_scale": 1.0},
  "image": {"width": 96, "height": 80, "background": [0, 0, 0, 1]},
  "camera": {"projection": "perspective", "eye": [0.5, 0.4, 5], "target": [0, 0, 0], "fov_y": 40},
  "shading": {"model": "phong", "light_direction": [0.3, -0.2, -1], "ambient": 0.1, "diffuse": 0.8,
              "specular": 0.5, "shininess": 20},
  "render": {"mode": "opaque", "grid": 4, "culling": true} }
S
"$zsweep" render "$tmp/scene.json" -o "$tmp/s1.exr" --threads 1 --stats "$tmp/s1.json" >/dev/null || fail=1
"$zsweep" render "$tmp/scene.json" -o "$tmp/s2.exr" --threads 2 --tile-size 24 >/dev/null || fail=1
"$zsweep" render "$tmp/scene.json" -o "$tmp/s3.exr" --no-culling >/dev/null || fail=1
"$zsweep" reference "$tmp/scene.json" -o "$tmp/sref.exr" >/dev/null || fail=1
same "$tmp/s1.exr" "$tmp/s2.exr" "threads and tiles"
same "$tmp/s1.exr" "$tmp/s3.exr" "--no-culling"
close "$tmp/s1.exr" "$tmp/sref.exr" "scene vs reference"
grep -q '"renderer": "spheres"' "$tmp/s1.json" && grep -q '"spheres_visible": 4' "$tmp/s1.json" \
  || { echo "FAIL stats: $(cat "$tmp/s1.json")"; fail=1; }
"$zsweep" render "$tmp/scene.json" -o "$tmp/s.png" >/dev/null && [[ -s "$tmp/s.png" ]] || { echo "FAIL png"; fail=1; }

# Translucent modes on the same scene (two spheres of alpha 0.5 among
# opaque ones): sorted with no tolerance is the reference's exact composite,
# peel to completion is sorted bit for bit, threads and tiles change nothing.
for m in sorted peel dual_peel weighted; do
  sed "s/\"mode\": \"opaque\"/\"mode\": \"$m\", \"tolerance\": 0, \"max_layers\": 0/" "$tmp/scene.json" >"$tmp/$m.json"
  "$zsweep" render "$tmp/$m.json" -o "$tmp/$m.exr" --stats "$tmp/$m.st.json" >/dev/null || { echo "FAIL render $m"; fail=1; }
  "$zsweep" render "$tmp/$m.json" -o "$tmp/$m.2.exr" --threads 2 --tile-size 16 >/dev/null || fail=1
  same "$tmp/$m.exr" "$tmp/$m.2.exr" "$m: threads and tiles"
  grep -q '"fragments_composited"' "$tmp/$m.st.json" || { echo "FAIL $m stats: $(cat "$tmp/$m.st.json")"; fail=1; }
done
"$zsweep" reference "$tmp/sorted.json" -o "$tmp/tref.exr" >/dev/null || fail=1
close "$tmp/sorted.exr" "$tmp/tref.exr" "sorted vs reference"
same "$tmp/sorted.exr" "$tmp/peel.exr" "peel to completion vs sorted"
close "$tmp/sorted.exr" "$tmp/dual_peel.exr" "dual_peel to completion vs sorted"

# Bad scenes: one line naming the scene, exit 1, no output file.
bad() {  # name json expected-substring
  printf '%s\n' "$2" >"$tmp/$1.json"
  "$zsweep" render "$tmp/$1.json" -o "$tmp/$1.exr" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  if [[ $rc -ne 1 || -e "$tmp/$1.exr" || $(wc -l <"$tmp/err") -ne 1 ]] || ! grep -qF -- "$3" "$tmp/err"; then
    echo "FAIL $1: rc $rc, stderr: $(cat "$tmp/err")"; fail=1
  fi
}
bad both '{"spheres": "set.sph", "surfaces": ["c.obj"]}' "one of 'mesh', 'spheres' or 'surfaces'"
bad shading_on_volume '{"mesh": "m.off", "shading": {}}' "'shading' is for sphere and surface scenes"
bad unknown_key '{"spheres": "set.sph", "render": {"scan": "span"}}' "render"
bad bad_mode '{"spheres": "set.sph", "render": {"mode": "glass"}}' "render.mode must be"
bad bad_color '{"spheres": {"path": "set.sph", "color": "scalar"}}' "no scalar"
bad bad_tolerance '{"spheres": "set.sph", "render": {"mode": "sorted", "tolerance": 300}}' "render.tolerance"
bad missing_file '{"spheres": "nowhere.sph"}' "nowhere.sph"
bad bad_light '{"spheres": "set.sph", "shading": {"light_direction": [0, 0, 0]}}' "light_direction"
exit $fail
