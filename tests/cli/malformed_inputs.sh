#!/usr/bin/env bash
# Every file in tests/data/bad must be rejected by `zsweep mesh info` with
# exactly the one-line error listed in tests/data/bad/EXPECTED, exit code 1,
# nothing on stdout; `mesh convert` of it must leave no output file, and
# `render` of it must fail with the same line and leave no image.
set -u
zsweep=$1; src=$2
cd "$src/tests/data/bad" || exit 1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0
listed=()
while IFS=$'\t' read -r file expected; do
  [[ -z "$file" || "$file" == \#* ]] && continue
  listed+=("$file")
  args=("$file")
  "$zsweep" mesh info "${args[@]}" >"$tmp/out" 2>"$tmp/err"; rc=$?
  want="zsweep: error: $expected"
  if [[ $rc -ne 1 ]]; then echo "FAIL $file: exit $rc, want 1"; ((fail++)); continue; fi
  if [[ "$(cat "$tmp/err")" != "$want" ]]; then
    echo "FAIL $file:"; echo "  got:  $(cat "$tmp/err")"; echo "  want: $want"; ((fail++)); continue
  fi
  if [[ -s "$tmp/out" ]]; then echo "FAIL $file: printed to stdout"; ((fail++)); continue; fi
  "$zsweep" mesh convert "$file" "$tmp/out.vtu" >/dev/null 2>&1
  if [[ -e "$tmp/out.vtu" ]] || compgen -G "$tmp/out*.vtu" >/dev/null; then
    echo "FAIL $file: convert left an output file"; ((fail++)); continue
  fi
  # render: the same line, and no image (nor its temporary) left behind.
  "$zsweep" render "$file" -o "$tmp/r.png" --width 8 --height 8 >/dev/null 2>"$tmp/err"; rc=$?
  if [[ $rc -ne 1 || "$(cat "$tmp/err")" != "$want" ]]; then
    echo "FAIL render $file: exit $rc: $(cat "$tmp/err")"; ((fail++)); continue
  fi
  if compgen -G "$tmp/r*.png" >/dev/null; then echo "FAIL render $file: left an output file"; ((fail++)); continue; fi
  ((pass++))
done < EXPECTED
# Every bad file must be listed, so none is silently untested.
for f in *; do
  [[ "$f" == EXPECTED ]] && continue
  if [[ ! " ${listed[*]} " == *" $f "* ]]; then echo "FAIL $f: not listed in EXPECTED"; ((fail++)); fi
done
echo "malformed inputs: $pass passed, $fail failed"
[[ $fail -eq 0 && $pass -ge 15 ]]
