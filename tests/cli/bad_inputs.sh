#!/usr/bin/env bash
# Bad input at the command line and in scenes: each case checks the exit code,
# the one error (or warning) line on stderr, and the output file: none for an
# error (not even a temporary), the image for a warning.
set -u
zsweep=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cube="$src/tests/fuzz/corpus/off/cube_five.off"
pass=0; fail=0

# expect NAME RC STDERR_REGEX OUTPUT -- ARGS...
# OUTPUT: +path must exist afterwards (it is then removed), -path must not
# (nor any temporary beside it), =path is not checked.
expect() {
  local name=$1 want_rc=$2 want_err=$3 out=$4; shift 5
  "$zsweep" "$@" >"$tmp/stdout" 2>"$tmp/stderr"; local rc=$?
  local err; err=$(cat "$tmp/stderr")
  local lines; lines=$(grep -c '' "$tmp/stderr")
  if [[ $rc -ne $want_rc ]]; then echo "FAIL $name: exit $rc, want $want_rc ($err)"; ((fail++)); return; fi
  if [[ $lines -ne 1 || ! "$err" =~ $want_err ]]; then
    echo "FAIL $name:"; echo "  got:  $err"; echo "  want: $want_err (one line)"; ((fail++)); return
  fi
  local path=${out:1}
  if [[ $out == -* ]] && { [[ -e "$path" ]] || compgen -G "$(dirname "$path")/*.zs-tmp-*" >/dev/null; }; then
    echo "FAIL $name: left an output file"; ((fail++)); return
  fi
  if [[ $out == +* && ! -s "$path" ]]; then echo "FAIL $name: no output file"; ((fail++)); return; fi
  [[ $out == +* ]] && rm -f "$path"
  ((pass++))
}
scene() { printf '%s' "$2" > "$tmp/$1.json"; echo "$tmp/$1.json"; }

# Images of zero size, or too large for the budget or the format: refused
# before anything large is allocated (these would need gigabytes).
expect zero_width 2 '^zsweep: error: --width: 0 is out of range: must be in \[1, 1048576\] \(see --help\)$' -"$tmp/o.png" -- \
  render --width 0 -o "$tmp/o.png"
expect zero_width_scene 1 'image.width must be an integer from 1 to 1048576$' -"$tmp/o.png" -- \
  render "$(scene zw '{"mesh": "'"$cube"'", "image": {"width": 0}}')" -o "$tmp/o.png"
expect over_budget_exr 1 '^zsweep: error: memory budget of 64.0 MiB cannot hold a 1048576x1048576 render of this mesh' \
  -"$tmp/o.exr" -- render --width 1048576 --height 1048576 --memory-budget 64 -o "$tmp/o.exr"
expect png_too_wide 1 "^zsweep: error: $tmp/o.png: PNG is limited to 1000000 pixels per side" -"$tmp/o.png" -- \
  render --width 1048576 --height 8 -o "$tmp/o.png"
expect too_many_tiles 1 'in 8-pixel tiles is too many tiles; use a larger tile size$' -"$tmp/o.exr" -- \
  render --width 1048576 --height 1048576 --tile-size 8 -o "$tmp/o.exr"
expect reference_over_budget 1 "cannot hold the reference's 1048576x1048576 float image" -"$tmp/o.exr" -- \
  reference --width 1048576 --height 1048576 -o "$tmp/o.exr"

# Unreadable and unwritable paths.
expect missing_mesh 1 "^zsweep: error: $tmp/none.off: (no such file|cannot open)" -"$tmp/o.png" -- \
  render "$tmp/none.off" -o "$tmp/o.png"
expect mesh_is_dir 1 "^zsweep: error: $tmp: is a directory, not a mesh file$" -"$tmp/o.png" -- render "$tmp" -o "$tmp/o.png"
expect out_no_dir 1 "^zsweep: error: $tmp/no/o.png: cannot write: No such file or directory$" -"$tmp/no/o.png" -- \
  render "$cube" -o "$tmp/no/o.png"
mkdir "$tmp/dir.png"
expect out_is_dir 1 "^zsweep: error: $tmp/dir.png: " ="$tmp/dir.png" -- render "$cube" -o "$tmp/dir.png"
expect stats_no_dir 1 "^zsweep: error: $tmp/no/s.json: cannot write: No such file or directory$" -"$tmp/o.png" -- \
  render "$cube" -o "$tmp/o.png" --stats "$tmp/no/s.json"
expect reference_out_no_dir 1 "^zsweep: error: $tmp/no/r.exr: cannot write: No such file or directory$" \
  -"$tmp/no/r.exr" -- reference "$cube" -o "$tmp/no/r.exr"
expect unknown_format 1 "^zsweep: error: $tmp/o.xyz: unsupported image format" -"$tmp/o.xyz" -- \
  render "$cube" -o "$tmp/o.xyz"

# Scene files: syntax, unknown keys, transfer functions.
expect json_syntax 1 'syn.json: invalid JSON: .*parse error at line 2, column 2[0-9]' -"$tmp/o.png" -- \
  render "$(scene syn $'{"mesh": "m.off",\n "image": {"width": 3,}}')" -o "$tmp/o.png"
expect unknown_key 1 "uk.json: unknown key 'scene.imgae' \(allowed: mesh, spheres, surfaces, image, camera, transfer_function, shading, render, ground, lights, shadows, ao, clip, crop, clip_geometry\)$" \
  -"$tmp/o.png" -- render "$(scene uk '{"mesh": "'"$cube"'", "imgae": {}}')" -o "$tmp/o.png"
expect unknown_nested_key 1 "unknown key 'camera.fov'" -"$tmp/o.png" -- \
  render "$(scene uk2 '{"mesh": "'"$cube"'", "camera": {"fov": 30}}')" -o "$tmp/o.png"
expect tf_unsorted 1 'transfer_function.color: points must be strictly increasing in the scalar \(point 1 is out of order\)$' \
  -"$tmp/o.png" -- render "$(scene tfu '{"mesh": "'"$cube"'", "transfer_function": {"color": [[1,0,0,0],[0,1,1,1]], "opacity": [[0,0],[1,1]]}}')" -o "$tmp/o.png"
expect tf_duplicate 1 'transfer_function.opacity: points must be strictly increasing in the scalar \(point 1 is a duplicate\)$' \
  -"$tmp/o.png" -- render "$(scene tfd '{"mesh": "'"$cube"'", "transfer_function": {"color": [[0,0,0,0],[1,1,1,1]], "opacity": [[0,0],[0,1]]}}')" -o "$tmp/o.png"
expect tf_out_of_range 1 'transfer_function.color: values must be in \[0, 1\]$' -"$tmp/o.png" -- \
  render "$(scene tfr '{"mesh": "'"$cube"'", "transfer_function": {"color": [[0,0,0,0],[1,1,1,2]], "opacity": [[0,0],[1,1]]}}')" -o "$tmp/o.png"
expect tf_number_overflow 1 "tfn.json: invalid JSON: .*number overflow parsing '1e999'$" -"$tmp/o.png" -- \
  render "$(scene tfn '{"mesh": "'"$cube"'", "transfer_function": {"color": [[0,0,0,0]], "opacity": [[0,1e999]]}}')" -o "$tmp/o.png"
expect budget_not_representable 1 'render.memory_budget_mb must be positive and below 2\^44$' -"$tmp/o.png" -- \
  render "$(scene mb '{"mesh": "'"$cube"'", "render": {"memory_budget_mb": 1e40}}')" -o "$tmp/o.png"
expect budget_option_range 2 '^zsweep: error: --memory-budget: 0 is out of range: must be positive and at most 1.7e\+13 \(see --help\)$' -"$tmp/o.png" -- \
  render "$cube" --memory-budget 0 -o "$tmp/o.png"
expect empty_mesh 1 'empty0.off: mesh has no tets$' -"$tmp/o.png" -- \
  render "$(printf '0 0\n' > "$tmp/empty0.off"; echo "$tmp/empty0.off")" -o "$tmp/o.png"

# Renders that work but are not what was likely meant: a warning, exit 0, the image.
printf '5 2\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 2\nnan 1 1 1\n0 1 2 3\n1 2 3 4\n' > "$tmp/nan.off"
expect nonfinite_tets 0 "^zsweep: warning: $tmp/nan.off: 1 of 2 tets have a non-finite coordinate or scalar; they are left out$" \
  +"$tmp/o.png" -- render "$tmp/nan.off" -o "$tmp/o.png" --width 16 --height 16
expect behind_camera 0 "^zsweep: warning: $tmp/o.png: the image is empty: the whole mesh is behind the camera$" +"$tmp/o.png" -- \
  render "$(scene behind '{"mesh": "'"$cube"'", "image": {"width": 16, "height": 16}, "camera": {"projection": "perspective", "eye": [0.5, 0.5, -5], "target": [0.5, 0.5, -10], "up": [0, 1, 0], "fov_y": 30}}')" -o "$tmp/o.png"
expect outside_view 0 "the image is empty: the mesh is outside the view$" +"$tmp/o.png" -- \
  render "$(scene aside '{"mesh": "'"$cube"'", "image": {"width": 16, "height": 16}, "camera": {"eye": [50, 50, 5], "target": [50, 50, 0], "up": [0, 1, 0], "height": 2}}')" -o "$tmp/o.png"
expect transparent_tf 0 "the image is empty: the transfer function's opacity is zero wherever the mesh is" +"$tmp/o.png" -- \
  render "$(scene clear '{"mesh": "'"$cube"'", "image": {"width": 16, "height": 16}, "transfer_function": {"color": [[0,1,1,1]], "opacity": [[0,0],[1,0]]}}')" -o "$tmp/o.png"

echo "bad inputs: $pass passed, $fail failed"
[[ $fail -eq 0 && $pass -ge 25 ]]
