#!/usr/bin/env bash
# scripts/bench spheres-ao --quick (no VTK, no Tachyon, no display; a few
# thousand spheres per set and 1hpv when pymol-data is installed, 128²,
# directions 6 and 18, maps 64² and 128²): every zsweep run (renders and
# references) exits 0; per set and direction count, the error against the same
# directions traced exactly does not grow with the map size (0.005 slack); over
# the sets, 18 directions are no further from the Monte Carlo reference than 6
# (0.005 slack); the Monte Carlo reference's N vs 4N difference matches its
# binomial expectation within 30 %; the CSVs, the Markdown and the PNGs are
# written and non-empty.
# Skipped (77) without a python3 that has numpy, matplotlib and OpenImageIO.
set -u
zsweep=$1; src=$2
py=""
for c in /usr/bin/python3 python3; do
  if command -v "$c" >/dev/null && "$c" -c 'import numpy, matplotlib, OpenImageIO' 2>/dev/null; then py=$c; break; fi
done
[[ -n "$py" ]] || { echo "SKIP: no python3 with numpy, matplotlib and OpenImageIO"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
ZSWEEP="$zsweep" PYTHON="$py" DISPLAY= "$src/scripts/bench" spheres-ao --quick --out "$tmp" >"$tmp/log" 2>&1 \
  || { echo "FAIL: bench spheres-ao exit $?"; tail -20 "$tmp/log"; exit 1; }
"$py" - "$tmp" <<'PY'
import csv, os, sys
d = sys.argv[1]
fail = 0
def load(f):
    return list(csv.DictReader(open(os.path.join(d, f))))
t6, t7, grid, refs = load("ao-table6.csv"), load("ao-table7.csv"), load("ao-error.csv"), load("ao-references.csv")
sets = ["c1", "c2", "c3", "c4"] + (["1hpv"] if os.path.exists("/usr/share/pymol/data/tut/1hpv.pdb") else [])
if [r["set"] for r in t6] != sets:
    print("FAIL Table 6 sets", [r["set"] for r in t6]); fail = 1
for r in t6:
    if r["phong_exit"] != "0" or r["ao_exit"] != "0" or not float(r["phong_ms"]) > 0 or not float(r["ao_ms"]) > 0 \
            or not float(r["maps_ms"]) > 0:
        print(f"FAIL Table 6 {r['set']}: exit {r['phong_exit']}/{r['ao_exit']}, ms {r['phong_ms']}/{r['ao_ms']}"); fail = 1
for r in grid + refs + t7:
    if r["exit_status"] != "0":
        print(f"FAIL {r['set']} {r.get('kind', '')} {r['directions']} {r.get('map_size', '')}: exit {r['exit_status']}")
        fail = 1
if len(grid) != 4 * len(sets) or len(refs) != 4 * len(sets) or len(t7) != 2 * len(sets):
    print(f"FAIL rows: grid {len(grid)}, references {len(refs)}, Table 7 {len(t7)}"); fail = 1
for r in t7:
    if not float(r["maps_ms"]) > 0 or not float(r["map_mb"]) > 0:
        print(f"FAIL Table 7 {r['set']} {r['directions']}: {r['maps_ms']} ms, {r['map_mb']} MiB"); fail = 1
def err(s, dirs, m, key):
    x = [float(r[key]) for r in grid if r["set"] == s and r["directions"] == str(dirs) and r["map_size"] == str(m)]
    return x[0] if x and x[0] == x[0] else float("inf")
tol = 0.005
mc6 = mc18 = 0.0
for s in sets:
    for dirs in (6, 18):
        small, large = err(s, dirs, 64, "vs_exact_mean"), err(s, dirs, 128, "vs_exact_mean")
        if not large <= small + tol:
            print(f"FAIL {s} {dirs} directions: error vs exact grows with the map: {small} (64) -> {large} (128)"); fail = 1
    mc6 += err(s, 6, 128, "vs_mc_mean") / len(sets)
    mc18 += err(s, 18, 128, "vs_mc_mean") / len(sets)
    mc = [r for r in refs if r["set"] == s and r.get("noise_floor_mean")]
    if len(mc) != 1 or not 0.7 <= float(mc[0]["n_vs_4n_mean"]) / float(mc[0]["n_vs_4n_expected"]) <= 1.3:
        print(f"FAIL {s}: MC N vs 4N {[(r['n_vs_4n_mean'], r['n_vs_4n_expected']) for r in mc]}"); fail = 1
if not mc18 <= mc6 + tol:
    print(f"FAIL mean error vs MC: 18 directions {mc18} > 6 directions {mc6}"); fail = 1
for f in ["ao-table6.csv", "ao-table7.csv", "ao-error.csv", "ao-references.csv", "ao-results.md", "ao-time-error.png",
          "ao-error-map.png", "ao-table7.png", "ao-table6.png"]:
    p = os.path.join(d, f)
    if not os.path.exists(p) or not os.path.getsize(p):
        print("FAIL empty or missing", f); fail = 1
if not fail:
    print(f"bench_spheres_ao_quick: all checks passed (mean error vs MC: 6 directions {mc6:.4f}, 18 {mc18:.4f})")
sys.exit(fail)
PY
