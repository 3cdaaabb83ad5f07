#!/usr/bin/env bash
# `zsweep bench scan` on a small generated mesh: the CSV has every column,
# span equals the bounding box exactly, B-Convert's hits are a subset, and the
# plots and tables are written.
set -u
zsweep=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; echo "bench scan: 0 passed, 1 failed"; exit 1; }
"$zsweep" mesh generate blob --tets 3000 --seed 3 -o "$tmp/blob.off" >/dev/null || fail "generate"
"$zsweep" bench scan "$tmp/blob.off" --sizes 64,128,256 --raster-only-above 128 \
  --variants truncate,round,dilate,dda3d,runlength --csv "$tmp/b.csv" --plots "$tmp/plots" 2>/dev/null >/dev/null \
  || fail "bench scan exited non-zero"
head -1 "$tmp/b.csv" | grep -q '^mesh,size,strategy,variant,list_generation_ms,scan_convert_ms,total_ms,pixel_tests,pixel_hits,pixel_misses,missing_pixels,rendered_pixels,image_max_abs_diff,face_to_bbox_area_ratio' \
  || fail "CSV header"
[ "$(tail -n +2 "$tmp/b.csv" | wc -l)" -eq 21 ] || fail "expected 21 rows (3 sizes x 7 strategies/variants)"
python3 - "$tmp/b.csv" <<'PY' || fail "CSV checks"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
by = {(r["size"], r["strategy"], r["variant"]): r for r in rows}
for size in ("64", "128", "256"):
    bbox = by[(size, "bbox", "-")]
    span = by[(size, "span", "-")]
    assert span["pixel_hits"] == bbox["pixel_hits"], ("span hits", size)
    assert span["missing_pixels"] == "0"
    assert int(span["pixel_tests"]) < int(bbox["pixel_tests"])
    if size != "256":
        assert float(span["image_max_abs_diff"]) == 0.0, "span image differs"
        assert int(bbox["rendered_pixels"]) > 0
    for v in ("truncate", "round", "dilate", "dda3d", "runlength"):
        b = by[(size, "bconvert", v)]
        assert int(b["pixel_hits"]) + int(b["missing_pixels"]) == int(bbox["pixel_hits"]), v
        # B-Convert tests fewer candidates than the box (the point of it);
        # dilation widens every row by two pixels, so small faces may not.
        if v != "dilate":
            assert int(b["pixel_tests"]) < int(bbox["pixel_tests"]), v
    assert by[(size, "bconvert", "runlength")]["pixel_hits"] == by[(size, "bconvert", "truncate")]["pixel_hits"]
    assert int(by[(size, "bconvert", "round")]["missing_pixels"]) <= int(by[(size, "bconvert", "truncate")]["missing_pixels"])
print("csv ok")
PY
for f in tables.md blob-time.png; do [ -s "$tmp/plots/$f" ] || fail "missing $f"; done
grep -q 'Table 4.10 analogue' "$tmp/plots/tables.md" || fail "tables.md lacks Table 4.10"
# Merging runs: the CSV reads back into the same tables.
"$zsweep" bench report "$tmp/b.csv" "$tmp/b.csv" --plots "$tmp/merged" >/dev/null || fail "bench report"
[ -s "$tmp/merged/tables.md" ] && [ -s "$tmp/merged/blob-time.png" ] || fail "bench report outputs"
"$zsweep" bench report "$tmp/blob.off" --plots "$tmp/x" >/dev/null 2>&1 && fail "bench report accepted a non-CSV"
echo "bench scan: 1 passed, 0 failed"
