#!/usr/bin/env python3
"""project.bench_harness: the benchmarks' layout (scripts/benchmarks/), read
from the code with `ast`:
- every module parses;
- the shared library (benchmarks/lib/) imports nothing of the benchmarks;
- a benchmark (a module or package directly under benchmarks/) imports only
  the shared library and its own modules, never another benchmark (nor the
  entry, __main__.py, which alone picks a benchmark by name);
- no module imports a benchmark module by its bare name, and none touches
  sys.path (workers run as `python3 -m benchmarks.X` with scripts/ on
  PYTHONPATH, or by path);
- no import cycle among the modules;
- no module over 450 lines (the aim is ~400).
Usage: bench_harness.py SOURCE_DIR"""
import ast
import os
import sys

LIMIT = 450


def modules(top):
    """{dotted name: path} of the package at `top` (named after its folder)."""
    base = os.path.dirname(top)
    out = {}
    for root, dirs, files in os.walk(top):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__")
        for f in sorted(files):
            if f.endswith(".py"):
                rel = os.path.relpath(os.path.join(root, f), base)[:-3].split(os.sep)
                if rel[-1] == "__init__":
                    rel = rel[:-1]
                out[".".join(rel)] = os.path.join(root, f)
    return out


def imported(name, path, tree, mods):
    """(line, dotted name) of the package's modules that `name` imports."""
    is_pkg = os.path.basename(path) == "__init__.py"
    pkg = name.split(".") if is_pkg else name.split(".")[:-1]
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = ".".join(pkg[:len(pkg) - node.level + 1] + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            out.append((node.lineno, base))
            out += [(node.lineno, f"{base}.{a.name}") for a in node.names if f"{base}.{a.name}" in mods]
    return out


def unit(mod):
    """The benchmark (or 'lib', or the entry) a module belongs to."""
    parts = mod.split(".")
    return ".".join(parts[:2]) if len(parts) > 1 else mod


def main(src):
    top = os.path.join(src, "scripts", "benchmarks")
    root = os.path.basename(top)
    mods = modules(top)
    bare = {m.split(".")[-1] for m in mods} | {m.split(".")[1] for m in mods if m.count(".") >= 1}
    lib = f"{root}.lib"
    fails, graph = [], {m: set() for m in mods}
    if lib not in mods:
        fails.append(f"{top}: no shared library lib/")
    for name, path in mods.items():
        rel = os.path.relpath(path, src)
        text = open(path).read()
        n = len(text.splitlines())
        if n > LIMIT:
            fails.append(f"{rel}: {n} lines (over {LIMIT}; split it by what it does)")
        try:
            tree = ast.parse(text, rel)
        except SyntaxError as e:
            fails.append(f"{rel}: does not parse: {e}")
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and node.attr == "path" and \
                    isinstance(node.value, ast.Name) and node.value.id == "sys":
                fails.append(f"{rel}:{node.lineno}: touches sys.path")
            if isinstance(node, ast.Attribute) and node.attr == "addsitedir":
                fails.append(f"{rel}:{node.lineno}: site.addsitedir")
        me = unit(name)
        for line, target in imported(name, path, tree, mods):
            if target.split(".")[0] in bare and target.split(".")[0] != root:
                fails.append(f"{rel}:{line}: imports {target} by its bare name (import it package-relative)")
                continue
            if not (target == root or target.startswith(root + ".")):
                continue  # the standard library, numpy, vtk, zsweep, ...
            if target in mods:
                graph[name].add(target)
            them = unit(target)
            if name == f"{root}.__main__":
                ok = them == lib
            elif me == lib:
                ok = them == lib
            else:
                ok = them in (lib, me) and target != root
            if not ok:
                what, may = ("the shared library", lib) if me == lib else (f"benchmark {me}", f"{lib} and its own modules")
                fails.append(f"{rel}:{line}: {what} imports {target} (only {may} allowed)")
    # Import cycles.
    state = {}

    def visit(m, stack):
        state[m] = 1
        stack.append(m)
        for t in sorted(graph[m]):
            if state.get(t) == 1:
                fails.append("import cycle: " + " -> ".join(stack[stack.index(t):] + [t]))
            elif t not in state:
                visit(t, stack)
        stack.pop()
        state[m] = 2
    for m in sorted(graph):
        if m not in state:
            visit(m, [])
    for f in fails:
        print("FAIL", f)
    print(f"bench_harness: {len(mods)} modules, {len(fails)} problem(s)")
    return 1 if fails else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__.splitlines()[-1])
    sys.exit(main(sys.argv[1]))
