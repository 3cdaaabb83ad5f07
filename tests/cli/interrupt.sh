#!/usr/bin/env bash
# An interrupted render leaves no temporary behind (base/util/temp_registry.h):
# SIGINT, SIGTERM, SIGHUP and SIGQUIT while tiles stream into an EXR or PNG
# remove NAME.zs-tmp-PID-N.EXT, the process still dies of the signal (exit
# status 128+N), and an output already there from before is untouched.
set -u
zsweep=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# Job control on: without it bash starts background jobs with SIGINT and
# SIGQUIT ignored, and zsweep keeps a signal its parent ignores.
set -m
ulimit -c 0  # SIGQUIT dumps core by default
cd "$tmp" || exit 1
for ext in exr png; do
  echo "an older output" > "big.$ext"
  for sig in INT TERM HUP QUIT; do
    "$zsweep" render -o "big.$ext" --width 3000 --height 3000 --threads 1 >out.txt 2>err.txt &
    pid=$!
    # Wait until the temporary exists (the writer opens it before the first tile).
    for _ in $(seq 600); do
      compgen -G "big.zs-tmp-*" >/dev/null && break
      sleep 0.05
    done
    compgen -G "big.zs-tmp-*" >/dev/null || { kill -9 $pid; fail "$ext: no temporary appeared: $(cat err.txt)"; }
    kill -s $sig $pid
    wait $pid
    rc=$?
    want=$((128 + $(kill -l $sig)))
    [ $rc -eq $want ] || fail "$ext SIG$sig: exit status $rc, expected $want"
    left=$(compgen -G "big.zs-tmp-*")
    [ -z "$left" ] || fail "$ext SIG$sig: left behind: $left"
    [ "$(cat big.$ext)" = "an older output" ] || fail "$ext SIG$sig: the existing output was touched"
  done
done
echo "interrupt: ok"
