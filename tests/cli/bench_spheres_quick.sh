#!/usr/bin/env bash
# scripts/bench spheres --quick (no VTK, no Embree, no display): every set
# gets its orbit rows (3 frames x basic and optimized, one thread), every
# zsweep run exits 0, and optimized == basic bit for bit. (Every zsweep process
# costs ~0.5 s of start-up here, so --quick leaves out the 2-thread runs.)
# Skipped (77) without a python3 that has numpy and matplotlib.
set -u
zsweep=$1; src=$2
py=""
for c in /usr/bin/python3 python3; do
  if command -v "$c" >/dev/null && "$c" -c 'import numpy, matplotlib' 2>/dev/null; then py=$c; break; fi
done
[[ -n "$py" ]] || { echo "SKIP: no python3 with numpy and matplotlib"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
ZSWEEP="$zsweep" PYTHON="$py" DISPLAY= "$src/scripts/bench" spheres --quick --out "$tmp" >"$tmp/log" 2>&1 \
  || { echo "FAIL: bench spheres exit $?"; tail -20 "$tmp/log"; exit 1; }
"$py" - "$tmp" <<'PY'
import csv, os, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "spheres-frames.csv"))))
fail = 0
for s in ("c1", "c2", "c3", "c4"):
    for renderer, t in (("zsweep-basic", "1"), ("zsweep-optimized", "1")):
        got = sorted(r["frame"] for r in rows if r["set"] == s and r["renderer"] == renderer and r["threads"] == t)
        if got != ["0", "1", "2"]:
            print(f"FAIL {s} {renderer} {t} threads: frames {got}"); fail = 1
for r in rows:
    if r["exit_status"] != "0" or not r["ms"] or float(r["ms"]) <= 0:
        print(f"FAIL {r['set']} frame {r['frame']} {r['renderer']}: exit {r['exit_status']}, ms {r['ms']}"); fail = 1
    if r["same_as_basic"] != "yes" or float(r["max_abs_vs_basic"]) != 0:
        print(f"FAIL {r['set']} frame {r['frame']} {r['renderer']} {r['threads']}: differs from basic "
              f"(max abs {r['max_abs_vs_basic']})"); fail = 1
summary = list(csv.DictReader(open(os.path.join(d, "spheres-summary.csv"))))
if [s["set"] for s in summary] != ["c1", "c2", "c3", "c4"]:
    print("FAIL summary sets", [s["set"] for s in summary]); fail = 1
for f in ["results.md"] + [f"spheres-{s}.png" for s in ("c1", "c2", "c3", "c4", "mean")]:
    if not os.path.getsize(os.path.join(d, f)):
        print("FAIL empty", f); fail = 1
sys.exit(fail)
PY
