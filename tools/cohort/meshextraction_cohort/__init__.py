"""meshextraction-cohort: runs the meshextraction command-line tool over a cohort of scans
on Dask's distributed scheduler (a LocalCluster by default, or an existing cluster).

Modules:
  manifest      the cohort's cases, read from a CSV or JSON manifest; a shape model's meshes
  task          one case on a worker: extract, measure, write under temporary names, rename
  outputs       the output layout, atomic writes, and the verification that lets a rerun resume
  runner        the Dask client: skip verified cases, submit the rest, retry, record, summarise
  report        the summary CSV/JSON and the HTML report (inline SVG charts)
  model_task    one step of a shape model on a worker: a `meshextraction shape-model` command
  model_runner  the shape model's build: its steps as tasks, pass by pass, kept when they verify
  cli           the command line (run, shape-model)
"""

__version__ = "0.1.0"
