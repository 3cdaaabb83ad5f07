#!/usr/bin/env bash
# .zsm through the command line: `mesh generate -o X.zsm` writes the mesh that
# `-o X.off` writes, and keeps the scalar's name (.off has none); .off -> .zsm
# -> .off gives the same text; `mesh info` reports the same mesh; `render` of
# the .zsm, directly and as a scene's mesh, gives the image of the .off; a
# bad .zsm is one line naming it.
set -u
zsweep=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
cd "$tmp" || exit 1
"$zsweep" mesh generate blob --tets 3000 --seed 3 -o g.off >/dev/null || { echo "FAIL: generate .off"; exit 1; }
"$zsweep" mesh generate blob --tets 3000 --seed 3 -o g.zsm >/dev/null || { echo "FAIL: generate .zsm"; exit 1; }
"$zsweep" mesh convert g.zsm from_zsm.off >/dev/null || fail=1
cmp -s from_zsm.off g.off || { echo "FAIL: generate -o .zsm differs from -o .off"; fail=1; }
"$zsweep" mesh convert g.off c.zsm >/dev/null || fail=1
"$zsweep" mesh convert c.zsm back.off >/dev/null || fail=1
cmp -s back.off g.off || { echo "FAIL: .off -> .zsm -> .off changed the text"; fail=1; }
info() {  # mesh info without the file's name, the timing and the scalar's name
  "$zsweep" mesh info "$1" | grep -vE '^(mesh|topology \+ validation):' | sed 's/^scalar: *[a-z]*,/scalar: NAME,/'
}
info g.off > a.txt; info g.zsm > b.txt
diff a.txt b.txt >/dev/null || { echo "FAIL: mesh info differs:"; diff a.txt b.txt; fail=1; }
grep -q '^tets:' b.txt || { echo "FAIL: mesh info g.zsm printed no tet count"; fail=1; }
"$zsweep" mesh info g.zsm | grep -q '^scalar: *radial, ' || { echo "FAIL: g.zsm lost the scalar's name"; fail=1; }
"$zsweep" render g.off -o off.png --width 64 --height 48 >/dev/null || fail=1
"$zsweep" render g.zsm -o zsm.png --width 64 --height 48 >/dev/null || fail=1
cmp -s off.png zsm.png || { echo "FAIL: render g.zsm differs from render g.off"; fail=1; }
printf '{"mesh": "%s", "image": {"width": 64, "height": 48}}' "$tmp/g.zsm" > scene.json
"$zsweep" render scene.json -o scene.png >/dev/null || fail=1
cmp -s off.png scene.png || { echo "FAIL: a scene with mesh g.zsm renders unlike g.off"; fail=1; }
head -c 300 g.zsm > cut.zsm
"$zsweep" mesh info cut.zsm >out.txt 2>err.txt; rc=$?
[ $rc -eq 1 ] && [ "$(wc -l <err.txt)" -eq 1 ] && [ ! -s out.txt ] \
  && grep -q '^zsweep: error: cut.zsm: truncated: ' err.txt \
  || { echo "FAIL: truncated .zsm: exit $rc: $(cat err.txt)"; fail=1; }
[ $fail -eq 0 ] && echo "zsm round trip: ok"
exit $fail
