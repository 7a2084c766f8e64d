"""The command line of meshextraction-cohort."""

import argparse
import os
import shlex
import shutil
import sys

from . import __version__
from .manifest import ManifestError, read_manifest

_DESCRIPTION = """Runs the meshextraction command-line tool over a cohort of scans on Dask's
distributed scheduler: a LocalCluster on this machine (--workers), or an existing cluster
(--scheduler / --scheduler-file). Each case's outputs are written under temporary names and
renamed when complete; a rerun skips the cases whose outputs verify, so an interrupted run
resumes where it stopped."""

_RUN_DESCRIPTION = """Per case of MANIFEST (CSV or JSON: case, image, iso, inside, label,
segmentation, options): OUTDIR/cases/CASE/ gets the mesh, its quality JSON
(`meshextraction quality --json`), a log, and the case's record. OUTDIR gets summary.csv,
summary.json and report.html. Exit status: 0 every case succeeded, 1 some failed, 2 bad
arguments or manifest, 130 interrupted (rerun to resume)."""


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


def _parser():
    parser = argparse.ArgumentParser(prog="meshextraction-cohort", description=_DESCRIPTION)
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    run = commands.add_parser("run", help="extract and measure every case of a manifest", description=_RUN_DESCRIPTION)
    run.add_argument("manifest", metavar="MANIFEST", help="CSV or JSON manifest of the cohort")
    run.add_argument("outdir", metavar="OUTDIR", help="output folder (created; reused by a rerun)")
    where = run.add_mutually_exclusive_group()
    where.add_argument(
        "--workers", type=_positive, help="LocalCluster worker processes (default: cores / --task-threads)"
    )
    where.add_argument("--scheduler", metavar="ADDRESS", help="an existing Dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--scheduler-file", metavar="FILE", help="an existing scheduler's JSON scheduler file")
    run.add_argument(
        "--meshextraction",
        metavar="PATH",
        default=_default_tool(),
        help="the command-line tool, at the same path on every worker (default: $MESHEXTRACTION, "
        "meshextraction on PATH, or the build tree's; now %(default)s)",
    )
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
    run.add_argument(
        "--task-threads",
        type=_positive,
        default=1,
        help="threads of the tool per case (extract --threads) (default: 1)",
    )
    run.add_argument("--mesh-format", default="vtk", choices=("vtk", "obj", "off", "gii", "byu"), help="(default: vtk)")
    run.add_argument(
        "--retries",
        type=int,
        default=3,
        help="retries of a task whose worker died or that raised; an error of the tool is not retried (default: 3)",
    )
    run.add_argument("--timeout", type=float, metavar="SECONDS", help="kill a command of the tool after this long")
    run.add_argument("--force", action="store_true", help="recompute every case, even those whose outputs verify")
    run.add_argument(
        "--dashboard", metavar="ADDRESS", help="serve the LocalCluster's Dask dashboard here (e.g. :8787; needs bokeh)"
    )
    run.add_argument("--title", default="Cohort report", help="the HTML report's title")
    model = commands.add_parser(
        "shape-model", help="the shape model of a cohort's meshes on Dask (not yet; see meshextraction shape-model)",
        add_help=True
    )
    model.add_argument("inputs", nargs="*", metavar="MANIFEST_OR_MESHES")
    return parser


def main(argv=None):
    parser = _parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 2
    if args.command == "shape-model":
        print(
            "meshextraction-cohort shape-model: not yet on Dask (the per-mesh matching as tasks and the PCA as their "
            "reduction); nothing was done. On one machine, `meshextraction shape-model MESH... --output MODEL.h5` "
            "builds the model; the meshes of a run are OUTDIR/cases/*/*.vtk.",
            file=sys.stderr,
        )
        return 2
    args.common_options = shlex.split(args.common_options)
    args.quality_options = shlex.split(args.quality_options)
    if os.sep not in args.meshextraction:
        args.meshextraction = shutil.which(args.meshextraction) or args.meshextraction
    args.meshextraction = os.path.abspath(args.meshextraction)
    local = not (args.scheduler or args.scheduler_file)
    if local and not (os.path.isfile(args.meshextraction) and os.access(args.meshextraction, os.X_OK)):
        parser.error(f"the command-line tool {args.meshextraction} is not an executable file: give --meshextraction")
    if args.workers is None:
        args.workers = max(1, (os.cpu_count() or 1) // args.task_threads)
    try:
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
    from .runner import run as run_cohort

    return run_cohort(cases, args)
