"""What every benchmark shares: the paths (ROOT, ZSWEEP, SHARED), running a
command and a worker module, the machine's name, peak RSS, the CSV of the
rows, table cells, the table between <!-- NAME:begin ... --> and
<!-- NAME:end --> markers of a Markdown file in docs/ (appended under
`heading` when the markers are missing), and copying plots into docs/bench."""
import csv
import json
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
SCRIPTS = os.path.join(ROOT, "scripts")
ZSWEEP = os.environ.get("ZSWEEP", os.path.join(ROOT, "build", "src", "zsweep"))
SHARED = os.environ.get("ZSWEEP_SHARED", os.path.join(ROOT, "..", "shared", "datasets"))


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw)


def run_stats(cmd, stats, timeout, err_chars=200):
    """Runs `cmd` (a zsweep process that writes --stats `stats`) under
    `timeout` s: (row, stats). row: exit_status (the exit code, or "timeout
    after T s"), process_s, and on failure error (its last stderr line,
    cut to err_chars); stats: the JSON, or None when it failed."""
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"exit_status": f"timeout after {timeout:g} s"}, None
    row = {"exit_status": p.returncode, "process_s": round(time.perf_counter() - t0, 3)}
    if p.returncode != 0:
        err = p.stderr.strip().splitlines()
        row["error"] = err[-1][:err_chars] if err else ""
        sys.stderr.write(f"zsweep failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}\n")
        return row, None
    with open(stats) as f:
        return row, json.load(f)


def worker_env(**extra):
    """The environment of a worker started as `python3 -m benchmarks.X`:
    scripts/ on PYTHONPATH (so the worker finds this package), plus `extra`."""
    path = os.environ.get("PYTHONPATH")
    return dict(os.environ, PYTHONPATH=SCRIPTS + (os.pathsep + path if path else ""), **extra)


def fail(prog, msg):
    """A worker's or a benchmark's fatal error: one line on stderr, exit 1."""
    print(f"{prog}: {msg}", file=sys.stderr)
    sys.exit(1)


def peak_rss_mb():
    """This process's peak resident set (VmHWM), MiB, one decimal."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM"):
                    return round(int(line.split()[1]) / 1024, 1)
    except OSError:
        pass
    return float("nan")


def luminance(rgb):
    """Rec. 709 luminance of [..., R, G, B]."""
    return rgb[..., 0] * 0.2126 + rgb[..., 1] * 0.7152 + rgb[..., 2] * 0.0722


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def cpu_vector_isa():
    """The widest vector kernel zsweep picks on this CPU (segment_batch.cpp):
    the hosts this project runs on differ in it, and it moves the timings."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    flags = set(line.split(":", 1)[1].split())
                    if "avx512f" in flags:
                        return "AVX-512"
                    if "avx2" in flags and "fma" in flags:
                        return "AVX2, no AVX-512"
                    return "no AVX2"
    except OSError:
        pass
    return "unknown vector ISA"


# ---------------------------------------------------------------- tables

def isnum(x):
    """A measured number (not a bool, not NaN)."""
    return isinstance(x, (int, float)) and not isinstance(x, bool) and x == x


def fmt(x, d=1):
    """A table cell: "–" for no value (None, "", NaN), a number with
    thousands separators and d decimals, any other value as its text."""
    if x is None or (isinstance(x, str) and x == ""):
        return "–"
    if isinstance(x, (str, bool)):
        return str(x)
    if x != x:
        return "–"
    return f"{x:,.{d}f}"


def all_cols(rows):
    """The rows with every column any of them has (in first-seen order)."""
    cols = []
    for r in rows:
        for k in r:
            if k not in cols:
                cols.append(k)
    return [{k: r.get(k, "") for k in cols} for r in rows]


def write_csv(path, rows):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def read_csv(d, name):
    """A CSV a run wrote (for --replot): numbers back as int or float."""
    def num(v):
        try:
            x = float(v)
        except ValueError:
            return v
        return int(x) if x.is_integer() and "." not in v and "e" not in v else x
    with open(os.path.join(d, name)) as f:
        return [{k: num(v) for k, v in r.items()} for r in csv.DictReader(f)]


def replace_block(path, name, lines, heading, source=None):
    """Replaces (or appends under `heading`) the block marked `name` in the
    Markdown file `path`; `source`: the command named as its writer
    (default scripts/NAME)."""
    begin, end = f"<!-- {name}:begin", f"<!-- {name}:end -->"
    source = source or f"scripts/{name}"
    block = "\n".join([f"{begin} (written by {source}; do not edit by hand) -->"] + lines + [end])
    text = open(path).read() if os.path.exists(path) else "# Benchmarks\n\n"
    if begin in text and end in text:
        text = text[:text.index(begin)] + block + text[text.index(end) + len(end):]
    else:
        text = text.rstrip() + f"\n\n{heading}\n\n" + block + "\n"
    with open(path, "w") as f:
        f.write(text)


def copy_to_docs(files):
    """Copies the files (plots, CSVs) into docs/bench."""
    d = os.path.join(ROOT, "docs", "bench")
    os.makedirs(d, exist_ok=True)
    for f in files:
        shutil.copy(f, os.path.join(d, os.path.basename(f)))
