#!/usr/bin/env bash
# tests/project/layers.py finds what it must: a tiny tree with one broken
# rule of each kind fails with each named, and the same tree without them
# passes. Usage: layers_selftest.sh SOURCE_DIR
set -u
src=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mk() { mkdir -p "$(dirname "$tmp/src/$1")"; printf '%s\n' "${@:2}" > "$tmp/src/$1"; }
mk base/util/a.h '#pragma once'
mk raster/r.h '#include "base/util/a.h"'
mk geometry/tets/t.h '#include "base/util/a.h"'
mk render/frame_settings.h '#include "base/util/a.h"'
mk render/volume/v.h '#include "render/frame_settings.h"' '#include "raster/r.h"'
mk render/spheres/s.h '#include "geometry/tets/t.h"'
mk scene/sc.h '#include "render/volume/v.h"'
python3 "$src/tests/project/layers.py" "$tmp/src" >"$tmp/ok.log" || { echo "FAIL: a clean tree fails"; cat "$tmp/ok.log"; exit 1; }
mk render/spheres/s.h '#include "render/volume/v.h"'
mk raster/r.h '#include "geometry/tets/t.h"'
mk base/util/a.h '#include "scene/sc.h"'
mk surfaces/x.h '#pragma once'
mk lighting/r.h '#pragma once'
if python3 "$src/tests/project/layers.py" "$tmp/src" >"$tmp/bad.log"; then echo "FAIL: a broken tree passes"; exit 1; fi
fail=0
for want in "renderers never include one another" "raster and geometry are independent" "runs up the layers" \
            "surfaces/ is not a role folder" "a second header named r.h"; do
  grep -q "$want" "$tmp/bad.log" || { echo "FAIL: not reported: $want"; fail=1; }
done
[[ $fail == 0 ]] && echo "ok: every broken rule reported"
exit $fail
