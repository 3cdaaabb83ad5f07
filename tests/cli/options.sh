#!/usr/bin/env bash
# Options, table-driven (issue 38: items 7, 8, 11, 12, 14): every numeric
# option refuses a word, a fraction where it counts, and values out of range
# with readable bounds (exit 2); options that do not apply to the input are
# refused (exit 2) rather than ignored; an unknown array name lists the
# arrays; summaries say what was left out and which scalar was chosen.
set -u
zsweep=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cube="$src/tests/fuzz/corpus/off/cube_five.off"
sph="$src/tests/data/spheres/small.sph"
surf="$src/tests/data/surfaces/pyramid.obj"
pass=0; fail=0

# case NAME RC STDERR_REGEX STDOUT_REGEX -- ARGS...
# STDERR_REGEX '' means stderr must be empty, else it must be one line that
# matches; STDOUT_REGEX '' means stdout is not checked. No error leaves an output.
case_() {
  local name=$1 want_rc=$2 want_err=$3 want_out=$4; shift 5
  rm -f "$tmp"/o.*
  "$zsweep" "$@" >"$tmp/stdout" 2>"$tmp/stderr"; local rc=$?
  local err out; err=$(cat "$tmp/stderr"); out=$(cat "$tmp/stdout")
  if [[ $rc -ne $want_rc ]]; then echo "FAIL $name: exit $rc, want $want_rc ($err)"; ((fail++)); return; fi
  if [[ -z $want_err && -n $err ]] || [[ -n $want_err && ( $(grep -c '' "$tmp/stderr") -ne 1 || ! "$err" =~ $want_err ) ]]; then
    echo "FAIL $name:"; echo "  stderr: $err"; echo "  want:   ${want_err:-nothing}"; ((fail++)); return
  fi
  if [[ -n $want_out && ! "$out" =~ $want_out ]]; then
    echo "FAIL $name:"; echo "  stdout: $out"; echo "  want:   $want_out"; ((fail++)); return
  fi
  if [[ $rc -ne 0 ]] && compgen -G "$tmp/o.*" >/dev/null; then echo "FAIL $name: left an output file"; ((fail++)); return; fi
  ((pass++))
}
E='^zsweep: error: '
o="$tmp/o.png"

# Numbers: a word is not a number, a fraction not a whole number, and the
# bounds are written as people write them (not DBL_MAX in 300 digits).
case_ width_word 2 "$E--width: 'abc' is not a number \(see --help\)$" '' -- render --width abc -o "$o"
case_ width_fraction 2 "$E--width: '64.5' is not a whole number" '' -- render --width 64.5 -o "$o"
case_ width_zero 2 "$E--width: 0 is out of range: must be in \[1, 1048576\]" '' -- render --width 0 -o "$o"
case_ height_word 2 "$E--height: 'x' is not a number" '' -- render --height x -o "$o"
case_ threads_zero 2 "$E--threads: 0 is out of range: must be in \[1, 1024\]" '' -- render --threads 0 -o "$o"
case_ early_termination_negative 2 "$E--early-termination: -1 is out of range: must be in \[0, 255\]" '' -- \
  render "$cube" --early-termination -1 -o "$o"
case_ max_list_length_negative 2 "$E--max-list-length: -5 is out of range: must be in \[0, 4294967295\]" '' -- \
  render "$cube" --max-list-length -5 -o "$o"
case_ tile_size_big 2 "$E--tile-size: 5000 is out of range: must be in \[8, 4096\]" '' -- render --tile-size 5000 -o "$o"
case_ memory_budget_zero 2 "$E--memory-budget: 0 is out of range: must be positive and at most 1.7e\+13" '' -- \
  render --memory-budget 0 -o "$o"
case_ frames_zero 2 "$E--frames: 0 is out of range: must be in \[1, 100000\]" '' -- render --frames 0 -o "$o"
case_ reference_threads_word 2 "$E--threads: 'many' is not a number" '' -- reference --threads many -o "$tmp/o.exr"
case_ ao_samples_negative 2 "$E--ao-samples: -1 is out of range: must be in \[0, 1048576\]" '' -- \
  reference "$sph" --ao-samples -1 -o "$tmp/o.exr"
case_ count_zero 2 "$E--count: 0 is out of range: must be at least 1 \(see --help\)$" '' -- \
  spheres generate c1 --count 0 -o "$tmp/o.sph"
case_ seed_negative 2 "$E--seed: -1 is out of range: must be at least 0" '' -- spheres generate c1 --seed -1 -o "$tmp/o.sph"
case_ compare_scale_word 2 "$E--scale: 'abc' is not a number" '' -- compare "$cube" "$cube" --scale abc --diff "$o"
case_ compare_scale_without_diff 2 "$E--scale requires --diff" '' -- compare "$cube" "$cube" --scale 0.1
case_ zero_volume_eps_word 2 "$E--zero-volume-eps: 'tiny' is not a number" '' -- mesh info "$cube" --zero-volume-eps tiny

# Options that do not apply to the input: refused, not ignored.
case_ scalar_on_spheres 2 "$E$sph: --scalar applies to tet meshes only, and this is a sphere set$" '' -- \
  render "$sph" --scalar nosuch -o "$o"
case_ scalar_on_surface 2 "$E$surf: --scalar applies to tet meshes only, and this is a surface scene$" '' -- \
  render "$surf" --scalar nosuch -o "$o"
case_ integrator_on_spheres 2 "$E$sph: --integrator applies to tet meshes only, and this is a sphere set$" '' -- \
  render "$sph" --integrator exact -o "$o"
case_ early_termination_on_surface 2 "--early-termination applies to tet meshes only, and this is a surface scene$" '' -- \
  render "$surf" --early-termination 1 -o "$o"
case_ q_on_spheres 2 "$E$sph: --q applies to tet meshes only" '' -- render "$sph" --q "$cube" -o "$o"
case_ no_culling_on_volume 2 "$E$cube: --no-culling applies to sphere sets and surfaces only, and this is a tet mesh$" '' -- \
  render "$cube" --no-culling -o "$o"
case_ ao_samples_no_input 2 "${E}the default scene: --ao-samples applies to sphere sets only, and this is a tet mesh$" '' -- \
  reference --ao-samples 4 -o "$tmp/o.exr"
case_ ao_samples_without_ao 2 "$E$sph: --ao-samples needs a sphere scene with an 'ao' block$" '' -- \
  reference "$sph" --ao-samples 4 -o "$tmp/o.exr"
case_ variant_without_bconvert 2 "$E$cube: --variant applies to the bconvert scan, and the scan is span$" '' -- \
  render "$cube" --variant dilate -o "$o"
case_ precision_without_exact 2 "$E$cube: --precision applies to the exact integrator, and the integrator is linear$" '' -- \
  render "$cube" --integrator linear --precision single -o "$o"
case_ projection_with_camera 2 "${E}the default scene: --projection applies to the automatic camera, and this scene has its own$" '' -- \
  render --projection perspective -o "$o"
case_ scalar_no_input 2 "${E}the default scene: --scalar applies to a mesh file; this scene has none$" '' -- \
  render --scalar density -o "$o"
printf '{"mesh": "%s"}' "$cube" > "$tmp/scene.json"
case_ scalar_with_scene 2 "$E$tmp/scene.json: --scalar applies to a mesh file; a scene names it as mesh.scalar$" '' -- \
  render "$tmp/scene.json" --scalar density -o "$o"
case_ mesh_info_scalar_default 2 "$E--scalar applies to a mesh file, not the embedded default mesh$" '' -- mesh info --scalar x
case_ mesh_info_eps_spheres 2 "$E$sph: --zero-volume-eps applies to tet meshes only, and this is a sphere set$" '' -- \
  mesh info "$sph" --zero-volume-eps 0.1
case_ mesh_info_q_spheres 2 "$E$sph: --q applies to tet meshes only, and this is a sphere set$" '' -- mesh info "$sph" --q x
# Mesh files: a name that is not there lists what is; --q on a non-PLOT3D file.
case_ scalar_unknown_off 1 "$E$cube: no array named 'nosuch'; available: scalar \(point\)$" '' -- \
  render "$cube" --scalar nosuch -o "$o"
case_ scalar_unknown_convert 1 "$E$cube: no array named 'nosuch'; available: scalar \(point\)$" '' -- \
  mesh convert "$cube" --scalar nosuch "$tmp/o.vtu"
case_ q_on_off 2 "$E$cube: --q applies to PLOT3D grids only, and this is a .off mesh$" '' -- \
  render "$cube" --q "$cube" -o "$o"
case_ q_on_off_mesh_info 2 "$E$cube: --q applies to PLOT3D grids only, and this is a .off mesh$" '' -- \
  mesh info "$cube" --q "$cube"
printf '{"mesh": {"path": "%s", "q": "%s"}}' "$cube" "$cube" > "$tmp/q.json"
case_ q_in_scene_on_off 1 "$E$cube: a PLOT3D solution file \($cube\) applies to PLOT3D grids only, and this is a .off mesh$" '' -- \
  render "$tmp/q.json" -o "$o"
case_ scalar_named_ok 0 '' "^wrote $o: 16x16, " -- render "$cube" --scalar scalar --width 16 --height 16 -o "$o"
case_ variant_with_bconvert 0 '' "^wrote $o: " -- render "$cube" --scan bconvert --variant dilate --width 16 --height 16 -o "$o"

# Constant scalars: the first array that varies when none is named, said in
# the summary; a warning when the scalar is constant.
printf '# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nPOINT_DATA 4\nSCALARS Density double 1\nLOOKUP_TABLE default\n1 1 1 1\nSCALARS height double 1\nLOOKUP_TABLE default\n0 0 0 1\n' > "$tmp/const.vtk"
case_ constant_default_skipped 0 '' "; scalar 'height' \('Density' is constant \(1\)\)$" -- \
  render "$tmp/const.vtk" --width 16 --height 16 -o "$o"
case_ constant_named_warns 0 "^zsweep: warning: $tmp/const.vtk: scalar 'Density' is constant \(1\); every point gets the same colour and opacity$" \
  "^wrote $o: " -- render "$tmp/const.vtk" --scalar Density --width 16 --height 16 -o "$o"
printf '4 1\n0 0 0 2\n1 0 0 2\n0 1 0 2\n0 0 1 2\n0 1 2 3\n' > "$tmp/const.off"
case_ constant_off_warns 0 "^zsweep: warning: $tmp/const.off: scalar 'scalar' is constant \(2\), as is every other array" "^wrote " -- \
  render "$tmp/const.off" --width 16 --height 16 -o "$o"
shared=${ZSWEEP_SHARED:-$src/../shared/datasets}
if [[ -f $shared/postxyz.bin && -f $shared/postq.bin ]]; then
  case_ post_automatic_scalar 0 '' "; scalar 'Pressure' \('Density' is constant \(1\)\)$" -- \
    render "$shared/postxyz.bin" --q "$shared/postq.bin" --width 32 --height 32 -o "$o"
  case_ post_density_warns 0 "scalar 'Density' is constant \(1\); every point" "^wrote " -- \
    render "$shared/postxyz.bin" --q "$shared/postq.bin" --scalar density --width 32 --height 32 -o "$o"
else
  echo "note: $shared/postxyz.bin absent: the oxygen post cases are skipped"
fi

# Summaries say what was left out.
printf '0 0 0 1\nnan 0 0 1\n2 0 0 1\n' > "$tmp/nan.sph"
case_ nan_sphere_summary 0 '' "2 spheres drawn of 2, .*; left out: 1 sphere with a non-finite centre or a zero, negative or non-finite radius$" -- \
  render "$tmp/nan.sph" --width 16 --height 16 -o "$o"
printf '5 2\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 2\nnan 1 1 1\n0 1 2 3\n1 2 3 4\n' > "$tmp/nan.off"
case_ nan_tet_summary 0 "1 of 2 tets have a non-finite coordinate" "; left out: 1 tet with a non-finite coordinate or scalar$" -- \
  render "$tmp/nan.off" --width 16 --height 16 -o "$o"
case_ nan_tet_reference_summary 0 '' "; left out: 1 tet with a non-finite coordinate or scalar$" -- \
  reference "$tmp/nan.off" --width 16 --height 16 -o "$tmp/o.exr"
printf 'OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n2 0 3\n' > "$tmp/line.off"
case_ dropped_element_summary 0 '' "; left out: 1 element with fewer than three corners \(a line or point\)$" -- \
  render "$tmp/line.off" --width 16 --height 16 -o "$o"

# Memory: a tile larger than the image costs only the image's pixels.
case_ big_tile_small_image 0 '' "^wrote $o: 512x512, " -- \
  render --width 512 --height 512 --tile-size 4096 --memory-budget 200 -o "$o"

# Messages: directories and coincident points named as such.
mkdir -p "$tmp/d.json" "$tmp/d.png"
case_ scene_is_directory 1 "$E$tmp/d.json: is a directory, not a scene file$" '' -- render "$tmp/d.json" -o "$o"
case_ image_is_directory 1 "$E$tmp/d.png: is a directory, not an image$" '' -- compare "$tmp/d.png" "$tmp/d.png"
printf '4 1\n1 1 1 0\n1 1 1 1\n1 1 1 2\n1 1 1 3\n0 1 2 3\n' > "$tmp/same.off"
case_ coincident_points 1 "$E$tmp/same.off: all points coincide \(at 1, 1, 1\): nothing has an extent" '' -- \
  render "$tmp/same.off" -o "$o"

echo "options: $pass passed, $fail failed"
[[ $fail -eq 0 && $pass -ge 45 ]]
