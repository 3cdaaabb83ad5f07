"""scripts/bench spheres --ao (alias scripts/bench spheres-ao): ambient occlusion
(ao.py runs it; ao_runs.py: settings and zsweep runs; ao_others.py: VTK's SSAO
and Tachyon, ao_ssao_worker.py the VTK worker; ao_report.py: tables; ao_plots.py:
plots)."""
