#!/usr/bin/env bash
# spx.off -> .vtu -> .off keeps every count `mesh info` reports, and the
# final .off is byte-identical to writing spx.off directly.
set -u
zsweep=$1; src=$2
spx="${ZSWEEP_SHARED:-$src/../shared/datasets}/spx.off"
[ -f "$spx" ] || { echo "SKIP: $spx not found (shared datasets absent)"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
counts() { "$zsweep" mesh info "$1" | grep -E '^(points|tets|faces|boundary faces|orientation|zero-volume tets):'; }
counts "$spx" > "$tmp/a.txt" || fail=1
grep -qx 'points: *2896' "$tmp/a.txt" || { echo "FAIL: spx points"; fail=1; }
grep -qx 'tets: *12936' "$tmp/a.txt" || { echo "FAIL: spx tets"; fail=1; }
grep -qx 'faces: *27252' "$tmp/a.txt" || { echo "FAIL: spx faces"; fail=1; }
grep -qx 'boundary faces: *2760' "$tmp/a.txt" || { echo "FAIL: spx boundary faces"; fail=1; }
grep -q '12 positive, 12924 negative' "$tmp/a.txt" || { echo "FAIL: spx orientation split"; fail=1; }
"$zsweep" mesh convert "$spx" "$tmp/spx.vtu" >/dev/null || fail=1
"$zsweep" mesh convert "$tmp/spx.vtu" "$tmp/back.off" >/dev/null || fail=1
"$zsweep" mesh convert "$spx" "$tmp/direct.off" >/dev/null || fail=1
for f in spx.vtu back.off; do
  counts "$tmp/$f" > "$tmp/b.txt" || fail=1
  diff "$tmp/a.txt" "$tmp/b.txt" || { echo "FAIL: counts differ after round trip via $f"; fail=1; }
done
cmp -s "$tmp/back.off" "$tmp/direct.off" || { echo "FAIL: .off via .vtu differs from direct .off"; fail=1; }
cat "$tmp/a.txt"
[ $fail -eq 0 ] && echo "spx round trip: 1 passed, 0 failed" || echo "spx round trip: 0 passed, 1 failed"
exit $fail
