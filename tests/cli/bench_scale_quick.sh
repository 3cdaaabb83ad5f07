#!/usr/bin/env bash
# scripts/bench scale at toy sizes (no VTK, no display, docs untouched): two
# grids render at one thread with every phase timed and bytes per tet
# measured, a size beyond memory is skipped by its estimate (not generated),
# and both plots are written. Skipped (77) without a python3 with matplotlib.
# The grids are large enough (10 and 40 MB over the baseline) that bytes per
# tet stays well above the baseline's own noise (about 1 MB of RSS).
set -u
zsweep=$1; src=$2
py=""
for c in /usr/bin/python3 python3; do
  if command -v "$c" >/dev/null && "$c" -c 'import matplotlib' 2>/dev/null; then py=$c; break; fi
done
[[ -n "$py" ]] || { echo "SKIP: no python3 with matplotlib"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
ZSWEEP="$zsweep" PYTHON="$py" DISPLAY= "$src/scripts/bench" scale --tets 0.1,0.4,100000 --threads 1 --size 128 --no-vtk \
  --no-doc --csv "$tmp/s.csv" --work "$tmp" >"$tmp/log" 2>&1 || { echo "FAIL: bench scale exit $?"; tail -20 "$tmp/log"; exit 1; }
"$py" - "$tmp" <<'PY'
import csv, os, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "s.csv"))))
fail = 0
ok = [r for r in rows if r["status"] == "0"]
if [int(r["tets"]) for r in ok] != [109760, 425920]:
    print("FAIL rendered sizes", [r["tets"] for r in ok]); fail = 1
for r in ok:
    for k in ("load_s", "topology_s", "setup_s", "sweep_s", "first_frame_s", "later_frame_s", "bytes_per_tet",
              "est_bytes_per_tet", "gen_s"):
        if not r[k] or float(r[k]) <= 0:
            print(f"FAIL {r['mesh']}: {k} = {r[k]!r}"); fail = 1
skipped = [r for r in rows if r["status"].startswith("skipped")]
if len(skipped) != 1 or not skipped[0]["tets"].startswith("1000"):
    print("FAIL skipped rows", [(r["tets"], r["status"]) for r in skipped]); fail = 1
for f in ("scale-time.png", "scale-memory.png"):
    if not os.path.exists(os.path.join(d, f)) or not os.path.getsize(os.path.join(d, f)):
        print("FAIL no plot", f); fail = 1
if [x for x in os.listdir(d) if x.startswith("zsweep-scale-")]:
    print("FAIL scratch directory left behind"); fail = 1
sys.exit(fail)
PY
