#!/usr/bin/env python3
"""The tree by role (docs/renderers.md, "The tree"), checked from the #include
lines of src/: no include runs up the layers, raster/ and geometry/ never
include each other, a renderer (render/<name>/) never includes another, every
top folder is a known role, and no two headers share a file name.

Usage: layers.py SRC_DIR. Prints each broken rule as file:line and exits 1."""
import os
import re
import sys

# Level of each top folder, lowest first; render/ itself (frame_settings.h)
# sits below the renderers in its subfolders.
LEVEL = {"base": 0, "raster": 1, "geometry": 1, "lighting": 2, "render": 3, "output": 5, "scene": 6,
         "app": 7, "cli": 8, "python": 8, "mpi": 8, "bench": 8, "tools": 8}
RENDERER_LEVEL = 4
INDEPENDENT = {"raster", "geometry"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def unit(rel):
    """(top folder, renderer or '') of a path relative to src/."""
    parts = rel.split("/")
    top = parts[0] if len(parts) > 1 else ""
    renderer = parts[1] if top == "render" and len(parts) > 2 else ""
    return top, renderer


def level(top, renderer):
    return RENDERER_LEVEL if renderer else LEVEL[top]


def check(src):
    broken, headers = [], {}
    for root, _, files in os.walk(src):
        for name in sorted(files):
            if not name.endswith((".h", ".cpp")):
                continue
            path = os.path.join(root, name)
            rel = os.path.relpath(path, src).replace(os.sep, "/")
            if name.endswith(".h"):
                if name in headers:
                    broken.append(f"{rel}: a second header named {name} (first: {headers[name]})")
                headers.setdefault(name, rel)
            top, renderer = unit(rel)
            if top and top not in LEVEL:
                broken.append(f"{rel}: {top}/ is not a role folder")
                continue
            if not top:
                continue  # src/main.cpp: the program, above everything
            with open(path, errors="replace") as f:
                for n, line in enumerate(f, 1):
                    m = INCLUDE.match(line)
                    if not m or "/" not in m.group(1):
                        continue
                    t_top, t_renderer = unit(m.group(1))
                    if t_top not in LEVEL:
                        continue  # a test helper or a third-party header
                    where = f"{rel}:{n} includes {m.group(1)}"
                    if (t_top, t_renderer) == (top, renderer):
                        continue
                    if renderer and t_renderer:
                        broken.append(f"{where}: renderers never include one another")
                    elif {top, t_top} == INDEPENDENT:
                        broken.append(f"{where}: raster and geometry are independent")
                    elif level(t_top, t_renderer) > level(top, renderer) and level(top, renderer) < 8:
                        broken.append(f"{where}: runs up the layers")
    return broken


if __name__ == "__main__":
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        sys.exit("usage: layers.py SRC_DIR")
    problems = check(sys.argv[1])
    for p in problems:
        print(p)
    print(f"layers: {len(problems)} broken")
    sys.exit(1 if problems else 0)
