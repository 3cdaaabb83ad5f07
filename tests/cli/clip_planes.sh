#!/usr/bin/env bash
# Clip planes and a crop box in a scene: the engine and the reference agree
# (float images, within 1e-5) and count what they cut; a plane that keeps
# none of the mesh says so; a bad plane is one line naming the scene, and no
# image.
set -u
zsweep=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
cd "$tmp" || exit 1
"$zsweep" mesh generate grid --cells 6 --jitter 0.1 -o g.zsm >/dev/null || { echo "FAIL: generate"; exit 1; }
scene() {  # scene NAME CLIP-AND-CROP-JSON
  printf '{"mesh": "%s", "image": {"width": 64, "height": 48}, %s}' "$tmp/g.zsm" "$2" > "$1"
}
scene s.json '"clip": [{"plane": [0.5, -1, 0.3, 0.2]}], "crop": [-0.8, 0.9, -1, 1, -0.6, 1]'
"$zsweep" render s.json -o e.exr --stats e.json >/dev/null || { echo "FAIL: render"; fail=1; }
"$zsweep" reference s.json -o r.exr --stats r.json >/dev/null || { echo "FAIL: reference"; fail=1; }
max=$("$zsweep" compare e.exr r.exr --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["max_abs"])')
python3 -c "import sys; sys.exit(0 if $max <= 1e-5 else 1)" || { echo "FAIL: engine vs reference: max abs $max"; fail=1; }
python3 - e.json r.json <<'PY' || fail=1
import json, sys
e, r = (json.load(open(p)) for p in sys.argv[1:3])
if not (e["tets_clipped"] > 0 and e["segments_clipped"] > 0 and r["segments_clipped"] > 0):
    print("FAIL: clip counts", e["tets_clipped"], e["segments_clipped"], r["segments_clipped"]); sys.exit(1)
PY
"$zsweep" render g.zsm --width 64 --height 48 -o plain.exr >/dev/null || fail=1
cmp -s plain.exr e.exr && { echo "FAIL: the clip planes changed nothing"; fail=1; }
scene none.json '"clip": [{"plane": [1, 0, 0, 5]}]'
"$zsweep" render none.json -o none.png >out.txt 2>err.txt || fail=1
grep -q "clip planes keep none of the mesh" out.txt err.txt || { echo "FAIL: no word on an empty clip: $(cat out.txt err.txt)"; fail=1; }
scene bad.json '"clip": [{"plane": [0, 0, 0, 1]}]'
"$zsweep" render bad.json -o bad.png >out.txt 2>err.txt; rc=$?
[ $rc -ne 0 ] && [ "$(wc -l <err.txt)" -eq 1 ] && [ ! -e bad.png ] && grep -q "bad.json: clip\[0\].plane's normal" err.txt \
  || { echo "FAIL: zero normal: exit $rc: $(cat err.txt)"; fail=1; }
[ $fail -eq 0 ] && echo "clip planes: ok"
exit $fail
