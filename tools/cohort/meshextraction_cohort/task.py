"""One case on a Dask worker: extract each surface with `meshextraction extract`, measure the
written mesh with `meshextraction quality`, and commit the outputs.

An attempt works in its own folder, cases/CASE/.attempt-RUN-XXXXXXXX/, where every file
has its final name (so the quality JSON names the mesh as it will be called). When every
surface is extracted and valid, the files are renamed into cases/CASE/ and the record is
renamed last. A worker that dies leaves only its attempt folder; the retry counts and
removes such folders, so the record says how many attempts the case took.

The command-line tool runs under `setpriv --pdeathsig KILL` where util-linux has it, so a
killed worker does not leave its extraction running, and under GNU time where it is
installed, which measures the tool's own peak memory. It runs in a session of its own, so
a Ctrl-C meant for the client does not kill it (the client stops the workers, and with
them the tool). Errors of the tool (an unreadable
image, an invalid surface) are results, recorded with their message; an exception here
(a file-system error) propagates so that Dask retries the task.
"""

import json
import os
import shlex
import shutil
import signal
import socket
import subprocess
import threading
import time
import uuid

from . import outputs

_MESSAGE_LIMIT = 2000
_TIME_FORMAT = "%M %e %U %S"
_probed = {}


def _works(command):
    try:
        return subprocess.run(command, capture_output=True).returncode == 0
    except OSError:
        return False


def _helpers():
    """The helpers this system has, probed once per worker process: setpriv with
    --pdeathsig (util-linux), so that a killed worker's extraction dies with it; GNU time,
    which measures the tool's own peak memory (wait4 on the worker's direct child counts
    the worker's size at fork too)."""
    if not _probed:
        setpriv, gnu_time = shutil.which("setpriv"), shutil.which("time")
        death = [setpriv, "--pdeathsig", "KILL", "--"] if setpriv else []
        _probed["death"] = death if death and _works(death + ["true"]) else []
        _probed["time"] = (
            gnu_time if gnu_time and _works([gnu_time, "-f", _TIME_FORMAT, "-o", os.devnull, "true"]) else None
        )
    return _probed["death"], _probed["time"]


def _launch_prefix(time_file):
    death, gnu_time = _helpers()
    if gnu_time is None:
        return death
    return death + [gnu_time, "-f", _TIME_FORMAT, "-o", time_file, "--"] + death


def _read_time_file(path, status):
    """(status, peak memory in MB, CPU seconds) from GNU time's output file, or None."""
    try:
        with open(path) as stream:
            lines = stream.read().splitlines()
        peak_kb, _, user, system = lines[-1].split()
    except (OSError, ValueError, IndexError):
        return None
    for line in lines[:-1]:
        if line.startswith("Command terminated by signal"):
            status = -int(line.split()[-1])
    return status, int(peak_kb) / 1024.0, float(user) + float(system)


def _error_message(stderr_text, status):
    lines = [line.rstrip() for line in stderr_text.splitlines() if line.strip()]
    if status < 0:
        name = signal.Signals(-status).name if -status in signal.valid_signals() else str(-status)
        reason = f"killed by {name}"
        if -status == signal.SIGKILL:
            reason += " (out of memory, the time limit, or killed by hand)"
        return reason
    for i, line in enumerate(lines):
        if "error:" in line:
            return "\n".join(lines[i:])[:_MESSAGE_LIMIT]
    return "\n".join(lines[-5:])[:_MESSAGE_LIMIT] or f"exit status {status}"


def run_step(name, command, cwd, log, timeout=None, threads=None):
    """Runs one command, its output appended to the log; returns its status, wall and CPU
    time and peak resident memory (of the tool's process alone)."""
    stderr_path = os.path.join(cwd, f".{name.replace(' ', '-')}.stderr")
    time_path = os.path.join(cwd, f".{name.replace(' ', '-')}.time")
    log.write(f"$ {shlex.join(command)}\n".encode())
    log.flush()
    # ITK's filters that take no thread count (the quality command's) use every core: hold
    # them to the task's share, so that one task per core does not oversubscribe the cores.
    env = dict(os.environ, ITK_GLOBAL_DEFAULT_NUMBER_OF_THREADS=str(threads)) if threads else None
    started = time.monotonic()
    with open(stderr_path, "w+b") as stderr:
        process = subprocess.Popen(
            _launch_prefix(time_path) + command, cwd=cwd, stdout=log, stderr=stderr, start_new_session=True, env=env
        )
        expired = threading.Event()
        timer = threading.Timer(timeout, lambda: (expired.set(), process.kill())) if timeout else None
        if timer:
            timer.start()
        try:
            _, wait_status, usage = os.wait4(process.pid, 0)
        finally:
            if timer:
                timer.cancel()
        process.returncode = status = os.waitstatus_to_exitcode(wait_status)
        seconds = time.monotonic() - started
        stderr.seek(0)
        stderr_text = stderr.read().decode(errors="replace")
    os.unlink(stderr_path)
    measured = _read_time_file(time_path, status) if status >= 0 else None
    if os.path.exists(time_path):
        os.unlink(time_path)
    if measured:
        status, peak_mb, cpu = measured
    else:
        peak_mb, cpu = usage.ru_maxrss / 1024.0, usage.ru_utime + usage.ru_stime
    log.write(stderr_text.encode())
    step = {
        "step": name,
        "status": status,
        "seconds": round(seconds, 4),
        "cpu_seconds": round(cpu, 4),
        "max_rss_mb": round(peak_mb, 2),
    }
    log.write(
        f"# {name}: exit status {status}, {step['seconds']} s, CPU {step['cpu_seconds']} s, "
        f"peak memory {step['max_rss_mb']} MB\n\n".encode()
    )
    log.flush()
    if status != 0:
        step["message"] = _error_message(stderr_text, status)
        if expired.is_set():
            step["message"] = f"stopped after the time limit of {timeout} s (--timeout)"
    return step


def start_attempt(directory, run_id):
    """Removes what earlier attempts left in a task's folder (a dead worker's attempt
    folder, a stale record, named after the folder) and makes this attempt's folder; the
    number counts this run's earlier attempts."""
    os.makedirs(directory, exist_ok=True)
    earlier = [d for d in os.listdir(directory) if d.startswith(".attempt-")]
    number = 1 + sum(d.startswith(f".attempt-{run_id}-") for d in earlier)
    for d in earlier:
        shutil.rmtree(os.path.join(directory, d), ignore_errors=True)
    stale = os.path.join(directory, f"{os.path.basename(directory)}.result.json")
    if os.path.exists(stale):
        os.unlink(stale)
    attempt = os.path.join(directory, f".attempt-{run_id}-{uuid.uuid4().hex[:8]}")
    os.mkdir(attempt)
    outputs.write_json_atomically(
        os.path.join(attempt, "attempt.json"), {"pid": os.getpid(), "host": socket.gethostname(), "number": number}
    )
    return number, attempt


def _surface_summary(surface, mesh_path, quality):
    q_area, q_angle = quality.get("q_area", {}), quality.get("q_angle", {})
    return {
        "name": surface["name"],
        "mesh": os.path.basename(mesh_path),
        "quality_json": f"{surface['name']}.quality.json",
        "mesh_bytes": os.path.getsize(mesh_path),
        "mesh_sha256": outputs.sha256(mesh_path),
        "valid": quality.get("valid_closed_surface") is True,
        "points": quality.get("points"),
        "triangles": quality.get("triangles"),
        "q_area_mean": q_area.get("mean"),
        "q_area_min": q_area.get("min"),
        "q_angle_mean": q_angle.get("mean"),
        "q_angle_min": q_angle.get("min"),
        "q_angle_below_0_3": quality.get("fraction_q_angle_below_0_3"),
        "q_area_histogram": q_area.get("histogram"),
        "q_angle_histogram": q_angle.get("histogram"),
    }


def _invalid_reason(quality):
    keys = (
        "boundary_edges",
        "non_manifold_edges",
        "non_manifold_vertices",
        "degenerate_triangles",
        "inverted_triangles_vs_outward",
        "inconsistently_oriented_edges",
        "self_intersecting_pairs",
    )
    found = ", ".join(f"{quality[k]} {k.replace('_', ' ')}" for k in keys if quality.get(k, 0) > 0)
    return "not a valid closed surface" + (f": {found}" if found else "")


def _extract_surface(job, surface, attempt, log):
    """Extracts and measures one surface in the attempt folder; returns (steps, summary or
    None, failure message or None)."""
    mesh = f"{surface['name']}.{job['mesh_format']}"
    quality_json = f"{surface['name']}.quality.json"
    tool, case = job["tool"], job["case"]
    extract = [tool, "extract", case["image"], mesh, "--threads", str(job["task_threads"])]
    extract += list(surface["arguments"]) + list(job["common_options"]) + list(case["options"])
    steps = [run_step(f"extract {surface['name']}", extract, attempt, log, job.get("timeout"), job["task_threads"])]
    if steps[-1]["status"] != 0:
        return steps, None, f"extract {surface['name']}: {steps[-1]['message']}"
    measure = [tool, "quality", mesh, "--json", quality_json] + list(job["quality_options"])
    steps.append(run_step(f"quality {surface['name']}", measure, attempt, log, job.get("timeout"), job["task_threads"]))
    if steps[-1]["status"] != 0:
        return steps, None, f"quality {surface['name']}: {steps[-1]['message']}"
    quality = outputs.quality_of(os.path.join(attempt, quality_json))
    if quality is None:
        return steps, None, f"quality {surface['name']}: {quality_json} is not a quality report"
    summary = _surface_summary(surface, os.path.join(attempt, mesh), quality)
    if not summary["valid"]:
        return steps, summary, f"{surface['name']}: {_invalid_reason(quality)}"
    return steps, summary, None


def worker_address():
    try:
        from distributed import get_worker

        return get_worker().address
    except (ImportError, ValueError):
        return None


def commit(directory, attempt, record, planned_files):
    """Moves the attempt's files into the task's folder, then its log and its record, both
    named after the folder, the record last. A failed task removes the outputs an earlier
    run left for it, so nothing looks done that is not."""
    task_id = os.path.basename(directory)
    for name in planned_files:
        if record["status"] == "ok":
            os.replace(os.path.join(attempt, name), os.path.join(directory, name))
        elif os.path.exists(os.path.join(directory, name)):
            os.unlink(os.path.join(directory, name))
    os.replace(os.path.join(attempt, f"{task_id}.log"), os.path.join(directory, f"{task_id}.log"))
    outputs.write_json_atomically(os.path.join(attempt, f"{task_id}.result.json"), record)
    os.replace(os.path.join(attempt, f"{task_id}.result.json"), os.path.join(directory, f"{task_id}.result.json"))


def run_case(job):
    """The Dask task: one case, start to commit. Returns the case's record."""
    case_id = job["case"]["case"]
    directory = outputs.case_dir(job["outdir"], case_id)
    number, attempt = start_attempt(directory, job["run_id"])
    started = time.time()
    steps, surfaces, failure = [], [], None
    with open(os.path.join(attempt, f"{case_id}.log"), "wb") as log:
        log.write(f"# case {case_id}, attempt {number}, worker {worker_address()} pid {os.getpid()}\n".encode())
        log.write(f"# case specification: {json.dumps(job['case'], sort_keys=True)}\n\n".encode())
        for surface in job["surfaces"]:
            surface_steps, summary, failure = _extract_surface(job, surface, attempt, log)
            steps += surface_steps
            if summary is not None:
                surfaces.append(summary)
            if failure is not None:
                log.write(f"# FAILED: {failure}\n".encode())
                break
    record = {
        "version": outputs.RECORD_VERSION,
        "case": case_id,
        "image": job["case"]["image"],
        "fingerprint": job["fingerprint"],
        "run_id": job["run_id"],
        "status": "failed" if failure else "ok",
        "message": failure,
        "attempts": number,
        "worker": worker_address(),
        "host": socket.gethostname(),
        "pid": os.getpid(),
        "started": round(started, 3),
        "wall_seconds": round(time.time() - started, 4),
        "cpu_seconds": round(sum(s["cpu_seconds"] for s in steps), 4),
        "max_rss_mb": max((s["max_rss_mb"] for s in steps), default=0.0),
        "steps": steps,
        "surfaces": surfaces,
    }
    planned = [
        f"{s['name']}{suffix}" for s in job["surfaces"] for suffix in (f".{job['mesh_format']}", ".quality.json")
    ]
    commit(directory, attempt, record, planned)
    shutil.rmtree(attempt, ignore_errors=True)
    return record
