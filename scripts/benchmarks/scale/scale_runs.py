"""The zsweep side of `scripts/bench scale`: grid sizes, the memory and disk
estimates that decide what is run, and the processes (generate, mesh info,
render), each bounded by a timeout and run under /usr/bin/time so a run that
fails (out of memory, killed, timed out) still gives its exit status, last
stderr line and peak RSS instead of stopping the benchmark."""
import json
import os
import re
import shutil
import signal
import subprocess
import tempfile
import time

from ..lib.common import ZSWEEP

# Estimates that decide which sizes are run (before anything is generated):
# a render's peak is about 100 bytes per tet (`zsweep mesh info` prints its own
# estimate, render_memory), generating about 40 plus the file (`.vtu`: 48 bytes
# per tet measured on a 1 M grid; .zsm is taken as the same).
RENDER_BYTES_PER_TET = 110
GEN_BYTES_PER_TET = 40
FILE_BYTES_PER_TET = 50
MEM_SHARE = 0.8       # of MemAvailable
LARGEST_CAP = 300e6   # tets, --largest
JITTER = "0.15"
# The phases of a render, as derive() names them: (column, label).
PHASES = [("load_s", "load"), ("topology_s", "topology"), ("setup_s", "per-view set-up"), ("sweep_s", "sweep"),
          ("first_frame_s", "first frame"), ("later_frame_s", "later frame")]
TIME = "/usr/bin/time"


def cells_for(mtets):
    """Cells per axis of the smallest grid with at least `mtets` million tets
    (5 per cube), so "100" is ≥ 100 M (272³ cubes: 100.6 M)."""
    n = max(2, round((mtets * 1e6 / 5) ** (1 / 3)))
    while tets_of(n) < mtets * 1e6:
        n += 1
    while n > 2 and tets_of(n - 1) >= mtets * 1e6:
        n -= 1
    return n


def tets_of(n):
    return 5 * n ** 3


def label(tets):
    """'0.214 M', '1.03 M', '41.2 M', '100.6 M', '1002 M'."""
    m = tets / 1e6
    return f"{m:.3g} M" if m < 100 else f"{m:.4g} M"


def meminfo(key):
    """A /proc/meminfo field in bytes (MemAvailable, MemTotal); 0 if unknown."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith(key + ":"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def too_big(n, work):
    """Why a grid of n³ cubes should not be generated and rendered here (None
    when it fits): its render (RENDER_BYTES_PER_TET) or its generation
    (GEN_BYTES_PER_TET plus the file) over MEM_SHARE of MemAvailable now, or
    its file over the free disk of the work directory."""
    t = tets_of(n)
    avail = meminfo("MemAvailable")
    need = max(t * RENDER_BYTES_PER_TET, t * (GEN_BYTES_PER_TET + FILE_BYTES_PER_TET))
    if avail and need > MEM_SHARE * avail:
        return (f"estimated {need / 1e9:.1f} GB > {MEM_SHARE:.0%} of MemAvailable "
                f"({avail / 1e9:.1f} GB)")
    free = shutil.disk_usage(work).free
    if t * FILE_BYTES_PER_TET > free:
        return f"file ~{t * FILE_BYTES_PER_TET / 1e9:.1f} GB > {free / 1e9:.1f} GB free in {work}"
    return None


def largest_cells():
    """--largest: the largest n with 5·n³·RENDER_BYTES_PER_TET under MEM_SHARE
    of MemAvailable now, at most LARGEST_CAP tets."""
    cap = min(MEM_SHARE * meminfo("MemAvailable") / RENDER_BYTES_PER_TET, LARGEST_CAP)
    n = int((cap / 5) ** (1 / 3))
    while tets_of(n + 1) <= cap:
        n += 1
    while n > 2 and tets_of(n) > cap:
        n -= 1
    return n


def budget_mib(a):
    """zsweep's --memory-budget (MiB): --memory-budget, else the larger of
    its own default (half of RAM) and MEM_SHARE of MemAvailable now, so a
    size the estimate lets through is not refused by a smaller budget."""
    if a.memory_budget:
        return a.memory_budget
    return max(MEM_SHARE * meminfo("MemAvailable"), meminfo("MemTotal") / 2) / 2**20


def stop(p):
    """Kills the process group `p` leads: its members first, so that the
    leader (/usr/bin/time) reaps them and leaves no zombie behind, then the
    leader. Its (stdout, stderr)."""
    for d in os.listdir("/proc"):
        if d.isdigit() and int(d) != p.pid:
            try:
                if os.getpgid(int(d)) == p.pid:
                    os.kill(int(d), signal.SIGKILL)
            except OSError:
                pass
    try:
        return p.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        return p.communicate()


def timed(cmd, timeout, env=None):
    """Runs `cmd` in its own process group, bounded by `timeout` s (then the
    group is killed): {exit_status (code, or "timeout after T s"), wall_s,
    error (last stderr line, when it failed), peak_rss_bytes (from
    /usr/bin/time, when there)}, and its stdout."""
    rss = None
    if os.access(TIME, os.X_OK):
        fd, rss = tempfile.mkstemp(prefix="zsweep-scale-rss-")
        os.close(fd)
        cmd = [TIME, "-f", "%M", "-o", rss] + cmd
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                         start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
        row = {"exit_status": p.returncode}
    except subprocess.TimeoutExpired:
        out, err = stop(p)
        row = {"exit_status": f"timeout after {timeout:g} s"}
    row["wall_s"] = round(time.perf_counter() - t0, 3)
    lines = [ln for ln in err.strip().splitlines() if not ln.startswith("Command ")]
    if row["exit_status"] != 0 and lines:
        row["error"] = lines[-1][:200]
    if rss:
        try:
            with open(rss) as f:
                kb = f.read().split()
            row["peak_rss_bytes"] = int(kb[-1]) * 1024
        except (OSError, ValueError, IndexError):
            pass
        os.remove(rss)
    return row, out


def generate(n, path, timeout):
    """`zsweep mesh generate grid --cells n --jitter 0.15 --field gaussians`:
    gen_* columns (wall, the generator's own generated/written seconds, peak
    RSS, file size, status)."""
    row, out = timed([ZSWEEP, "mesh", "generate", "grid", "--cells", str(n), "--jitter", JITTER,
                      "--field", "gaussians", "-o", path], timeout)
    g = {"gen_status": row["exit_status"], "gen_s": row["wall_s"], "gen_peak_rss_bytes": row.get("peak_rss_bytes")}
    m = re.search(r"generated in ([\d.]+) s, written in ([\d.]+) s", out)
    if m:
        g["gen_generated_s"], g["gen_written_s"] = float(m.group(1)), float(m.group(2))
    if row["exit_status"] == 0:
        g["file_bytes"] = os.path.getsize(path)
    else:
        g["gen_error"] = row.get("error", "")
    return g


def mesh_info(path, timeout):
    """`zsweep mesh info --json`, or None when it fails."""
    row, out = timed([ZSWEEP, "mesh", "info", path, "--json"], timeout)
    return json.loads(out) if row["exit_status"] == 0 else None


def render(inp, threads, a, work, tag, budget_mib=None, out_ext="png"):
    """One `zsweep render INPUT --threads T --frames F --stats` process (a
    mesh: automatic camera and transfer function; or a scene .json): the
    row's timing columns (derive), status and peak RSS. The image is kept as
    work/TAG.png (or out_ext)."""
    out = os.path.join(work, f"{tag}.{out_ext}")
    stats = os.path.join(work, f"{tag}.stats.json")
    if os.path.exists(stats):
        os.remove(stats)
    cmd = [ZSWEEP, "render", inp, "--width", str(a.size), "--height", str(a.size), "--threads", str(threads),
           "--frames", str(a.frames), "--stats", stats, "-o", out]
    if budget_mib:
        cmd += ["--memory-budget", f"{budget_mib:.0f}"]
    row, _ = timed(cmd, a.timeout)
    r = {"threads": threads, "status": row["exit_status"], "error": row.get("error", ""), "process_s": row["wall_s"],
         "peak_rss_bytes": row.get("peak_rss_bytes")}
    if row["exit_status"] == 0 and os.path.exists(stats):
        with open(stats) as f:
            r.update(derive(json.load(f)))
    r["image"] = out
    return r


def derive(st):
    """The columns of one render's --stats: the phases in seconds. time_ms
    set-up, order and binning are the last frame's (the renderer the stats
    come from), so sweep = that frame − its set-up; first frame = load +
    topology + frame 1 (what a user waits for the first image); later frame =
    the best of frames 2.. (each a whole per-view set-up + sweep)."""
    t = st["time_ms"]
    frames = st.get("frame_ms") or [t["total"]]
    ms = lambda x: round(x / 1000, 4)  # noqa: E731
    r = {"tets": st["mesh"]["tets"], "points": st["mesh"]["points"], "fragments": st["fragments"],
         "load_s": ms(t["load"]), "topology_s": ms(t["topology"]), "setup_s": ms(t["setup"]),
         "order_s": ms(t["order"]), "binning_s": ms(t["binning"]), "sweep_s": ms(frames[-1] - t["setup"]),
         "first_frame_s": ms(t["load"] + t["topology"] + frames[0]),
         "second_frame_s": ms(frames[1]) if len(frames) > 1 else float("nan"),
         "later_frame_s": ms(min(frames[1:])) if len(frames) > 1 else float("nan"),
         "frame_ms": " ".join(f"{x:.1f}" for x in frames),
         "budget_mib": round(st.get("memory_budget_bytes", 0) / 2**20)}
    if st.get("peak_rss_bytes"):
        r["peak_rss_bytes"] = st["peak_rss_bytes"]
    return r
