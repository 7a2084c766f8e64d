"""One step of a shape model on a Dask worker: a `meshextraction shape-model` command
(prepare, match, renew or finish) run in an attempt folder of the step's folder
steps/STEP/, and its outputs committed.

The tool writes its mesh or model whole under the final name (it writes a partial file and
renames it when complete). Its --json is a name in the attempt folder (the command runs
there), renamed into place when the command succeeded and the JSON reads; then the step's
record, with the checksums of the outputs, is renamed into steps/STEP/, last (task.commit).
A step that fails removes the outputs an earlier run left for it. As for `run`, an error of
the tool is the step's result, recorded with its message; an exception here (a file-system
error) propagates so that Dask retries the task.
"""

import os
import shutil
import socket
import time

from . import outputs, task

# The attempt folder's subfolder for the command's JSON (apart from the attempt's own files).
_STAGING = "out"


def staged(path):
    """The --json argument for the final path `path`: a name in the attempt's staging folder."""
    return os.path.join(_STAGING, os.path.basename(path))


def _read_result(job, attempt):
    """(the JSON the command wrote, None), or (None, why it is not a result)."""
    name = os.path.basename(job["json"])
    result = outputs.read_json(os.path.join(attempt, _STAGING, name))
    if not isinstance(result, dict):
        return None, f"the tool wrote no JSON object to {name}"
    missing = [key for key in job["expect"] if key not in result]
    if missing:
        return None, f"{name} has no {', '.join(missing)}"
    absent = [path for path in job["outputs"] if path != job["json"] and not os.path.isfile(path)]
    if absent:
        return None, f"the tool did not write {', '.join(absent)}"
    return result, None


def run_model_step(job):
    """The Dask task: one step, start to commit. Returns the step's record."""
    directory = job["directory"]
    number, attempt = task.start_attempt(directory, job["run_id"])
    os.mkdir(os.path.join(attempt, _STAGING))
    for path in job["outputs"]:
        outputs.remove_partial_files(path)
    started = time.time()
    with open(os.path.join(attempt, f"{job['step']}.log"), "wb") as log:
        log.write(f"# {job['label']}, attempt {number}, worker {task.worker_address()} pid {os.getpid()}\n".encode())
        step = task.run_step(job["step"], job["command"], attempt, log, job.get("timeout"), job["threads"])
        result, failure = None, step.get("message")
        if step["status"] == 0:
            result, failure = _read_result(job, attempt)
        if failure is not None:
            log.write(f"# FAILED: {failure}\n".encode())
    digests = {}
    if failure is None:
        os.replace(os.path.join(attempt, _STAGING, os.path.basename(job["json"])), job["json"])
        digests = {os.path.relpath(path, job["outdir"]): outputs.sha256(path) for path in job["outputs"]}
    else:
        for path in job["outputs"]:
            if os.path.exists(path):
                os.unlink(path)
    record = {
        "version": outputs.RECORD_VERSION,
        "step": job["step"],
        "label": job["label"],
        "fingerprint": job["fingerprint"],
        "run_id": job["run_id"],
        "status": "failed" if failure else "ok",
        "message": failure,
        "attempts": number,
        "worker": task.worker_address(),
        "host": socket.gethostname(),
        "pid": os.getpid(),
        "started": round(started, 3),
        "wall_seconds": round(time.time() - started, 4),
        "cpu_seconds": step["cpu_seconds"],
        "max_rss_mb": step["max_rss_mb"],
        "steps": [step],
        "outputs": digests,
        "result": result,
    }
    task.commit(directory, attempt, record, [])
    shutil.rmtree(attempt, ignore_errors=True)
    return record
