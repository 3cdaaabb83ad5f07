"""Thread scaling and peak memory of `zsweep render` at large sizes.

Run through scripts/bench scaling (alias scripts/bench-scaling). For every
mesh, size and thread count it renders once (one process per run, so peak RSS is that render's), to a
streamed EXR in a scratch directory that is deleted afterwards, and reads
time_ms.total and peak_rss_bytes from --stats. Speedups are within one run
of this script, thread count against one thread, same mesh and size.
Writes a CSV and the table between the bench-scaling markers of
docs/benchmarks.md.
"""
import argparse
import datetime
import json
import os
import shutil
import subprocess
import sys
import tempfile

from .lib.common import ROOT, ZSWEEP, cpu_name, cpu_vector_isa, replace_block, write_csv
from .lib.volume import mesh_args


def main(argv):
    ap = argparse.ArgumentParser(
        prog="bench scaling",
        description="Thread scaling and peak memory of `zsweep render` at 2048², 8192², 16384² on the shared "
                    "datasets. Writes docs/bench/scaling.csv and the table in docs/benchmarks.md between the "
                    "bench-scaling markers.")
    ap.add_argument("--meshes", default="spx,blunt,post")
    ap.add_argument("--sizes", default="2048,8192,16384")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--scan", default="span")
    ap.add_argument("--repeat", type=int, default=1, help="interleaved rounds over the thread counts; best of them")
    ap.add_argument("--csv", default=os.path.join(ROOT, "docs", "bench", "scaling.csv"))
    ap.add_argument("--no-doc", action="store_true", help="do not update docs/benchmarks.md")
    a = ap.parse_args(argv)
    work = tempfile.mkdtemp(prefix="zsweep-scaling-")
    rows = []
    try:
        for name in a.meshes.split(","):
            for size in [int(s) for s in a.sizes.split(",")]:
                threads = [int(s) for s in a.threads.split(",")]
                best = {}
                # Interleaved rounds: the thread counts are timed in turn, so a
                # drift in the machine's speed hits them alike; best of the rounds.
                for _ in range(a.repeat):
                    for t in threads:
                        out = os.path.join(work, f"{name}-{size}-{t}.exr")
                        stats = out + ".json"
                        subprocess.run([ZSWEEP, "render"] + mesh_args(name) +
                                       ["--width", str(size), "--height", str(size), "--threads", str(t),
                                        "--scan", a.scan, "-o", out, "--stats", stats],
                                       check=True, capture_output=True, text=True)
                        st = json.load(open(stats))
                        os.remove(out)
                        secs = st["time_ms"]["total"] / 1000
                        if t not in best or secs < best[t][0]:
                            best[t] = (secs, st)
                base = best[threads[0]][0]
                for t in threads:
                    secs, st = best[t]
                    row = {"mesh": name, "tets": st["mesh"]["tets"], "size": size, "threads": t,
                           "render_s": secs, "speedup": base / secs, "fragments": st["fragments"],
                           "peak_rss_mib": st["peak_rss_bytes"] / 2**20,
                           "budget_mib": st["memory_budget_bytes"] / 2**20, "tiles": st.get("tiles", 0)}
                    rows.append(row)
                    print(f"{name:6s} {size:6d}² {t} thread(s): {secs:8.2f} s ({row['speedup']:.2f}x), "
                          f"peak RSS {row['peak_rss_mib']:.0f} MiB, {st['fragments']:,} fragments", flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    write_csv(a.csv, rows)
    if not a.no_doc:
        update_doc(rows, a)


def update_doc(rows, a):
    path = os.path.join(ROOT, "docs", "benchmarks.md")
    lines = [
        f"Measured {datetime.date.today().isoformat()} on {cpu_name()} ({os.cpu_count()} cores, {cpu_vector_isa()}), "
        f"`exact` integrator, `{a.scan}` scan, streamed EXR output, default memory budget (half of RAM), "
        f"`scripts/bench-scaling --meshes {a.meshes} --sizes {a.sizes} --threads {a.threads} --repeat {a.repeat}` "
        f"(best of {a.repeat} interleaved round(s)). Speedup: against one thread in the same run.",
        "",
        "| mesh | tets | size | threads | render (s) | speedup | fragments | peak RSS (MiB) |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for r in rows:
        lines.append(f"| {r['mesh']} | {r['tets']:,} | {r['size']}² | {r['threads']} | {r['render_s']:.2f} | "
                     f"{r['speedup']:.2f}× | {r['fragments']:,} | {r['peak_rss_mib']:.0f} |")
    replace_block(path, "bench-scaling", lines, "## Thread scaling and peak memory")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
