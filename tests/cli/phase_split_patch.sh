#!/usr/bin/env bash
# scripts/phase-split measures the engine with scripts/phase-split.patch
# applied; the patch must still apply to the sources it patches, or the
# measurement tool has rotted (docs/performance.md, seventh round).
set -u
src=$2
patch=$src/scripts/phase-split.patch
[ -f "$patch" ] || { echo "FAIL: $patch missing"; exit 1; }
command -v git >/dev/null || { echo "SKIP: no git"; exit 77; }
# Against the working files (git apply works outside a repository too).
if (cd "$src" && git apply --check "$patch"); then
  echo "phase-split.patch: applies"
else
  echo "FAIL: scripts/phase-split.patch no longer applies to src/render/volume/{compositor.h,tile_sweep.cpp}; regenerate it"
  exit 1
fi
