#!/usr/bin/env python3
# What a page fault costs on this machine: fresh anonymous memory touched
# once per page, then again (no faults the second time); the difference per
# GB, at each size given (GB). docs/scaling.md cites it: from a few GB up
# this VM takes several times longer per fault, which is what bends the
# large meshes' topology and first frames upwards.
#   python3 scripts/benchmarks/scale/first_touch.py 1 4 8 12
import mmap, sys, time
# First touch of fresh anonymous memory: seconds per GB, touched twice
# (the second pass has no page faults: the difference is the faults' cost).
for gb in map(float, sys.argv[1:]):
    n = int(gb * 1e9); m = mmap.mmap(-1, n)
    t0 = time.perf_counter()
    for i in range(0, n, 4096): m[i] = 1
    t1 = time.perf_counter()
    for i in range(0, n, 4096): m[i] = 2
    t2 = time.perf_counter()
    m.close()
    print(f"{gb:g} GB: page faults {((t1 - t0) - (t2 - t1)) / gb:.2f} s per GB")
