"""scripts/bench scale (alias scripts/bench-scale): zsweep against mesh size up to
100 M tets and beyond on one machine, issue 41 (scale.py runs it; scale_runs.py:
sizes, memory estimates, generating the grids, the zsweep processes;
scale_vtk.py and the worker scale_vtk_worker.py: VTK side by side on one mesh;
scale_report.py: the CSV, the growth ratios, the goals and the section of
docs/scaling.md; scale_plots.py: the plots)."""
