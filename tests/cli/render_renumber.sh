#!/usr/bin/env bash
# A mesh whose numbering is scattered is renumbered for locality before its
# topology is built (stats: mesh.renumbered, time_ms.renumber), and renders
# the image of the same mesh in its plain order, bit for bit; a mesh in plain
# grid order is left as it is.
set -u
zsweep=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
cd "$tmp" || exit 1
"$zsweep" mesh generate grid --cells 20 --jitter 0.1 -o plain.off >/dev/null || { echo "FAIL: generate"; exit 1; }
# The same tets over the same points, every id shuffled (Python, no numpy).
python3 - <<'PY' || { echo "FAIL: shuffle"; exit 1; }
import random
lines = [l for l in open("plain.off") if l.strip() and not l.startswith("#")]
head = lines[0].split()
skip = 1 if len(head) == 2 else 2
nv, nt = (int(x) for x in (head if len(head) == 2 else head + lines[1].split()))
pts, tets = lines[skip:skip + nv], lines[skip + nv:skip + nv + nt]
rng = random.Random(4)
perm = list(range(nv)); rng.shuffle(perm)
out = [None] * nv
for i, p in enumerate(pts): out[perm[i]] = p
rng.shuffle(tets)
with open("shuffled.off", "w") as f:
    f.write(f"{nv} {nt}\n"); f.writelines(out)
    f.writelines(" ".join(str(perm[int(x)]) for x in t.split()) + "\n" for t in tets)
PY
for m in plain shuffled; do
  "$zsweep" render $m.off --width 64 --height 48 --threads 2 -o $m.exr --stats $m.json >/dev/null || { echo "FAIL: render $m"; fail=1; }
done
"$zsweep" compare plain.exr shuffled.exr | grep -q "^max abs 0 " || { echo "FAIL: images differ: $("$zsweep" compare plain.exr shuffled.exr)"; fail=1; }
python3 - <<'PY' || fail=1
import json
p, s = json.load(open("plain.json")), json.load(open("shuffled.json"))
ok = True
if p["mesh"]["renumbered"]: print("FAIL: the plain grid was renumbered"); ok = False
if not s["mesh"]["renumbered"] or not s["time_ms"]["renumber"] > 0: print("FAIL: the shuffled mesh was not renumbered"); ok = False
if p["fragments"] != s["fragments"]: print("FAIL: fragment counts differ"); ok = False
raise SystemExit(0 if ok else 1)
PY
exit $fail
