"""What the benchmark scripts share: the machine's name, the CSV of their rows,
and their table between <!-- NAME:begin ... --> and <!-- NAME:end --> markers
of docs/benchmarks.md (appended under `heading` when the markers are missing)."""
import csv
import os


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


def write_csv(path, rows):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


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
