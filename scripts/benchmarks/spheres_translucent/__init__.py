"""scripts/bench spheres --translucent (alias scripts/bench spheres-translucent):
the translucent modes (translucent.py runs them; translucent_runs.py: the
renders and measures; translucent_tables.py: the tables and plots)."""
