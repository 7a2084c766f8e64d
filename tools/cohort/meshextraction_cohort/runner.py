"""The Dask side of `meshextraction-cohort run`: find the cases whose outputs already verify,
submit the others to a LocalCluster or an existing scheduler, record every result as it
comes, and write the summary and the report (also when interrupted).

Retries: a task whose worker dies is put back by the scheduler up to
distributed.scheduler.allowed-failures times (set from --retries for the LocalCluster; a
running scheduler keeps its own setting), then fails with KilledWorker; a task that raises
(a file-system error) is retried --retries times by Dask. An error of the command-line
tool is not retried: it is the case's result, recorded with its message.
"""

import concurrent.futures
import contextlib
import fcntl
import glob
import importlib
import logging
import os
import shutil
import signal
import time
import uuid

from . import model_task, outputs, report, task


def say(text):
    print(f"meshextraction-cohort: {text}", flush=True)


@contextlib.contextmanager
def exclusive(outdir):
    """One run at a time per output folder (a lock that dies with its process)."""
    os.makedirs(outdir, exist_ok=True)
    with open(os.path.join(outdir, ".lock"), "w") as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise SystemExit(f"meshextraction-cohort: another run is writing to {outdir}") from None
        yield


def plan(cases, outdir, common_options, force, threads=8):
    """For each case: (case, fingerprint, verified record or None, why it runs)."""
    fingerprints = [case.fingerprint(common_options) for case in cases]
    if force:
        return [(c, f, None, "--force") for c, f in zip(cases, fingerprints)]
    with concurrent.futures.ThreadPoolExecutor(threads) as pool:
        checks = list(pool.map(lambda cf: outputs.verify(outdir, cf[0].case_id, cf[1]), zip(cases, fingerprints)))
    return [(c, f, record, why) for c, f, (record, why) in zip(cases, fingerprints, checks)]


def make_job(case, fingerprint, args, run_id):
    """What a worker needs for one case: plain data, so any worker can run it."""
    return {
        "case": case.as_dict(),
        "surfaces": [{"name": s.name, "arguments": list(s.arguments)} for s in case.surfaces()],
        "fingerprint": fingerprint,
        "outdir": os.path.abspath(args.outdir),
        "tool": args.meshextraction,
        "common_options": list(args.common_options),
        "quality_options": list(args.quality_options),
        "task_threads": args.task_threads,
        "mesh_format": args.mesh_format,
        "timeout": args.timeout,
        "run_id": run_id,
    }


@contextlib.contextmanager
def dask_client(args):
    """A distributed Client on the given scheduler, or on a LocalCluster of --workers
    single-threaded worker processes; yields (client, description)."""
    import cloudpickle
    import dask
    import distributed

    # Ship this package's code with each task, so the workers of an existing cluster need
    # only Dask, not this package on their Python path. Dask pickles a function by value only
    # when its own module is registered, so the tasks' modules are registered besides the
    # package (whose registration covers the modules the tasks use).
    cloudpickle.register_pickle_by_value(importlib.import_module(__package__))
    cloudpickle.register_pickle_by_value(task)
    cloudpickle.register_pickle_by_value(model_task)
    cluster = None
    if args.scheduler or args.scheduler_file:
        client = distributed.Client(args.scheduler, scheduler_file=args.scheduler_file, timeout="60s")
        workers = len(client.scheduler_info().get("workers", {}))
        description = f"scheduler {client.scheduler.address} ({workers} workers now)"
    else:
        dask.config.set({"distributed.scheduler.allowed-failures": args.retries})
        cluster = distributed.LocalCluster(
            n_workers=args.workers,
            threads_per_worker=1,
            processes=True,
            dashboard_address=args.dashboard,
            silence_logs=logging.ERROR,
        )
        client = distributed.Client(cluster)
        _workers_ignore_interrupt(client)
        description = f"LocalCluster of {args.workers} worker processes x 1 thread"
    try:
        yield client, description
    finally:
        with contextlib.suppress(Exception):
            client.close(timeout=30)
        if cluster is not None:
            with contextlib.suppress(Exception):
                cluster.close(timeout=30)


def _workers_ignore_interrupt(client):
    """The LocalCluster's workers share the client's terminal, so Ctrl-C reaches them too: it
    is the client's to handle (it cancels the tasks and stops the cluster), and the tool runs
    in a session of its own, so an interrupted case is not recorded as failed."""
    from distributed.diagnostics.plugin import WorkerPlugin

    class IgnoreInterrupt(WorkerPlugin):
        name = "meshextraction-cohort-ignore-interrupt"

        def setup(self, worker):
            with contextlib.suppress(ValueError):  # not the main thread: nothing to do
                signal.signal(signal.SIGINT, signal.SIG_IGN)

    client.register_worker_plugin(IgnoreInterrupt())


def _failure_record(case, fingerprint, run_id, message):
    return {
        "version": outputs.RECORD_VERSION,
        "case": case.case_id,
        "image": case.image,
        "fingerprint": fingerprint,
        "run_id": run_id,
        "status": "failed",
        "message": message,
        "attempts": None,
        "steps": [],
        "surfaces": [],
    }


def task_error(error, retries):
    from distributed.scheduler import KilledWorker

    if isinstance(error, KilledWorker):
        return f"its worker died more often than the scheduler allows (KilledWorker): {error}"
    return f"task error after {retries} retries: {type(error).__name__}: {error}"


def _progress_line(done, total, record):
    case = record["case"]
    if record["status"] != "ok":
        lines = (record.get("message") or "no message").splitlines()
        text = lines[0] if len(lines) == 1 else f"{lines[0]} ... {lines[-1]}"
        return f"[{done:>{len(str(total))}}/{total}] FAILED {case}: {text}"
    qualities = [s for s in record["surfaces"] if s.get("q_area_mean") is not None]
    q_area = min(s["q_area_mean"] for s in qualities) if qualities else float("nan")
    q_angle = min(s["q_angle_min"] for s in qualities) if qualities else float("nan")
    retry = f", attempt {record['attempts']}" if (record.get("attempts") or 1) > 1 else ""
    return (
        f"[{done:>{len(str(total))}}/{total}] ok {case}: {record['wall_seconds']:.2f} s, "
        f"{record['max_rss_mb']:.0f} MB, q_area {q_area:.3f}, min q_angle {q_angle:.3f}{retry}"
    )


def _compute(client, todo, args, run_id, records):
    """Submits the cases and records each result as it arrives; returns the cases the run
    did not finish (non-empty when interrupted)."""
    from distributed import as_completed

    futures = {}
    for case, fingerprint, _, _ in todo:
        job = make_job(case, fingerprint, args, run_id)
        future = client.submit(
            task.run_case, job, key=f"extract-{case.case_id}-{run_id}", pure=False, retries=args.retries
        )
        futures[future] = (case, fingerprint)
    pending = {case.case_id for case, _, _, _ in todo}
    try:
        for done, future in enumerate(as_completed(futures), start=1):
            case, fingerprint = futures[future]
            try:
                record = future.result()
            except Exception as error:  # the task's own exception after its retries, or KilledWorker
                record = _failure_record(case, fingerprint, run_id, task_error(error, args.retries))
                directory = outputs.case_dir(args.outdir, case.case_id)
                os.makedirs(directory, exist_ok=True)
                outputs.write_json_atomically(outputs.record_path(args.outdir, case.case_id), record)
            record["computed"] = True
            records[case.case_id] = record
            pending.discard(case.case_id)
            print(_progress_line(done, len(todo), record), flush=True)
    except KeyboardInterrupt:
        say(f"interrupted: {len(todo) - len(pending)} of {len(todo)} cases finished; cancelling the rest")
        client.cancel(list(futures))
    return pending


def remove_attempts(outdir, run_id, tasks="cases"):
    """After the LocalCluster is closed no task of this run is running: remove the attempt
    folders that cancelled tasks left in the tasks' folders (OUTDIR/cases/*, OUTDIR/steps/*)."""
    for folder in glob.glob(os.path.join(outdir, tasks, "*", f".attempt-{run_id}-*")):
        shutil.rmtree(folder, ignore_errors=True)


def _adopt_committed(outdir, todo, pending, run_id, records):
    """An interrupted run's cases whose task committed its record before the client saw the
    result: they are done (and a rerun keeps them), so the summary counts them."""
    for case, fingerprint, _, _ in todo:
        if case.case_id not in pending:
            continue
        record = outputs.read_json(outputs.record_path(outdir, case.case_id))
        if record is None or record.get("run_id") != run_id:
            continue
        if record.get("status") == "ok" and outputs.verify(outdir, case.case_id, fingerprint)[0] is None:
            continue
        records[case.case_id] = dict(record, computed=True)
    return pending - set(records)


def raise_interrupt(signum, frame):
    raise KeyboardInterrupt


def run(cases, args):
    """The `run` command; returns the exit status (0 all ok, 1 some failed, 130 interrupted)."""
    signal.signal(signal.SIGTERM, raise_interrupt)
    run_id = time.strftime("%Y%m%dT%H%M%S") + "-" + uuid.uuid4().hex[:6]
    started = time.time()
    with exclusive(args.outdir):
        planned = plan(cases, args.outdir, args.common_options, args.force)
        records = {c.case_id: dict(r, computed=False) for c, _, r, _ in planned if r is not None}
        todo = [p for p in planned if p[2] is None]
        say(f"{len(cases)} cases; {len(records)} with verified outputs kept, {len(todo)} to run")
        pending, description = set(), "nothing to run"
        if todo:
            try:
                with dask_client(args) as (client, description):
                    say(f"{description}; retries {args.retries}")
                    if client.dashboard_link and args.dashboard:
                        say(f"Dask dashboard: {client.dashboard_link}")
                    pending = _compute(client, todo, args, run_id, records)
            except KeyboardInterrupt:
                pending = {c.case_id for c, _, _, _ in todo} - set(records)
                say("interrupted while starting or stopping the cluster")
            if not (args.scheduler or args.scheduler_file):
                remove_attempts(args.outdir, run_id)
            pending = _adopt_committed(args.outdir, todo, pending, run_id, records)
        totals = report.write_all(args, cases, records, pending, description, started, run_id)
    say(
        f"{totals['succeeded']} succeeded ({totals['reused']} kept from earlier runs), {totals['failed']} failed, "
        f"{totals['retried']} retried, {totals['not_run']} not run; "
        f"{os.path.join(args.outdir, 'summary.csv')}, {os.path.join(args.outdir, 'report.html')}"
    )
    if pending:
        say("rerun the same command to compute the rest")
        return 130
    return 1 if totals["failed"] else 0
