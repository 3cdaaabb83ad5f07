#!/usr/bin/env bash
# `mesh convert --renumber` on a mesh whose numbering is scattered writes
# the same mesh with its ids along a Morton curve (the id spread falls), and
# the three — plain grid order, shuffled, renumbered — render the same image
# bit for bit (a jittered grid: no two vertices tie in depth).
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
out=$("$zsweep" mesh convert shuffled.off renumbered.zsm --renumber) || { echo "FAIL: convert --renumber"; exit 1; }
python3 - "$out" <<'PY' || fail=1
import re, sys
m = re.search(r"renumbered \(id spread ([0-9.]+) -> ([0-9.]+)\)", sys.argv[1])
if not m or not float(m.group(2)) < 0.5 * float(m.group(1)):
    print("FAIL: convert --renumber said: " + sys.argv[1]); raise SystemExit(1)
PY
for m in plain.off shuffled.off renumbered.zsm; do
  "$zsweep" render $m --width 64 --height 48 --threads 2 -o $m.exr --stats $m.json >/dev/null || { echo "FAIL: render $m"; fail=1; }
done
for m in shuffled.off renumbered.zsm; do
  "$zsweep" compare plain.off.exr $m.exr | grep -q "^max abs 0 " || { echo "FAIL: $m: $("$zsweep" compare plain.off.exr $m.exr)"; fail=1; }
  cmp -s <(grep -E "^(points|tets|faces|boundary faces):" <("$zsweep" mesh info plain.off)) \
         <(grep -E "^(points|tets|faces|boundary faces):" <("$zsweep" mesh info $m)) || { echo "FAIL: $m: mesh info counts differ"; fail=1; }
done
exit $fail
