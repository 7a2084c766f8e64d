"""The command line of meshextraction-cohort."""

import argparse
import os
import shlex
import shutil
import sys

from . import __version__
from .manifest import MESH_EXTENSIONS, ManifestError, read_manifest, read_training_meshes

_DESCRIPTION = """Runs the meshextraction command-line tool over a cohort of scans on Dask's
distributed scheduler: a LocalCluster on this machine (--workers), or an existing cluster
(--scheduler / --scheduler-file). Each case's outputs are written under temporary names and
renamed when complete; a rerun skips the cases whose outputs verify, so an interrupted run
resumes where it stopped. `run` extracts and measures the meshes of a cohort's scans;
`shape-model` builds the statistical shape model of a cohort's meshes."""

_RUN_DESCRIPTION = """Per case of MANIFEST (CSV or JSON: case, image, iso, inside, label,
segmentation, options): OUTDIR/cases/CASE/ gets the mesh, its quality JSON
(`meshextraction quality --json`), a log, and the case's record. OUTDIR gets summary.csv,
summary.json and report.html. Exit status: 0 every case succeeded, 1 some failed, 2 bad
arguments or manifest, 130 interrupted (rerun to resume)."""

_MODEL_DESCRIPTION = """The landmark-free statistical shape model (thesis chapter 7) of the meshes given
by INPUT: mesh files (.ply, .vtk, .vtp, .stl, .obj, .off; each named by its file stem), or one
CSV or JSON manifest with the fields case and mesh, or the OUTDIR of a `run` (the mesh of every
case that succeeded). The steps of `meshextraction shape-model build` run as tasks: every mesh
prepared, then per template pass every mesh matched to the template and the template renewed
(the pass's reduction), then Procrustes analysis and PCA. OUTDIR gets model.h5 (statismo),
model.json (modes, variances), corresponded/NAME.ply (each mesh on the model's topology), the
steps' outputs (prepared/, pass-P/) and shape-model.log. A rerun keeps the steps whose inputs
and outputs are unchanged. Exit status: 0 the model was built, 1 a step failed (a model needs
every mesh; the message names it), 2 bad arguments or inputs, 130 interrupted (rerun to
resume)."""


def _default_tool():
    """--meshextraction's default: $MESHEXTRACTION, meshextraction on PATH, or the build
    tree's build/examples/meshextraction next to this package."""
    if os.environ.get("MESHEXTRACTION"):
        return os.environ["MESHEXTRACTION"]
    on_path = shutil.which("meshextraction")
    if on_path:
        return on_path
    here = os.path.dirname(os.path.abspath(__file__))
    return os.path.normpath(os.path.join(here, "..", "..", "..", "build", "examples", "meshextraction"))


def _positive(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError("must be at least 1")
    return value


def _add_cluster_options(command):
    """The options of both commands: where the tasks run, the tool, retries, --force."""
    where = command.add_mutually_exclusive_group()
    where.add_argument(
        "--workers", type=_positive, help="LocalCluster worker processes (default: cores / --task-threads)"
    )
    where.add_argument("--scheduler", metavar="ADDRESS", help="an existing Dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--scheduler-file", metavar="FILE", help="an existing scheduler's JSON scheduler file")
    command.add_argument(
        "--meshextraction",
        metavar="PATH",
        default=_default_tool(),
        help="the command-line tool, at the same path on every worker (default: $MESHEXTRACTION, "
        "meshextraction on PATH, or the build tree's; now %(default)s)",
    )
    command.add_argument(
        "--task-threads",
        type=_positive,
        default=1,
        help="threads of the tool per task (extract --threads; ITK's threads) (default: 1)",
    )
    command.add_argument(
        "--retries",
        type=int,
        default=3,
        help="retries of a task whose worker died or that raised; an error of the tool is not retried (default: 3)",
    )
    command.add_argument("--timeout", type=float, metavar="SECONDS", help="kill a command of the tool after this long")
    command.add_argument(
        "--force", action="store_true", help="recompute everything, even the outputs that verify"
    )
    command.add_argument(
        "--dashboard", metavar="ADDRESS", help="serve the LocalCluster's Dask dashboard here (e.g. :8787; needs bokeh)"
    )


def _fraction(text):
    value = float(text)
    if not 0.0 < value <= 1.0:
        raise argparse.ArgumentTypeError("must be in (0, 1]")
    return value


def _parser():
    parser = argparse.ArgumentParser(prog="meshextraction-cohort", description=_DESCRIPTION)
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    run = commands.add_parser("run", help="extract and measure every case of a manifest", description=_RUN_DESCRIPTION)
    run.add_argument("manifest", metavar="MANIFEST", help="CSV or JSON manifest of the cohort")
    run.add_argument("outdir", metavar="OUTDIR", help="output folder (created; reused by a rerun)")
    _add_cluster_options(run)
    run.add_argument(
        "--options",
        dest="common_options",
        default="",
        metavar="'OPTIONS'",
        help="extract options for every case, before the case's own (e.g. '--quality high')",
    )
    run.add_argument(
        "--quality-options",
        default="",
        metavar="'OPTIONS'",
        help="options of `meshextraction quality` (e.g. '--no-self-intersections' for very large meshes)",
    )
    run.add_argument("--mesh-format", default="vtk", choices=("vtk", "obj", "off", "gii", "byu"), help="(default: vtk)")
    run.add_argument("--title", default="Cohort report", help="the HTML report's title")
    model = commands.add_parser(
        "shape-model",
        help="the statistical shape model of a cohort's meshes (thesis ch. 7), its steps as tasks",
        description=_MODEL_DESCRIPTION,
    )
    model.add_argument(
        "inputs", nargs="+", metavar="INPUT", help="mesh files, or one manifest (case, mesh), or one run's OUTDIR"
    )
    model.add_argument("outdir", metavar="OUTDIR", help="output folder (created; reused by a rerun)")
    _add_cluster_options(model)
    model.add_argument("--passes", type=_positive, default=2, help="at most this many template passes (default: 2)")
    model.add_argument(
        "--variance-fraction",
        type=_fraction,
        default=0.95,
        metavar="F",
        help="keep the modes that explain this fraction of the variance (default: 0.95)",
    )
    model.add_argument(
        "--correspondence",
        choices=("surface", "point"),
        default="surface",
        help="closest points on the triangles or the nearest vertices (default: surface)",
    )
    model.add_argument(
        "--thesis", action="store_true", help="no non-rigid stage: the thesis' closest-point correspondence"
    )
    return parser


def _check_model_outdir(parser, args):
    """OUTDIR is the last argument: a mesh file there is an OUTDIR forgotten."""
    if os.path.isfile(args.outdir) or os.path.splitext(args.outdir)[1].lower() in MESH_EXTENSIONS:
        parser.error(f"OUTDIR {args.outdir} is a file or named like a mesh: give the output folder last")


def main(argv=None):
    parser = _parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 2
    if os.sep not in args.meshextraction:
        args.meshextraction = shutil.which(args.meshextraction) or args.meshextraction
    args.meshextraction = os.path.abspath(args.meshextraction)
    local = not (args.scheduler or args.scheduler_file)
    if local and not (os.path.isfile(args.meshextraction) and os.access(args.meshextraction, os.X_OK)):
        parser.error(f"the command-line tool {args.meshextraction} is not an executable file: give --meshextraction")
    if args.workers is None:
        args.workers = max(1, (os.cpu_count() or 1) // args.task_threads)
    try:
        if args.command == "shape-model":
            _check_model_outdir(parser, args)
            meshes, left_out = read_training_meshes(args.inputs)
        else:
            args.common_options = shlex.split(args.common_options)
            args.quality_options = shlex.split(args.quality_options)
            cases = read_manifest(args.manifest)
    except ManifestError as error:
        print(f"meshextraction-cohort: {error}", file=sys.stderr)
        return 2
    try:
        import distributed  # noqa: F401
    except ImportError:
        print(
            f"meshextraction-cohort: {sys.executable} has no dask.distributed; on Debian: apt-get install "
            "python3-distributed and run with /usr/bin/python3; elsewhere: pip install 'distributed>=2022.12'",
            file=sys.stderr,
        )
        return 2
    if args.command == "shape-model":
        from .model_runner import build_model

        if left_out:
            print(f"meshextraction-cohort: {len(left_out)} case(s) of the run failed, not in the model: "
                  f"{', '.join(left_out)}", flush=True)
        return build_model(meshes, args)
    from .runner import run as run_cohort

    return run_cohort(cases, args)
