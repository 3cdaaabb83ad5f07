# Sourced by tests/cli/*.sh (not a test itself): same A B WHAT checks that two
# images are pixel- and depth-identical (`zsweep compare`: max abs 0, no pixel
# hit in one only, depth max rel 0); needs $zsweep and $tmp, sets fail=1 and
# says why otherwise.
same() {
  "$zsweep" compare "$1" "$2" --json >"$tmp/cmp" 2>&1
  grep -q '"max_abs": 0.0,' "$tmp/cmp" && grep -q '"coverage_mismatches": 0,' "$tmp/cmp" \
    && grep -q '"max_rel": 0.0' "$tmp/cmp" || { echo "FAIL $3: $(tr -d '\n' <"$tmp/cmp")"; fail=1; }
}
