#!/usr/bin/env bash
# A write that fails half way (here a file size limit, as a full disk would)
# gives one line that names the output, not its temporary, and says why;
# exit 1, and nothing left behind: images (EXR, TIFF, PNG), meshes (.off, .zsm,
# .vtu, TetGen .node/.ele, whose writer reports no errors of its own) and
# sphere files.
set -u
zsweep=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
cd "$tmp" || exit 1
"$zsweep" spheres generate c1 --count 20000 -o s.sph >/dev/null || fail "spheres generate"
"$zsweep" mesh generate box --tets 5000 -o box.off >/dev/null || fail "mesh generate"
limited() {  # limited KB CMD...: run with writes past KB kilobytes refused (EFBIG, not SIGXFSZ)
  local kb=$1; shift
  (trap '' XFSZ; ulimit -f "$kb"; "$@")
}
check() {  # check OUT KB CMD...
  local out=$1 kb=$2; shift 2
  limited "$kb" "$@" >stdout.txt 2>err.txt
  local rc=$?
  [ $rc -eq 1 ] || fail "$out: exit $rc (expected 1): $(cat err.txt)"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "$out: not one line: $(cat err.txt)"
  grep -q "^zsweep: error: $out: .*File too large$" err.txt || fail "$out: message: $(cat err.txt)"
  grep -q "zs-tmp" err.txt && fail "$out: names the temporary: $(cat err.txt)"
  local left
  left=$(ls | grep -E "zs-tmp|^$out\$|^${out%.*}\.(node|ele)\$")
  [ -z "$left" ] || fail "$out: left behind: $left"
}
for ext in exr tif png; do
  check "big.$ext" 64 "$zsweep" render -o "big.$ext" --width 1200 --height 1200 --threads 2
done
for ext in off zsm vtu node; do
  check "x.$ext" 4 "$zsweep" mesh convert box.off "x.$ext"
done
for ext in sph sphb; do
  check "y.$ext" 64 "$zsweep" spheres convert s.sph "y.$ext"
done
echo "write_errors: ok"
