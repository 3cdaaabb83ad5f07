"""zsweep's benchmarks, one harness: `scripts/bench NAME [options]` runs
`python3 -m benchmarks NAME [options]` (__main__.py) with scripts/ on
PYTHONPATH; `scripts/bench NAME --help` gives a benchmark's options.

- lib/: the shared library (paths, running zsweep and the workers, peak RSS,
  CSV and Markdown tables, the sphere sets and views, the VTK sphere worker,
  the volume scene and VTK's volume mappers, the spheres benchmarks' options).
  It imports no benchmark.
- One benchmark per module or package beside it (spheres/, spheres_translucent/,
  spheres_ao/, shadows/, vs_vtk.py, vs_paraview.py, scaling.py, scale/). A benchmark
  imports the shared library and its own modules, never another benchmark;
  no module edits sys.path (workers run as `python3 -m benchmarks.X` with
  scripts/ on PYTHONPATH, pvpython's paraview_worker.py by path).
  tests/bench_harness.py checks this.
"""
