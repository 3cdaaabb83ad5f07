#!/usr/bin/env bash
# `zsweep render` streams tiles into the output: EXR, TIFF and PNG of the
# embedded default scene agree with each other and with another tile size,
# a budget smaller than the float image still renders the same image, and a
# budget too small for the engine gives one line and no file.
set -u
zsweep=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
W=1000; H=700
render() {  # render NAME ARGS...: output $tmp/NAME, stats $tmp/NAME.json, summary line $tmp/NAME.txt
  local name=$1; shift
  "$zsweep" render --width $W --height $H --threads 2 -o "$tmp/$name" --stats "$tmp/$name.json" "$@" \
    >"$tmp/$name.txt" 2>"$tmp/$name.err" || fail "render $name $*: $(cat "$tmp/$name.err")"
}
render t64.exr --tile-size 64
render t64.tif --tile-size 64
render t64.png --tile-size 64
render t256.exr --tile-size 256
render zip.exr --compression zip
render piz.exr --compression piz
render lzw.tif --compression lzw
# 1000x700 float RGBA is 10.7 MiB: the image cannot be held, tiles stream.
render small.exr --memory-budget 6
render small.png --memory-budget 6

grep -Eq "^wrote $tmp/t64.exr: ${W}x${H}, [0-9]+ fragments, [0-9]+ rendered pixels, [0-9.]+ ms$" "$tmp/t64.exr.txt" \
  || fail "summary line: $(cat "$tmp/t64.exr.txt")"
cmp_json() { "$zsweep" compare "$tmp/$1" "$tmp/$2" --json > "$tmp/$1-$2.cmp" || fail "compare $1 $2"; }
cmp_json t64.exr t64.tif
cmp_json t64.exr t256.exr
cmp_json t64.exr zip.exr
cmp_json t64.exr piz.exr
cmp_json t64.exr lzw.tif
cmp_json t64.exr small.exr
cmp_json t64.png t64.exr
cmp_json t64.png small.png
python3 - "$tmp" $W $H <<'PY' || fail "checks"
import json, sys
d, W, H = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
c = lambda a, b: json.load(open(f"{d}/{a}-{b}.cmp"))
for a, b in (("t64.exr", "t64.tif"), ("t64.exr", "t256.exr"), ("t64.exr", "small.exr"), ("t64.png", "small.png"),
             ("t64.exr", "zip.exr"), ("t64.exr", "piz.exr"), ("t64.exr", "lzw.tif")):
    assert c(a, b)["max_abs"] == 0, (a, b, c(a, b))
# PNG is the same values quantized to 8 bits (round to nearest).
q = c("t64.png", "t64.exr")
assert q["max_abs"] <= 0.5 / 255 + 1e-6 and q["pixels_over_1_255"] == 0, q
st = {n: json.load(open(f"{d}/{n}.json")) for n in ("t64.exr", "t256.exr", "small.exr")}
for n, s in st.items():
    assert s["image"] == {"width": W, "height": H}, (n, s["image"])
    for k in ("time_ms", "fragments", "rendered_pixels", "peak_rss_bytes", "memory_budget_bytes", "tiles", "tile_size"):
        assert k in s, (n, k)
assert st["t64.exr"]["tile_size"] == 64 and st["t64.exr"]["tiles"] == 16 * 11, st["t64.exr"]
assert st["t256.exr"]["tile_size"] == 256 and st["t256.exr"]["tiles"] == 4 * 3, st["t256.exr"]
assert st["t64.exr"]["fragments"] == st["t256.exr"]["fragments"] == st["small.exr"]["fragments"]
assert st["small.exr"]["memory_budget_bytes"] == 6 << 20, st["small.exr"]
assert st["t64.exr"]["rendered_pixels"] > 10000
print(f"peak RSS: default budget {st['t64.exr']['peak_rss_bytes'] >> 20} MiB, "
      f"6 MiB budget {st['small.exr']['peak_rss_bytes'] >> 20} MiB (informative)")
PY

# Too small for the engine's shared state: its one-line error, exit 1, no file.
for ext in exr png; do
  out=$("$zsweep" render --width $W --height $H -o "$tmp/never.$ext" --memory-budget 0.5 2>&1 >/dev/null); rc=$?
  [ $rc -eq 1 ] || fail "tiny budget ($ext): exit $rc"
  [ "$(echo "$out" | wc -l)" -eq 1 ] || fail "tiny budget ($ext): more than one line: $out"
  echo "$out" | grep -q "^zsweep: error: memory budget of .* cannot hold" || fail "tiny budget ($ext): '$out'"
  compgen -G "$tmp/never*" >/dev/null && fail "tiny budget ($ext) left a file: $(ls "$tmp")"
done
# An unwritable output fails before rendering, naming the file.
out=$("$zsweep" render --width 64 --height 64 -o "$tmp/no/such/dir/x.exr" 2>&1 >/dev/null) && fail "unwritable output succeeded"
echo "$out" | grep -q "$tmp/no/such/dir/x.exr" || fail "unwritable output: '$out'"
"$zsweep" render --tile-size 4 -o "$tmp/bad.exr" >/dev/null 2>&1 && fail "--tile-size 4 accepted"
# Compression: the default EXR codec is RLE (lossless, fast); a name the
# format does not offer, or any name for PNG, is one line naming the file.
python3 - "$tmp" <<'PY' || fail "EXR compression attributes"
import struct, sys
def compression(path):  # the header's "compression" attribute (OpenEXR file layout)
    b = open(path, "rb").read(4096)
    i = 8  # magic, version
    while b[i] != 0:
        name_end = b.index(0, i); typ_end = b.index(0, name_end + 1)
        size = struct.unpack_from("<i", b, typ_end + 1)[0]
        if b[i:name_end] == b"compression":
            return b[typ_end + 5]
        i = typ_end + 5 + size
    return None
d = sys.argv[1]
got = {n: compression(f"{d}/{n}") for n in ("t64.exr", "zip.exr", "piz.exr")}
assert got == {"t64.exr": 1, "zip.exr": 3, "piz.exr": 4}, got  # RLE default, ZIP, PIZ
PY
for bad in "exr --compression lzw" "png --compression zip"; do
  set -- $bad
  out=$("$zsweep" render --width 64 --height 64 -o "$tmp/c.$1" $2 $3 2>&1 >/dev/null); rc=$?
  [ $rc -eq 1 ] || fail "compression $bad: exit $rc"
  [ "$(echo "$out" | wc -l)" -eq 1 ] || fail "compression $bad: more than one line: $out"
  echo "$out" | grep -q "$tmp/c.$1" || fail "compression $bad: '$out'"
  [ -e "$tmp/c.$1" ] && fail "compression $bad left a file"
done
echo "render tiled: ok"
