#!/usr/bin/env bash
# scripts/bench spheres-translucent --quick (no VTK, no Embree, no display;
# small sets, 256², the small sweep): every zsweep run exits 0; peel run to
# completion (t 0, no cap) equals sorted exact (max abs 0); sorted t 8 is
# within 8/510 of exact; no row whose t/2-levels bound is guaranteed breaks
# it; the CSVs, the Markdown and the PNGs are written and non-empty.
# Skipped (77) without a python3 that has numpy and matplotlib.
set -u
zsweep=$1; src=$2
py=""
for c in /usr/bin/python3 python3; do
  if command -v "$c" >/dev/null && "$c" -c 'import numpy, matplotlib' 2>/dev/null; then py=$c; break; fi
done
[[ -n "$py" ]] || { echo "SKIP: no python3 with numpy and matplotlib"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
ZSWEEP="$zsweep" PYTHON="$py" DISPLAY= "$src/scripts/bench" spheres-translucent --quick --out "$tmp" \
  >"$tmp/log" 2>&1 || { echo "FAIL: bench spheres-translucent exit $?"; tail -20 "$tmp/log"; exit 1; }
"$py" - "$tmp" <<'PY'
import csv, os, sys
d = sys.argv[1]
sets = ["c1", "c2", "c3", "c4"]
fail = 0
modes = list(csv.DictReader(open(os.path.join(d, "translucent-modes.csv"))))
errors = list(csv.DictReader(open(os.path.join(d, "translucent-errors.csv"))))
summary = list(csv.DictReader(open(os.path.join(d, "translucent-summary.csv"))))
if [s["set"] for s in summary] != sets:
    print("FAIL summary sets", [s["set"] for s in summary]); fail = 1
for s in summary:
    if s["compare_matches_zsweep"] != "yes":
        print(f"FAIL {s['set']}: the in-process compare differs from zsweep compare"); fail = 1
for r in modes + errors:
    if r["exit_status"] != "0" or not r["ms"] or float(r["ms"]) <= 0:
        print(f"FAIL {r['set']} {r['mode']} t={r['t']} cap={r['cap']}: exit {r['exit_status']}, ms {r['ms']}"); fail = 1
for s in sets:
    labels = {r["label"] for r in modes if r["set"] == s}
    if len(labels) != 7:
        print(f"FAIL {s}: Table 5 rows {sorted(labels)}"); fail = 1
    rows = [r for r in errors if r["set"] == s]
    peel = [r for r in rows if r["mode"] == "peel" and r["t"] == "0" and r["cap"] == "0"]
    if len(peel) != 1 or peel[0]["max_abs"] == "" or float(peel[0]["max_abs"]) != 0:
        print(f"FAIL {s}: peel t=0 cap 0 vs sorted exact: {[r['max_abs'] for r in peel]}"); fail = 1
    srt = [r for r in rows if r["mode"] == "sorted" and r["t"] == "8"]
    if len(srt) != 1 or srt[0]["max_abs"] == "" or float(srt[0]["max_abs"]) > 8 / 510 + 2e-6:
        print(f"FAIL {s}: sorted t=8 vs exact: {[r['max_abs'] for r in srt]} > 8/510"); fail = 1
    if {r["mode"] for r in rows} != {"sorted", "peel", "dual_peel", "weighted"} or len(rows) != 12:
        print(f"FAIL {s}: {len(rows)} sweep rows, modes {sorted({r['mode'] for r in rows})}"); fail = 1
for r in errors:
    if r["max_abs"] == "" or r["rmse"] == "":
        print(f"FAIL {r['set']} {r['mode']} t={r['t']} cap={r['cap']}: no error measured"); fail = 1
    if r["guaranteed"] == "yes" and r["within"] != "yes":
        print(f"FAIL {r['set']} {r['mode']} t={r['t']} cap={r['cap']}: guaranteed bound {r['bound_levels']} "
              f"levels, within {r['within']!r} (max abs {r['max_abs']})"); fail = 1
    if r["violation"]:
        print(f"FAIL {r['set']} {r['mode']} t={r['t']} cap={r['cap']}: violation {r['violation']}"); fail = 1
files = ["translucent-modes.csv", "translucent-errors.csv", "translucent-summary.csv", "translucent-results.md",
         "translucent-modes.png"] + [f"translucent-errors-{s}.png" for s in sets]
for f in files:
    p = os.path.join(d, f)
    if not os.path.exists(p) or not os.path.getsize(p):
        print("FAIL empty or missing", f); fail = 1
sys.exit(fail)
PY
