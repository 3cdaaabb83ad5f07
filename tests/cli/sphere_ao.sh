#!/usr/bin/env bash
# Ambient occlusion in sphere scenes (`ao` block, docs/spheres.md): the EXR has
# an AO channel in [0, 1] on spheres and +inf elsewhere; colour = AO × the
# colour without AO; an isolated sphere has AO >= 0.99 over every pixel, and a
# sphere with close neighbours is darker where they are; the maps' AO is
# within 0.01 (mean) of the same directions traced exactly, which is close to a
# Monte Carlo AO; `reference --ao-samples` needs an ao scene; threads and tiles
# change no bit; maps built in batches (a small --memory-budget) change no
# bit, and every budget above the smallest that renders renders the same; `occluders: "alpha"` lets translucent neighbours pass light (lighter
# than opaque occluders, within 0.01 of the reference's exact transmittance);
# AO in the translucent modes (each fragment × its AO) is within 0.01 of the
# translucent reference; bad `ao` blocks fail in one line, naming the file,
# with no output. Skipped (77) without a python3 that has numpy and OpenImageIO.
set -u
zsweep=$1; src=$2
py=""
for c in /usr/bin/python3 python3; do
  if command -v "$c" >/dev/null && "$c" -c 'import numpy, OpenImageIO' 2>/dev/null; then py=$c; break; fi
done
[[ -n "$py" ]] || { echo "SKIP: no python3 with numpy and OpenImageIO"; exit 77; }
tmp=${KEEP_TMP:-$(mktemp -d)}; [[ -n "${KEEP_TMP:-}" ]] || trap 'rm -rf "$tmp"' EXIT
fail=0
printf '0 0 0 1\n' >"$tmp/one.sph"
# A sphere with six touching neighbours around its equator and one above.
{ echo "0 0 0 1"; for a in 0 60 120 180 240 300; do
    awk -v a="$a" 'BEGIN { t = a * 3.14159265358979 / 180; printf "%.9f 0 %.9f 0.9\n", 1.95 * cos(t), 1.95 * sin(t) }'
  done; echo "0 1.95 0 0.9"; } >"$tmp/crowd.sph"
scene() {  # name spheres ao-block [extra]
  printf '{"spheres": "%s", "image": {"width": 96, "height": 80}, "camera": {"projection": "perspective", "eye": [0.4, 3, 6], "target": [0, 0, 0], "fov_y": 40}%s%s}\n' \
    "$2" "${3:+, \"ao\": $3}" "${4:-}" >"$tmp/$1.json"
  echo "$tmp/$1.json"
}
run() { "$zsweep" render "$@" >/dev/null 2>"$tmp/err" || { echo "FAIL render $*: $(cat "$tmp/err")"; fail=1; }; }

run "$(scene one "$tmp/one.sph" '{"directions": 66, "map_size": 256}')" -o "$tmp/one.exr" --threads 2
run "$(scene crowd "$tmp/crowd.sph" '{"directions": 66, "map_size": 512}')" -o "$tmp/crowd.exr" --threads 2
run "$(scene crowd_imp "$tmp/crowd.sph" '{"directions": 18, "map_size": 512, "depth": "impostor"}')" -o "$tmp/crowd_imp.exr"
run "$(scene crowd_plain "$tmp/crowd.sph" '')" -o "$tmp/crowd_plain.exr"
# The references: the same 66 directions traced exactly (isolates the maps'
# error), and a cosine-weighted Monte Carlo AO (isolates the direction count's).
"$zsweep" reference "$tmp/crowd.json" -o "$tmp/crowd_ref.exr" >/dev/null 2>"$tmp/err" || { echo "FAIL reference: $(cat "$tmp/err")"; fail=1; }
"$zsweep" reference "$tmp/crowd.json" -o "$tmp/crowd_mc.exr" --ao-samples 1024 >/dev/null 2>"$tmp/err" \
  || { echo "FAIL reference --ao-samples: $(cat "$tmp/err")"; fail=1; }
# The same neighbours with RGBA colours, translucent (alpha 0.4 and 0.6).
{ echo "0 0 0 1 0.8 0.8 0.8 1"; for a in 0 60 120 180 240 300; do
    awk -v a="$a" 'BEGIN { t = a * 3.14159265358979 / 180; printf "%.9f 0 %.9f 0.9 0.5 0.7 0.9 0.4\n", 1.95 * cos(t), 1.95 * sin(t) }'
  done; echo "0 1.95 0 0.9 0.9 0.5 0.5 0.6"; } >"$tmp/tcrowd.sph"
for occ in opaque alpha; do
  for mode in opaque sorted; do
    f=$(scene "t_${occ}_$mode" "$tmp/tcrowd.sph" "{\"directions\": 66, \"map_size\": 512, \"occluders\": \"$occ\"}" \
      ", \"render\": {\"mode\": \"$mode\"}")
    run "$f" -o "$tmp/t_${occ}_$mode.exr" --threads 2
    "$zsweep" reference "$f" -o "$tmp/tr_${occ}_$mode.exr" >/dev/null 2>"$tmp/err" || { echo "FAIL reference $occ $mode: $(cat "$tmp/err")"; fail=1; }
  done
done
# Batches: 66 maps of 512² need ~70 MB; a 40 MiB budget holds a few at a time.
run "$tmp/crowd.json" -o "$tmp/crowd_batches.exr" --memory-budget 40 --stats "$tmp/batches.json"
for t in "1 64" "2 16" "3 33"; do
  set -- $t
  run "$tmp/crowd.json" -o "$tmp/crowd_t$1.exr" --threads "$1" --tile-size "$2"
done
"$py" - "$tmp" <<'PY' || fail=1
import sys, numpy as np, OpenImageIO as oiio
d = sys.argv[1]
def read(n):
    i = oiio.ImageInput.open(f"{sys.argv[1]}/{n}.exr")
    names = list(i.spec().channelnames)
    a = i.read_image("float")
    i.close()
    return names, a
bad = 0
names, one = read("one")
if names != ["R", "G", "B", "A", "Z", "AO"]:
    print("FAIL channels", names); bad = 1
ao = one[..., 5]
on = one[..., 3] > 0
if not (np.all(np.isinf(ao[~on])) and on.sum() > 500):
    print("FAIL AO must be +inf off the sphere", on.sum()); bad = 1
if ao[on].min() < 0.99:
    print("FAIL isolated sphere AO min", ao[on].min()); bad = 1
_, crowd = read("crowd")
_, imp = read("crowd_imp")
_, plain = read("crowd_plain")
a = crowd[..., 5]
on = crowd[..., 3] > 0
if not (0 <= a[on].min() and a[on].max() <= 1 and a[on].min() < 0.6 and a[on].max() > 0.9):
    print("FAIL crowd AO range", a[on].min(), a[on].max()); bad = 1
if np.abs(imp[..., 5][on] - a[on]).mean() > 0.1:
    print("FAIL impostor and disc maps disagree", np.abs(imp[..., 5][on] - a[on]).mean()); bad = 1
for t in (1, 2, 3):  # every channel, bit for bit
    _, other = read(f"crowd_t{t}")
    if not np.array_equal(other.view(np.uint32), crowd.view(np.uint32)):
        print("FAIL threads/tiles change the image", t); bad = 1
names, ref = read("crowd_ref")
_, mc = read("crowd_mc")
if names[-1] != "AO" or not np.array_equal(ref[..., 3] > 0, on):
    print("FAIL reference coverage or channels", names); bad = 1
else:
    d = np.abs(a[on] - ref[..., 5][on])
    if not (d.mean() < 0.01 and d.max() < 0.25):
        print("FAIL maps vs exact directions", d.mean(), d.max()); bad = 1
    m = np.abs(ref[..., 5][on] - mc[..., 5][on])
    if not (m.mean() < 0.06 and ref[..., 5][on].min() < 0.6):
        print("FAIL 66 directions vs Monte Carlo", m.mean()); bad = 1
_, batches = read("crowd_batches")
if not np.array_equal(batches.view(np.uint32), crowd.view(np.uint32)):
    print("FAIL maps in batches change the image"); bad = 1
import json
st = json.load(open(f"{sys.argv[1]}/batches.json"))["ao"]
if not st["batches"] > 1:
    print("FAIL the small budget did not give batches", st); bad = 1
# Translucent occluders and AO in translucent modes, against the reference.
aos = {}
for occ in ("opaque", "alpha"):
    for mode in ("opaque", "sorted"):
        names, img = read(f"t_{occ}_{mode}")
        _, ref = read(f"tr_{occ}_{mode}")
        on = np.isfinite(img[..., 5])
        if names[-1] != "AO" or not np.array_equal(on, np.isfinite(ref[..., 5])):
            print("FAIL AO coverage", occ, mode, names); bad = 1
            continue
        dd = np.abs(img[..., 5][on] - ref[..., 5][on])
        if not dd.mean() < 0.01:
            print("FAIL maps vs exact", occ, mode, dd.mean()); bad = 1
        c = np.abs(img[..., :4] - ref[..., :4])
        if not c.mean() < 0.01:
            print("FAIL colour vs reference", occ, mode, c.mean()); bad = 1
        aos[occ, mode] = img[..., 5][on].mean()
if aos and not aos["alpha", "opaque"] > aos["opaque", "opaque"] + 0.02:
    print("FAIL translucent occluders must pass light", aos); bad = 1
# Colour = AO x the colour without AO (float rounding only).
err = np.abs(crowd[..., :3][on] - a[on][:, None] * plain[..., :3][on]).max()
if err > 1e-6:
    print("FAIL colour is not AO x shaded colour", err); bad = 1
sys.exit(bad)
PY

# Every budget from the smallest that renders up renders too, and the same
# image: the maps are held when they fit beside the frame's own set-up (the
# visible list, the bins), else built in batches; never a budget error
# between the two (1hpv at 200x160, 18 maps of 256²: 5 MiB once failed
# although 4 MiB rendered). Needs pymol-data's 1hpv.
pdb=/usr/share/pymol/data/tut/1hpv.pdb
if [[ -f $pdb ]]; then
  printf '{"spheres": "%s", "image": {"width": 200, "height": 160}, "ao": {"directions": 18, "map_size": 256}}\n' \
    "$pdb" >"$tmp/hpv.json"
  run "$tmp/hpv.json" -o "$tmp/hpv.exr"
  first=""
  for b in $(seq 2 1 12); do
    if "$zsweep" render "$tmp/hpv.json" -o "$tmp/b$b.exr" --memory-budget "$b" >/dev/null 2>"$tmp/err"; then
      [[ -z "$first" ]] && first=$b
      "$zsweep" compare "$tmp/hpv.exr" "$tmp/b$b.exr" 2>&1 | grep -q "^max abs 0 " \
        || { echo "FAIL --memory-budget $b changes the image"; fail=1; }
    elif [[ -n "$first" ]]; then
      echo "FAIL --memory-budget $b fails although $first rendered: $(cat "$tmp/err")"; fail=1
    fi
  done
  [[ -n "$first" ]] || { echo "FAIL no budget up to 12 MiB renders 1hpv with AO"; fail=1; }
else
  echo "note: no $pdb (pymol-data); the budget sweep is left out"
fi

# Bad ao blocks: one line naming the file, non-zero exit, no output.
bad() {  # name spheres ao-block extra expected-text
  local f; f=$(scene "$1" "$2" "$3" "${4:-}")
  rm -f "$tmp/bad.png"
  if "$zsweep" render "$f" -o "$tmp/bad.png" >/dev/null 2>"$tmp/err"; then echo "FAIL $1 accepted"; fail=1; return; fi
  [[ $(wc -l <"$tmp/err") -eq 1 ]] && grep -q "$f" "$tmp/err" && grep -q "$5" "$tmp/err" \
    || { echo "FAIL $1 message: $(cat "$tmp/err")"; fail=1; }
  [[ -e "$tmp/bad.png" ]] && { echo "FAIL $1 left an output"; fail=1; }
}
bad dirs "$tmp/one.sph" '{"directions": 64}' '' "ao.directions must be 6, 18, 66"
bad size "$tmp/one.sph" '{"map_size": 4}' '' "ao.map_size"
bad biasneg "$tmp/one.sph" '{"bias": -1}' '' "ao.bias"
bad depth "$tmp/one.sph" '{"depth": "exact"}' '' "ao.depth"
bad occ "$tmp/one.sph" '{"occluders": "glass"}' '' 'ao.occluders must be'
bad key "$tmp/one.sph" '{"radius": 3}' '' "unknown key 'ao.radius'"
# Translucent modes need every map at once: a budget too small for them fails.
f=$(scene bigmaps "$tmp/one.sph" '{"directions": 66, "map_size": 1024}' ', "render": {"mode": "sorted"}')
"$zsweep" render "$f" -o "$tmp/bad.png" --memory-budget 64 >/dev/null 2>"$tmp/err" && { echo "FAIL sorted AO over budget accepted"; fail=1; }
grep -q 'needs every AO map in memory' "$tmp/err" || { echo "FAIL sorted AO budget message: $(cat "$tmp/err")"; fail=1; }
[[ -e "$tmp/bad.png" ]] && { echo "FAIL sorted AO over budget left an output"; fail=1; }
printf '{"mesh": "%s", "ao": {"directions": 6}}\n' "$src/tests/data/ok/no_final_newline.off" >"$tmp/vol.json"
"$zsweep" render "$tmp/vol.json" -o "$tmp/bad.png" >/dev/null 2>"$tmp/err" && { echo "FAIL ao in a volume scene accepted"; fail=1; }
grep -q "'ao' is for sphere scenes" "$tmp/err" || { echo "FAIL volume ao message: $(cat "$tmp/err")"; fail=1; }
"$zsweep" reference "$tmp/one.json" -o "$tmp/ref.exr" --ao-samples 4 >/dev/null 2>&1 || { echo "FAIL reference --ao-samples"; fail=1; }
"$zsweep" reference "$tmp/crowd_plain.json" -o "$tmp/ref.exr" --ao-samples 4 >/dev/null 2>"$tmp/err" \
  && { echo "FAIL --ao-samples without ao accepted"; fail=1; }
grep -q "needs a sphere scene with an 'ao' block" "$tmp/err" || { echo "FAIL --ao-samples message: $(cat "$tmp/err")"; fail=1; }
[[ $fail -eq 0 ]] && echo "sphere_ao: all checks passed"
exit $fail
