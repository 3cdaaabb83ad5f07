#!/usr/bin/env bash
# Cell data through the command line, on kiefer.vtu (von Mises stress per
# cell): rendered per tet by default and averaged with --association
# cell_to_point (another image); the same from a scene's mesh.association
# and from the .zsm that `mesh convert` writes (cell data kept); mesh info
# and --stats say it; an association the array does not have is one line
# naming the file, and no image.
set -u
zsweep=$1
shared=${ZSWEEP_SHARED:-$(dirname "$0")/../../../shared/datasets}
kiefer=$shared/kiefer.vtu
[ -f "$kiefer" ] || { echo "SKIP: $kiefer is absent (../shared/datasets)"; exit 77; }
kiefer=$(cd "$(dirname "$kiefer")" && pwd)/kiefer.vtu
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
cd "$tmp" || exit 1
size=(--width 64 --height 48)
"$zsweep" render "$kiefer" "${size[@]}" -o cell.png --stats cell.json >/dev/null || { echo "FAIL: render"; exit 1; }
grep -q '"association": *"cell"' cell.json || { echo "FAIL: --stats does not say cell data"; fail=1; }
grep -qE '"cell_data_tets": *[1-9]' cell.json || { echo "FAIL: --stats counts no cell-data tets"; fail=1; }
"$zsweep" render "$kiefer" "${size[@]}" --association cell_to_point -o avg.png --stats avg.json >/dev/null || fail=1
grep -q '"cell_data_tets": *0' avg.json || { echo "FAIL: averaged render counts cell-data tets"; fail=1; }
cmp -s cell.png avg.png && { echo "FAIL: cell data and their average render alike"; fail=1; }
printf '{"mesh": {"path": "%s", "association": "cell_to_point"}, "image": {"width": 64, "height": 48}}' \
  "$kiefer" > avg_scene.json
"$zsweep" render avg_scene.json -o avg_scene.png >/dev/null || fail=1
cmp -s avg.png avg_scene.png || { echo "FAIL: mesh.association differs from --association"; fail=1; }
"$zsweep" mesh convert "$kiefer" k.zsm >/dev/null || fail=1
"$zsweep" render k.zsm "${size[@]}" -o zsm.png >/dev/null || fail=1
cmp -s cell.png zsm.png || { echo "FAIL: the .zsm's cell data render unlike the .vtu's"; fail=1; }
"$zsweep" render k.zsm "${size[@]}" --association cell_to_point -o zsm_avg.png >/dev/null || fail=1
cmp -s cell.png zsm_avg.png && { echo "FAIL: the .zsm's cell data were not averaged"; fail=1; }
"$zsweep" mesh info k.zsm | grep -q '^scalar: .*(cell data: one value per tet), range' \
  || { echo "FAIL: mesh info k.zsm does not say cell data"; fail=1; }
"$zsweep" render "$kiefer" "${size[@]}" --association point -o bad.png >out.txt 2>err.txt; rc=$?
[ $rc -eq 1 ] && [ "$(wc -l <err.txt)" -eq 1 ] && [ ! -e bad.png ] && grep -qE "kiefer.vtu: no point data array .association is .point.." err.txt \
  || { echo "FAIL: --association point on cell data: exit $rc: $(cat err.txt)"; fail=1; }
"$zsweep" render "$kiefer" "${size[@]}" --association cells -o bad.png >out.txt 2>err.txt; rc=$?
[ $rc -eq 2 ] && [ ! -e bad.png ] && grep -q "association must be" err.txt \
  || { echo "FAIL: --association cells: exit $rc: $(cat err.txt)"; fail=1; }
"$zsweep" render avg_scene.json --association cell -o bad.png >out.txt 2>err.txt; rc=$?
[ $rc -eq 2 ] && grep -q "applies to a mesh file" err.txt \
  || { echo "FAIL: --association with a scene: exit $rc: $(cat err.txt)"; fail=1; }
[ $fail -eq 0 ] && echo "cell data: ok"
exit $fail
