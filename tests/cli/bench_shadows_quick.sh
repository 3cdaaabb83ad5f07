#!/usr/bin/env bash
# scripts/bench shadows --quick (no VTK, one thread): every scene gets its
# exact render and its 18 map renders (maps 512/1024 x PCF 1/4/9 x 1-SM,
# 2-SM max, 3-SM), tilted its acne and peter-panning runs; the bench itself
# asserts levels <= n*k+1, band RMSE < 0.5 and few far errors at map 1024, and
# that acne and peter-panning are detected (exit 1 otherwise); here: it exits
# 0, and results.csv, crossover.csv, summary.md and the PNGs are there.
# Skipped (77) without a /usr/bin/python3 that has numpy, scipy, matplotlib
# and OpenImageIO.
set -u
zsweep=$1; src=$2
py=""
for c in /usr/bin/python3 python3; do
  if command -v "$c" >/dev/null && "$c" -c 'import numpy, scipy, matplotlib, OpenImageIO' 2>/dev/null; then
    py=$c; break
  fi
done
[[ -n "$py" ]] || { echo "SKIP: no python3 with numpy, scipy, matplotlib and OpenImageIO"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
ZSWEEP="$zsweep" PYTHON="$py" DISPLAY= "$src/scripts/bench" shadows --quick --out "$tmp" >"$tmp/log" 2>&1 \
  || { echo "FAIL: bench shadows exit $?"; tail -30 "$tmp/log"; exit 1; }
"$py" - "$tmp" <<'PY'
import csv, os, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "results.csv"))))
fail = 0
scenes = sorted({r["scene"] for r in rows})
if not {"bars", "tilted"} <= set(scenes):
    print("FAIL scenes", scenes); fail = 1
per_scene = 1 + 2 * 3 * 3  # exact + maps x pcf x depths
want = per_scene * len(scenes) + 2  # + tilted's acne and peter-panning runs
if len(rows) != want:
    print(f"FAIL results.csv has {len(rows)} rows, want {want}"); fail = 1
for s in scenes:
    got = sorted((r["map_size"], r["depths"], r["select"], r["pcf"]) for r in rows if r["scene"] == s and r["kind"] == "map")
    if len(got) != 18 or len(set(got)) != 18:
        print(f"FAIL {s}: map configs {got}"); fail = 1
for r in rows:
    if float(r["time_ms"]) <= 0 or int(r["levels"]) > int(r["max_levels"]):
        print(f"FAIL {r['scene']} {r['config']} {r['map_size']}: ms {r['time_ms']}, levels {r['levels']}/{r['max_levels']}")
        fail = 1
cross = list(csv.DictReader(open(os.path.join(d, "crossover.csv"))))
if len(cross) != 6:
    print(f"FAIL crossover.csv has {len(cross)} rows, want 6"); fail = 1
text = open(os.path.join(d, "summary.md")).read()
for want_text in ("## bars", "## tilted", "Eq. 5.6", "Checks", "All passed"):
    if want_text not in text:
        print("FAIL summary.md lacks", want_text); fail = 1
for f in [f"scatter-{s}.png" for s in scenes] + ["crossover.png"]:
    p = os.path.join(d, f)
    if not os.path.isfile(p) or not os.path.getsize(p):
        print("FAIL missing or empty", f); fail = 1
sys.exit(fail)
PY
