#!/usr/bin/env bash
# `zsweep render --mpi` under `mpirun -np 2`: both schedules, one and two
# threads per rank, the default scene, a one-tet mesh, a sphere set and a
# triangle surface (its shadow map built on every rank), each image
# bit-identical to a single-process render; rank 0 alone writes (every rank
# runs in its own directory with a relative -o, and its stdout/stderr go to
# files there); failures give one line naming the file and never hang.
set -u
zsweep=$(realpath "$1"); src=$(realpath "$2")  # ranks run in other directories
command -v mpirun >/dev/null || { echo "SKIP: mpirun not found (Debian: openmpi-bin)"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0; pass=0
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }

# CI runs as root; two ranks on however many cores; shared memory only, and
# no single-copy (containers often forbid the ptrace it needs).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
mpi=(mpirun -np 2 --oversubscribe --bind-to none)

# mpirank CMD...: CMD under mpirun, rank R in $tmp/run/rankR with
# its stdout/stderr in out.txt/err.txt there. Sets rc (124: timed out).
mpirank() {
  rm -rf "$tmp/run"; mkdir -p "$tmp/run/rank0" "$tmp/run/rank1"
  timeout 60 "${mpi[@]}" bash -c 'cd "$0/rank$OMPI_COMM_WORLD_RANK" && exec "$@" >out.txt 2>err.txt' \
    "$tmp/run" "$@" >"$tmp/mpirun.out" 2>"$tmp/mpirun.err"
  rc=$?
}
# Rank 1 wrote nothing at all; rank 0 printed nothing on stderr.
only_rank0_wrote() {
  local extra; extra=$(cd "$tmp/run/rank1" && ls -A | grep -vx -e out.txt -e err.txt)
  [ -z "$extra" ] || { bad "$1: rank 1 wrote $extra"; return 1; }
  [ ! -s "$tmp/run/rank1/out.txt" ] && [ ! -s "$tmp/run/rank1/err.txt" ] || { bad "$1: rank 1 printed"; return 1; }
  [ ! -s "$tmp/run/rank0/err.txt" ] || { bad "$1: rank 0 stderr: $(head -3 "$tmp/run/rank0/err.txt")"; return 1; }
}
identical() {  # A.exr B.exr label
  local j; j=$("$zsweep" compare "$1" "$2" --json) || { bad "$3: compare failed"; return 1; }
  python3 -c 'import json,sys; d=json.loads(sys.argv[1]); sys.exit(0 if d["max_abs"] == 0 else 1)' "$j" \
    || { bad "$3: differs from the single-process render: $(echo $j | tr -d '\n')"; return 1; }
}

size=(--width 200 --height 150)
tiles=()
"$zsweep" render --help | grep -q -- '--tile-size' && tiles=(--tile-size 16)  # 130 tiles

# One tet, automatic camera: fills the image. Its scalar varies (a constant
# one renders with a warning on stderr, which these cases must not print).
small="$tmp/one_tet.off"
printf '4 1\n0 0 0 0\n1 0 0 1\n0 1 0 2\n0 0 1 3\n0 1 2 3\n' > "$small"
# A sphere set: the sphere renderer through the same MPI path (RGBA and Z).
spheres="$src/tests/data/spheres/small.pdb"
# A triangle surface: the surface renderer (RGBA, Z, lit0).
surface="$src/tests/data/surfaces/pyramid.obj"
inputs=("default" "$small" "$spheres" "$surface")
for input in "${inputs[@]}"; do
  in=(); [ "$input" = default ] || in=("$input")
  name=$(basename "$input")
  "$zsweep" render "${in[@]}" "${size[@]}" "${tiles[@]}" --threads 1 -o "$tmp/single.exr" >/dev/null 2>&1 \
    || { bad "$name: single-process render"; continue; }
  # Both schedules on the default scene, one run on the mesh (each mpirun
  # costs ~2 s here, mostly start-up: `zsweep --version` alone takes ~0.9 s).
  runs=("static 2")
  [ "$input" = default ] && runs=("static 1" "dynamic 1" "dynamic 2")
  for run in "${runs[@]}"; do
    set -- $run
    label="$name, $1, --threads $2"
    mpirank "$zsweep" render --mpi --mpi-schedule "$1" "${in[@]}" "${size[@]}" "${tiles[@]}" --threads "$2" \
      -o out.exr --stats stats.json
    [ $rc -eq 0 ] || { bad "$label: exit $rc: $(head -3 "$tmp/run/rank0/err.txt" "$tmp/mpirun.err")"; continue; }
    only_rank0_wrote "$label" || continue
    [ -s "$tmp/run/rank0/out.exr" ] && [ -s "$tmp/run/rank0/stats.json" ] || { bad "$label: no output"; continue; }
    grep -q '^wrote out.exr' "$tmp/run/rank0/out.txt" || { bad "$label: no 'wrote' line"; continue; }
    # Both ranks swept tiles (rank 0 prints "tiles N0/N1").
    grep -Eq '^mpi: 2 rank.*tiles [1-9][0-9]*/[1-9][0-9]*,' "$tmp/run/rank0/out.txt" \
      || { bad "$label: work not shared: $(grep '^mpi:' "$tmp/run/rank0/out.txt")"; continue; }
    identical "$tmp/run/rank0/out.exr" "$tmp/single.exr" "$label" && pass=$((pass + 1))
  done
done

# A PNG through the same path (the band writer sees tiles from two ranks).
"$zsweep" render "${size[@]}" "${tiles[@]}" -o "$tmp/single.png" >/dev/null 2>&1 || bad "single-process png"
mpirank "$zsweep" render --mpi --mpi-schedule static "${size[@]}" "${tiles[@]}" --threads 2 -o out.png
if [ $rc -eq 0 ] && only_rank0_wrote "png"; then
  cmp -s "$tmp/run/rank0/out.png" "$tmp/single.png" && pass=$((pass + 1)) || bad "png differs"
else
  bad "png: exit $rc"
fi

# errors LABEL FILE: exit non-zero (not a timeout), exactly one error line,
# from rank 0, naming FILE; rank 1 silent; no output image anywhere.
errors() {
  [ $rc -ne 0 ] && [ $rc -ne 124 ] || { bad "$1: exit $rc"; return; }
  local lines; lines=$(cat "$tmp/run/rank0/err.txt" "$tmp/run/rank1/err.txt" | grep -c 'zsweep: error:')
  [ "$lines" -eq 1 ] || { bad "$1: $lines error lines"; return; }
  [ "$(wc -l < "$tmp/run/rank0/err.txt")" -eq 1 ] || { bad "$1: rank 0 stderr: $(cat "$tmp/run/rank0/err.txt")"; return; }
  grep -q -- "$2" "$tmp/run/rank0/err.txt" || { bad "$1: does not name $2: $(cat "$tmp/run/rank0/err.txt")"; return; }
  [ ! -s "$tmp/run/rank1/err.txt" ] && [ ! -s "$tmp/run/rank1/out.txt" ] || { bad "$1: rank 1 printed"; return; }
  [ -z "$(find "$tmp/run" -name '*.exr')" ] || { bad "$1: left an image: $(find "$tmp/run" -name '*.exr')"; return; }
  pass=$((pass + 1))
}
# A missing input on every rank.
mpirank "$zsweep" render --mpi "$tmp/nope.off" -o out.exr
errors "missing input" "$tmp/nope.off"
# A missing input on rank 1 only: rank 0 reports rank 1's error.
mpirank bash -c '[ "$OMPI_COMM_WORLD_RANK" = 1 ] && m="$0/nope1.off" || m="$2";
  exec "$1" render --mpi "$m" -o out.exr' "$tmp" "$zsweep" "$small"
errors "missing input on rank 1" "rank 1: $tmp/nope1.off"
# Ranks that disagree on the image size stop together.
mpirank bash -c 'exec "$1" render --mpi --width $((64 + OMPI_COMM_WORLD_RANK)) -o out.exr' "$tmp" "$zsweep"
errors "different sizes" "disagree"

# A failure mid-render on rank 1 (a test hook makes its first run throw):
# that rank's one line, every rank ends (MPI_Abort), nothing under the
# output name (an aborted rank 0 may leave its temporary file).
ZSWEEP_MPI_FAIL_RANK=1 mpirank "$zsweep" render --mpi "${size[@]}" "${tiles[@]}" --threads 1 -o out.exr
if [ $rc -eq 0 ] || [ $rc -eq 124 ]; then bad "failure mid-render: exit $rc"
elif [ "$(cat "$tmp/run/rank1/err.txt")" != "zsweep: error: rank 1: failure injected by ZSWEEP_MPI_FAIL_RANK" ]; then
  bad "failure mid-render: rank 1 stderr: $(cat "$tmp/run/rank1/err.txt")"
elif [ -e "$tmp/run/rank0/out.exr" ] || [ -s "$tmp/run/rank0/err.txt" ]; then bad "failure mid-render: rank 0 output"
else pass=$((pass + 1)); fi

echo "mpi: $pass passed, $fail failed"
[ $fail -eq 0 ]
