#!/usr/bin/env bash
# scripts/same-images --quick: a binary against itself gives "9 of 9 the
# same" and exit 0; against a wrapper whose renders differ (one column wider)
# it names each differing scene and exits 1.
set -u
zsweep=$(realpath "$1"); src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
"$src/scripts/same-images" "$zsweep" "$zsweep" --quick --out "$tmp/a" >"$tmp/same.log" 2>&1 \
  || { echo "FAIL a binary against itself: $(tail -3 "$tmp/same.log")"; fail=1; }
grep -q "^same-images: \([0-9]*\) of \1 the same$" "$tmp/same.log" || { echo "FAIL summary: $(tail -1 "$tmp/same.log")"; fail=1; }
[[ $(grep -c ": same (max abs 0 " "$tmp/same.log") -ge 9 ]] || { echo "FAIL fewer than 9 scenes compared"; fail=1; }
cat >"$tmp/wider" <<W
#!/usr/bin/env bash
if [[ \$1 == render || \$1 == reference ]]; then exec "$zsweep" "\$@" --width 97; fi
exec "$zsweep" "\$@"
W
chmod +x "$tmp/wider"
if "$src/scripts/same-images" "$zsweep" "$tmp/wider" --quick --out "$tmp/b" >"$tmp/diff.log" 2>&1; then
  echo "FAIL different images pass"; fail=1
fi
[[ $(grep -c ": DIFFERENT" "$tmp/diff.log") -ge 9 ]] || { echo "FAIL not every differing scene named: $(cat "$tmp/diff.log")"; fail=1; }
[[ $fail -eq 0 ]] && echo "same_images: all checks passed"
exit $fail
