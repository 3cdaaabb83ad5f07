"""Replaces the block between <!-- NAME:begin ... --> and <!-- NAME:end --> of a
Markdown file (appending it under `heading` when the markers are missing),
for the benchmark scripts that write their tables into docs/benchmarks.md."""
import os


def replace_block(path, name, lines, heading):
    begin, end = f"<!-- {name}:begin", f"<!-- {name}:end -->"
    block = "\n".join([f"{begin} (written by scripts/{name}; do not edit by hand) -->"] + lines + [end])
    text = open(path).read() if os.path.exists(path) else "# Benchmarks\n\n"
    if begin in text and end in text:
        text = text[:text.index(begin)] + block + text[text.index(end) + len(end):]
    else:
        text = text.rstrip() + f"\n\n{heading}\n\n" + block + "\n"
    with open(path, "w") as f:
        f.write(text)
