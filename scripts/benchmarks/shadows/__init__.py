"""scripts/bench shadows (alias scripts/bench-shadows): shadow maps against exact
shadow rays and VTK (shadows.py runs it; shadow_scenes.py: the scenes;
shadow_runs.py: zsweep runs; shadow_grid.py: the grid, checks and crossover;
shadow_metrics.py: image metrics; shadow_vs_vtk.py and the worker shadow_vtk.py:
VTK side by side; shadow_report.py: charts and summary.md)."""
