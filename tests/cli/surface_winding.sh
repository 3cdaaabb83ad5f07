#!/usr/bin/env bash
# Surfaces whatever their winding, over a ground that never fights them: a
# closed mesh wound inward renders bit-identical to its outward twin, and the
# summary and --stats say it was turned; a flat mesh gets the automatic
# ground a clear gap below, so no ground pixel shows through it.
set -u
zsweep=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
py=/usr/bin/python3
d=$src/tests/data/surfaces

# A unit cube of triangles, counter-clockwise from outside, and its twin
# wound inward (every triangle's last two corners swapped).
printf 'OFF\n8 12 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n%s\n' \
  "3 0 3 2
3 0 2 1
3 4 5 6
3 4 6 7
3 0 1 5
3 0 5 4
3 2 3 7
3 2 7 6
3 1 2 6
3 1 6 5
3 0 4 7
3 0 7 3" >"$tmp/cube.off"
awk 'NF == 4 && $1 == 3 { print 3, $2, $4, $3; next } { print }' "$tmp/cube.off" >"$tmp/inward.off"
for n in cube inward; do
  f=$tmp/$n.off
  "$zsweep" render "$f" -o "$tmp/$n.exr" --width 96 --height 72 --stats "$tmp/$n.json" >"$tmp/$n.out" 2>"$tmp/err" \
    || { echo "FAIL render $n: $(cat "$tmp/err")"; fail=1; }
done
"$zsweep" compare "$tmp/cube.exr" "$tmp/inward.exr" --json >"$tmp/cmp" 2>&1
grep -q '"max_abs": 0.0,' "$tmp/cmp" || { echo "FAIL inward cube differs: $(tr -d '\n' <"$tmp/cmp")"; fail=1; }
grep -q ", 1 closed surface wound inward turned outward$" "$tmp/inward.out" || { echo "FAIL summary: $(cat "$tmp/inward.out")"; fail=1; }
grep -q "turned outward" "$tmp/cube.out" && { echo "FAIL outward summary: $(cat "$tmp/cube.out")"; fail=1; }
$py - "$tmp/cube.json" "$tmp/inward.json" <<'PY' || fail=1
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
ok = a["orientation"]["turned_outward"] == 0 and b["orientation"]["turned_outward"] == 1 \
     and b["orientation"]["closed_solids"] == 1 and b["orientation"]["two_sided_triangles"] == 0 \
     and a["triangles"]["back_face_culled"] == b["triangles"]["back_face_culled"] > 0 \
     and a["ground"]["lowered_by"] == 0 and a["ground"]["height"] == 0
if not ok: print("FAIL stats", a["orientation"], b["orientation"], a["ground"])
sys.exit(0 if ok else 1)
PY

# A flat open grid at y = 0.25 (faces down, so seen from above by its back):
# bare (automatic ground) and in a scene without ground, the grid's pixels are
# the same depth and colour; the ground is lowered by 1 % of the extent.
$py - "$tmp/flat.obj" <<'PY'
import sys
n = 12
with open(sys.argv[1], "w") as f:
    for j in range(n + 1):
        for i in range(n + 1):
            f.write("v %g 0.25 %g\n" % (i / n, j / n))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            f.write("f %d %d %d\nf %d %d %d\n" % (a, a + 1, a + n + 2, a, a + n + 2, a + n + 1))
PY
printf '{"surfaces": ["%s"]}\n' "$tmp/flat.obj" >"$tmp/alone.json"
"$zsweep" render "$tmp/flat.obj" -o "$tmp/over.exr" --width 96 --height 72 --stats "$tmp/over.json" >"$tmp/over.out" 2>"$tmp/err" \
  || { echo "FAIL render flat: $(cat "$tmp/err")"; fail=1; }
"$zsweep" render "$tmp/alone.json" -o "$tmp/alone.exr" --width 96 --height 72 >/dev/null 2>"$tmp/err" \
  || { echo "FAIL render flat alone: $(cat "$tmp/err")"; fail=1; }
grep -q ", ground lowered 0.01 below the mesh" "$tmp/over.out" || { echo "FAIL flat summary: $(cat "$tmp/over.out")"; fail=1; }
$py - "$tmp/alone.exr" "$tmp/over.exr" "$tmp/over.json" <<'PY' || fail=1
import json, sys
import numpy as np, OpenImageIO as oiio
a = oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT)
b = oiio.ImageBuf(sys.argv[2]).get_pixels(oiio.FLOAT)
g = json.load(open(sys.argv[3])).get("ground", {"height": None, "lowered_by": None})
mesh = a[:, :, 3] > 0
wrong = (a[:, :, :5][mesh] != b[:, :, :5][mesh]).any(axis=1).sum()
ground = (~mesh & np.isfinite(b[:, :, 4])).sum()
ok = mesh.sum() > 500 and wrong == 0 and ground > 500 and g["height"] is not None \
     and abs(g["height"] - 0.24) < 1e-12 and abs(g["lowered_by"] - 0.01) < 1e-12
if not ok: print("FAIL flat over ground:", mesh.sum(), "grid pixels,", wrong, "won by the ground;", ground, "ground pixels;", g)
sys.exit(0 if ok else 1)
PY
exit $fail
