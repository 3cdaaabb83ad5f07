#!/usr/bin/env bash
# `zsweep reference`, `zsweep compare` and `zsweep bench accuracy` end to end
# on the embedded default scene: the engine matches the reference, the
# approximate settings do not, and early termination stays within its bound.
set -u
zsweep=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
"$zsweep" reference --width 96 --height 80 -o "$tmp/ref.exr" --stats "$tmp/ref.json" >/dev/null || fail "reference"
"$zsweep" render --width 96 --height 80 -o "$tmp/z.exr" >/dev/null 2>&1 || fail "render"
"$zsweep" render --width 96 --height 80 --integrator taylor2 -o "$tmp/t2.exr" >/dev/null 2>&1 || fail "render taylor2"
"$zsweep" compare "$tmp/z.exr" "$tmp/ref.exr" --json > "$tmp/c.json" || fail "compare"
"$zsweep" compare "$tmp/t2.exr" "$tmp/ref.exr" --json --diff "$tmp/d.png" > "$tmp/c2.json" || fail "compare taylor2"
[ -s "$tmp/d.png" ] || fail "no difference image"
python3 - "$tmp" <<'PY' || fail "reference/compare checks"
import json, sys
d = sys.argv[1]
c, c2, st = (json.load(open(f"{d}/{n}")) for n in ("c.json", "c2.json", "ref.json"))
assert c["max_abs"] <= 1e-5, c
assert c["pixels_over_1_255"] == 0, c
assert c2["max_abs"] > 1e-3, c2  # the 2nd-order expansion is an approximation
assert st["lost_walks"] == 0 and st["rays_hit"] > 1000, st
PY
# --rgb: an image without alpha (as VTK's screen grabs) against one with it.
python3 - "$tmp" <<'PY' || fail "writing the --rgb test images"
import struct, sys, zlib
def png(path, channels, pixel):  # 4x3, one colour; colour type 2 = RGB, 6 = RGBA
    raw = b"".join(b"\0" + bytes(pixel) * 4 for _ in range(3))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
    hdr = struct.pack(">IIBBBBB", 4, 3, 8, 2 if channels == 3 else 6, 0, 0, 0)
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", hdr) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
# PNG alpha is straight: read back premultiplied, the RGBA image's colour
# over black is the RGB one to within rounding (102·128/255 ≈ 51, ...).
png(sys.argv[1] + "/rgba.png", 4, [102, 203, 253, 128])
png(sys.argv[1] + "/rgb.png", 3, [51, 102, 127])
PY
"$zsweep" compare "$tmp/rgba.png" "$tmp/rgb.png" --json > "$tmp/c4.json" || fail "compare rgba/rgb"
"$zsweep" compare "$tmp/rgba.png" "$tmp/rgb.png" --rgb --json > "$tmp/c3.json" || fail "compare --rgb"
python3 -c 'import json,sys; a,b=(json.load(open(f)) for f in sys.argv[1:]); assert abs(a["max_abs"]-127/255)<1e-6 and b["max_abs"]<1/255 and b["pixels_over_1_255"]==0, (a,b)' \
  "$tmp/c4.json" "$tmp/c3.json" || fail "--rgb must compare colour only"
# A missing scene: one line naming the file, exit 1, no output image.
out=$("$zsweep" reference "$tmp/nope.json" -o "$tmp/never.exr" 2>&1); rc=$?
[ $rc -eq 1 ] || fail "missing scene: exit $rc"
echo "$out" | grep -q "nope.json" || fail "missing scene: message '$out'"
[ ! -e "$tmp/never.exr" ] || fail "output written for a missing scene"
# The single-precision kernel: within its bound of the reference; a bad
# --precision is refused before anything is written.
"$zsweep" render --width 96 --height 80 --precision single -o "$tmp/s.exr" --stats "$tmp/s.json" >/dev/null 2>&1 \
  || fail "render single"
python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["precision"] == "single" and j["kernel"].endswith("-f32"), j' \
  "$tmp/s.json" || fail "stats do not name the single kernel"
"$zsweep" compare "$tmp/s.exr" "$tmp/ref.exr" --json > "$tmp/cs.json" || fail "compare single"
python3 -c 'import json,sys; c=json.load(open(sys.argv[1])); assert c["max_abs"] <= 2e-5 and c["pixels_over_1_255"] == 0, c' \
  "$tmp/cs.json" || fail "single precision against the reference"
out=$("$zsweep" render --width 96 --height 80 --precision half -o "$tmp/h.exr" 2>&1); rc=$?
[ $rc -ne 0 ] || fail "--precision half accepted"
echo "$out" | grep -q -- "--precision" || fail "--precision half: message '$out'"
[ ! -e "$tmp/h.exr" ] || fail "output written for a bad --precision"

"$zsweep" bench accuracy default --sizes 64 --csv "$tmp/a.csv" --plots "$tmp/plots" >/dev/null 2>&1 \
  || fail "bench accuracy exited non-zero"
python3 - "$tmp/a.csv" <<'PY' || fail "accuracy CSV checks"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
by = {(r["group"], r["setting"]): r for r in rows}
assert len(rows) == 5 + 7 + 6 + 5 + 3, len(rows)
exact = float(by[("integrator", "exact")]["max_abs"])
assert exact <= 1e-5, exact
assert float(by[("integrator", "exact-single")]["max_abs"]) <= 2e-5, by[("integrator", "exact-single")]
for s in ("linear", "preintegrated", "taylor2"):
    assert float(by[("integrator", s)]["max_abs"]) > 10 * exact, s
assert float(by[("scan", "span")]["max_abs"]) == float(by[("scan", "bbox")]["max_abs"])
for t in (1, 2, 4, 8, 16):
    r = by[("early-termination", f"t={t}")]
    assert r["within_bound"] == "yes", r
for n in (256, 64, 16, 4):
    assert by[("max-list", f"max-list={n}")]["max_abs"] == by[("max-list", "max-list=0")]["max_abs"]
PY
for f in accuracy-default-64.png accuracy-rmse-default-64.png et-bound-default-64.png; do
  [ -s "$tmp/plots/$f" ] || fail "missing $f"
done
echo "accuracy: ok"
