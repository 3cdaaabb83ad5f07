"""scripts/bench spheres: the orbit benchmark (orbit.py runs it, orbit_report.py
sums it up)."""
