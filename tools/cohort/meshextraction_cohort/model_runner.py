"""The Dask side of `meshextraction-cohort shape-model`: the landmark-free shape model of
thesis chapter 7 over a cohort's meshes, made as the in-process `meshextraction shape-model
build` makes it, from steps of the command-line tool (model_task runs one):

  prepare   every mesh made ready (largest component, turned outward): a task per mesh.
            The pivot is the first mesh with the most points; it is the first template.
  pass P    every prepared mesh matched to the template (similarity ICP, non-rigid
            correspondence; from pass 2 on warm-started from the mesh's previous pass): a
            task per mesh; then the template renewed from the corresponded meshes: one
            task, the pass's reduction. No further pass once the template moved less than
            0.01 mm (RMS), as in the in-process build.
  finish    Procrustes analysis and PCA of the last pass's corresponded meshes: the model.

OUTDIR/
  prepared/NAME.ply, NAME.json          the prepared mesh; its points, triangles, dropped vertices
  pass-P/template.ply                   the template of pass P (the pivot's prepared mesh, then
                                        the previous pass's next-template.ply; hard links)
  pass-P/NAME.corresponded.ply          the template's points on mesh NAME, in its frame
  pass-P/NAME.state.json                e2 and the template-to-mesh similarity
  pass-P/next-template.ply              the renewed template
  pass-P/renewal.json                   its change (RMS, mm) and gauge
  corresponded/NAME.ply                 the last pass's corresponded meshes (hard links)
  model.h5, model.json                  the statismo model; its modes and variances
  report/index.html                     the model: compactness, the first modes rendered
  shape-model.json                      the build: inputs, pivot, passes, every step's time
  shape-model.log                       every command of every build, its output, time, memory
  steps/STEP/                           each step's record and log (outputs.verify_step)

A step runs unless its outputs verify: a rerun keeps every step whose record has the
fingerprint of its command and of its inputs (the size and time of the input mesh; the
checksums of the outputs it reads) and whose outputs have the checksums it recorded. So an
interrupted build resumes, a changed mesh or option recomputes what depends on it, and a
step recomputed to the same outputs leaves the steps after it as they are. model.h5,
model.json and corresponded/ are removed when a build starts to compute, so they are there
only when they are the current model.
"""

import concurrent.futures
import contextlib
import hashlib
import json
import os
import re
import shutil
import signal
import time
import uuid
from dataclasses import dataclass

from . import model_task, outputs
from .runner import dask_client, exclusive, raise_interrupt, remove_attempts, say, task_error

# mm: the in-process build's passTolerance; a pass whose template moved less is the last.
PASS_TOLERANCE = 0.01


class BuildFailed(Exception):
    """Steps failed: a shape model cannot be built without each of its meshes."""


@dataclass
class Step:
    step: str  # its folder under OUTDIR/steps/, unique in the build
    name: str  # the input it works on (None for a pass's renewal and the finish)
    label: str  # how messages name it
    command: list
    outputs: list  # absolute paths, the JSON last
    expect: tuple  # the keys of its JSON
    inputs: dict  # besides the command's arguments, what the outputs depend on

    def fingerprint(self):
        spec = {"command": self.command[1:], "inputs": self.inputs}  # not the tool's path
        return hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()


def _cumulative_percent(model):
    total, running, shares = model["total_variance"], 0.0, []
    for variance in model["variances"]:
        running += variance
        shares.append(100.0 * running / total if total else float("nan"))
    return shares


class Build:
    """One build of the model in OUTDIR; run() returns the model's summary (model.json)."""

    def __init__(self, meshes, args, run_id):
        self.meshes, self.args, self.run_id = meshes, args, run_id
        self.names = [name for name, _ in meshes]
        self.outdir = os.path.abspath(args.outdir)
        self.records = {}  # step -> record of this build's steps, kept or computed
        self.steps = []  # the steps of this build, in order
        self.pivot, self.changes = None, []
        self.client, self.description = None, "no cluster (every step was kept)"
        self.exits = contextlib.ExitStack()
        self.model_dropped = False
        self.log = self.exits.enter_context(open(os.path.join(self.outdir, "shape-model.log"), "ab"))

    def say(self, text, progress=False):
        """A line on the console (progress lines without the program's name) and in the log."""
        if progress:
            print(text, flush=True)
        else:
            say(text)
        self.log.write(f"# {text}\n".encode())
        self.log.flush()

    def path(self, *parts):
        return os.path.join(self.outdir, *parts)

    def pass_path(self, number, name):
        return self.path(f"pass-{number}", name)

    def new_step(self, step, name, label, verb, arguments, files, expect, inputs):
        """The step running `meshextraction shape-model VERB ARGUMENTS --json` whose outputs
        are `files` (the JSON last), with --thesis for match and renew when asked."""
        command = [self.args.meshextraction, "shape-model", verb, *arguments, "--json", model_task.staged(files[-1])]
        if self.args.thesis and verb in ("match", "renew"):
            command.append("--thesis")
        return Step(step, name, label, command, files, expect, inputs)

    def outputs_of(self, *steps):
        return {step: self.records[step]["outputs"] for step in steps}

    # The steps -----------------------------------------------------------------------------

    def prepare_step(self, name, mesh):
        ply, info = self.path("prepared", f"{name}.ply"), self.path("prepared", f"{name}.json")
        status = os.stat(mesh)
        return self.new_step(
            f"prepare-{name}",
            name,
            f"prepare {name} ({mesh})",
            "prepare",
            [mesh, "--output", ply],
            [ply, info],
            ("points", "triangles"),
            {"mesh": [status.st_size, status.st_mtime_ns]},
        )

    def match_step(self, number, name, mesh, template):
        corresponded = self.pass_path(number, f"{name}.corresponded.ply")
        state = self.pass_path(number, f"{name}.state.json")
        arguments = [template.path, self.path("prepared", f"{name}.ply"), "--output", corresponded]
        arguments += ["--correspondence", self.args.correspondence]
        inputs = {"template": template.outputs, "prepared": self.outputs_of(f"prepare-{name}")}
        if number > 1:
            arguments += ["--initial", self.pass_path(number - 1, f"{name}.state.json")]
            arguments += ["--gauge", self.pass_path(number - 1, "renewal.json")]
            inputs["previous"] = self.outputs_of(f"pass-{number - 1}-match-{name}", f"pass-{number - 1}-renew")
        return self.new_step(
            f"pass-{number}-match-{name}",
            name,
            f"pass {number} match {name} ({mesh})",
            "match",
            arguments,
            [corresponded, state],
            ("e2", "template_to_mesh", "corresponded"),
            inputs,
        )

    def matched(self, number):
        """The states of pass `number` in input order, and what they depend on."""
        states = [self.pass_path(number, f"{name}.state.json") for name in self.names]
        return states, self.outputs_of(*[f"pass-{number}-match-{name}" for name in self.names])

    def renew_step(self, number, template):
        renewed, renewal = self.pass_path(number, "next-template.ply"), self.pass_path(number, "renewal.json")
        states, matched = self.matched(number)
        return self.new_step(
            f"pass-{number}-renew",
            None,
            f"pass {number} renewal of the template",
            "renew",
            [template.path, *states, "--output", renewed],
            [renewed, renewal],
            ("change", "gauge"),
            {"template": template.outputs, "matched": matched},
        )

    def finish_step(self, number, template):
        states, matched = self.matched(number)
        arguments = [template.path, *states, "--output", self.path("model.h5"), "--pivot", str(self.pivot)]
        arguments += ["--passes", str(number), "--variance-fraction", repr(self.args.variance_fraction)]
        arguments += ["--report", self.path("report")]
        return self.new_step(
            "finish",
            None,
            "finish (Procrustes analysis and PCA)",
            "finish",
            arguments,
            [self.path("model.h5"), self.path("report", "index.html"), self.path("model.json")],
            ("modes", "variances", "all_variances", "total_variance"),
            {"template": template.outputs, "matched": matched},
        )

    # Running them ------------------------------------------------------------------------

    def stage(self, steps, title, noun, progress):
        """Runs the steps whose outputs do not verify, a task each, and waits for them;
        returns the results (the JSON) of all, in order. Raises BuildFailed when one failed
        (after the others finished: their outputs serve the rerun). progress(step, result,
        "3/10") says what a step did: (what, details)."""
        self.steps += steps
        if self.args.force:
            checks = [(None, "--force")] * len(steps)
        else:
            with concurrent.futures.ThreadPoolExecutor(8) as pool:
                checks = list(pool.map(lambda s: outputs.verify_step(self.outdir, s.step, s.fingerprint()), steps))
        todo = []
        for step, (record, _) in zip(steps, checks):
            if record is None:
                todo.append(step)
            else:
                self.records[step.step] = dict(record, computed=False)
        kept = len(steps) - len(todo)
        if kept:
            counted = f"{kept} of {len(steps)} " if len(steps) > 1 else ""
            self.say(f"{title}: {counted}{noun} kept from an earlier build", progress=True)
        if todo:
            self.compute(todo, title, progress)
        return [self.records[step.step]["result"] for step in steps]

    def connect(self):
        if self.client is None:
            self.client, self.description = self.exits.enter_context(dask_client(self.args))
            self.say(f"{self.description}; retries {self.args.retries}")
        return self.client

    def drop_model(self):
        """Before the first step this build computes: the model of an earlier build goes, so
        that OUTDIR has a model only when it is the model of its steps."""
        if self.model_dropped:
            return
        self.model_dropped = True
        for path in (self.path("model.h5"), self.path("model.json")):
            if os.path.exists(path):
                os.unlink(path)
        shutil.rmtree(self.path("corresponded"), ignore_errors=True)
        shutil.rmtree(self.path("report"), ignore_errors=True)

    def job(self, step):
        """What a worker needs for one step: plain data, so any worker can run it."""
        return {
            "step": step.step,
            "label": step.label,
            "directory": outputs.step_dir(self.outdir, step.step),
            "command": step.command,
            "outputs": step.outputs,
            "json": step.outputs[-1],
            "expect": step.expect,
            "fingerprint": step.fingerprint(),
            "outdir": self.outdir,
            "run_id": self.run_id,
            "timeout": self.args.timeout,
            "threads": self.args.task_threads,
        }

    def compute(self, todo, title, progress):
        from distributed import as_completed

        self.drop_model()
        client = self.connect()
        for step in todo:
            os.makedirs(os.path.dirname(step.outputs[0]), exist_ok=True)
        futures = {}
        for step in todo:
            future = client.submit(
                model_task.run_model_step,
                self.job(step),
                key=f"shape-model-{step.step}-{self.run_id}",
                pure=False,
                retries=self.args.retries,
            )
            futures[future] = step
        failed = []
        try:
            for done, future in enumerate(as_completed(futures), start=1):
                step = futures[future]
                try:
                    record = future.result()
                except Exception as error:  # the task's own exception after its retries, or KilledWorker
                    record = {"step": step.step, "status": "failed", "message": task_error(error, self.args.retries)}
                self.records[step.step] = dict(record, computed=True)
                self.copy_log(step)
                if record["status"] == "ok":
                    what, details = progress(step, record["result"], f"{done}/{len(todo)}")
                    seconds, memory = record["wall_seconds"], record["max_rss_mb"]
                    retry = f", attempt {record['attempts']}" if record["attempts"] > 1 else ""
                    self.say(f"{title}: {what} ({details}; {seconds:.2f} s, {memory:.0f} MB{retry})", progress=True)
                else:
                    failed.append(f"{step.label}: {record['message']}")
                    lines = (record["message"] or "no message").splitlines()
                    more = " ..." if len(lines) > 1 else ""
                    self.say(f"{title}: FAILED {step.label}: {lines[0]}{more}", progress=True)
        except KeyboardInterrupt:
            self.say(f"interrupted: cancelling the {title} steps")
            client.cancel(list(futures))
            raise
        if failed:
            raise BuildFailed(failed)

    def copy_log(self, step):
        """The step's log, appended to OUTDIR/shape-model.log."""
        directory = outputs.step_dir(self.outdir, step.step)
        with contextlib.suppress(OSError), open(os.path.join(directory, f"{step.step}.log"), "rb") as log:
            shutil.copyfileobj(log, self.log)
        self.log.flush()

    # The build -----------------------------------------------------------------------------

    def run(self):
        prepared = self.stage(
            [self.prepare_step(name, mesh) for name, mesh in self.meshes],
            "prepare",
            "prepared meshes",
            lambda step, info, count: (
                f"prepared {count} {step.name}",
                f"{info['points']} points, {info['triangles']} triangles"
                + (f", {info['dropped_vertices']} vertices dropped" if info.get("dropped_vertices") else ""),
            ),
        )
        points = [info["points"] for info in prepared]
        self.pivot = max(range(len(points)), key=lambda i: (points[i], -i))  # the first with the most
        pivot = self.names[self.pivot]
        self.say(f"pivot: {pivot} (input {self.pivot}, {points[self.pivot]} points), the first template")
        source = Template(self.path("prepared", f"{pivot}.ply"), f"prepare-{pivot}")
        for number in range(1, self.args.passes + 1):
            template = source.placed(self, number)
            self.stage(
                [self.match_step(number, name, mesh, template) for name, mesh in self.meshes],
                f"pass {number}",
                "matches",
                lambda step, state, count: (f"matched {count} {step.name}", f"e2 {state['e2']:.4g} mm²"),
            )
            (renewal,) = self.stage(
                [self.renew_step(number, template)],
                f"pass {number}",
                "the renewed template",
                lambda step, renewal, count: ("template renewed", f"moved {renewal['change']:.4g} mm"),
            )
            self.changes.append(renewal["change"])
            if renewal["change"] < PASS_TOLERANCE:
                break
            source = Template(self.pass_path(number, "next-template.ply"), f"pass-{number}-renew")
        (model,) = self.stage(
            [self.finish_step(number, template)],
            "model",
            "the model",
            lambda step, model, count: ("Procrustes analysis and PCA", f"{model['modes']} modes"),
        )
        os.makedirs(self.path("corresponded"), exist_ok=True)
        for name in self.names:
            outputs.link_atomically(
                self.pass_path(number, f"{name}.corresponded.ply"), self.path("corresponded", f"{name}.ply")
            )
        self.prune(number)
        return model

    def prune(self, passes):
        """Removes what earlier builds left that is not part of this one: the files of
        inputs no longer given, the passes beyond the last, the steps of neither."""
        names, numbers = self.names, range(1, passes + 1)
        steps = {f"prepare-{name}" for name in names} | {f"pass-{p}-renew" for p in numbers} | {"finish"}
        expected = {
            "prepared": {f"{name}{extension}" for name in names for extension in (".ply", ".json")},
            "corresponded": {f"{name}.ply" for name in names},
            "steps": steps | {f"pass-{p}-match-{name}" for p in numbers for name in names},
        }
        for p in numbers:
            per_mesh = {f"{name}{extension}" for name in names for extension in (".corresponded.ply", ".state.json")}
            expected[f"pass-{p}"] = per_mesh | {"template.ply", "next-template.ply", "renewal.json"}
        stale = [f for f in os.listdir(self.outdir) if re.fullmatch(r"pass-\d+", f) and f not in expected]
        stale += [os.path.join(f, e) for f, kept in expected.items() for e in set(os.listdir(self.path(f))) - kept]
        for path in map(self.path, stale):
            if os.path.isdir(path):
                shutil.rmtree(path, ignore_errors=True)
            else:
                os.unlink(path)

    def close(self, interrupted):
        """Stops the cluster; after an interruption on the LocalCluster, removes what its
        cancelled steps left (attempt folders, the tool's partial files)."""
        self.exits.close()
        if interrupted and self.client is not None and not (self.args.scheduler or self.args.scheduler_file):
            remove_attempts(self.outdir, self.run_id, "steps")
            for step in self.steps:
                for path in step.outputs:
                    outputs.remove_partial_files(path)

    def summary(self, status, message, model, started):
        """OUTDIR/shape-model.json: the inputs, the pivot, the passes, the model, every step."""
        rows = []
        for step in self.steps:
            record = self.records.get(step.step)
            if record is None:
                rows.append({"step": step.step, "status": "not run"})
                continue
            this_run = "computed" if record["computed"] else "kept"
            row = {"step": step.step, "status": record["status"], "this_run": this_run}
            for key in ("attempts", "wall_seconds", "cpu_seconds", "max_rss_mb", "worker", "message"):
                row[key] = record.get(key)
            rows.append(row)
        document = {
            "status": status,
            "message": message,
            "run_id": self.run_id,
            "cluster": self.description,
            "wall_seconds": round(time.time() - started, 3),
            "options": {
                "passes": self.args.passes,
                "variance_fraction": self.args.variance_fraction,
                "correspondence": self.args.correspondence,
                "thesis": self.args.thesis,
            },
            "inputs": [{"name": name, "mesh": mesh} for name, mesh in self.meshes],
            "pivot": self.pivot,
            "template_changes": self.changes,
            "model": model,
            "steps": rows,
        }
        outputs.write_json_atomically(self.path("shape-model.json"), document)
        return rows


@dataclass
class Template:
    """A template: the file a step made (the pivot's prepared mesh, a renewed template),
    and, once placed as a pass's template.ply, that path and the checksums of the step's
    outputs (what the steps that read the template depend on)."""

    source: str
    step: str
    path: str = None
    outputs: dict = None

    def placed(self, build, number):
        """The template as pass `number`'s template.ply (a hard link to its source)."""
        path = build.pass_path(number, "template.ply")
        os.makedirs(os.path.dirname(path), exist_ok=True)
        outputs.link_atomically(self.source, path)
        return Template(self.source, self.step, path, build.outputs_of(self.step))


def _final_lines(meshes, model, rows, outdir, changes, pivot):
    shares = " ".join(f"{k}:{share:.1f}" for k, share in enumerate(_cumulative_percent(model), start=1))
    computed = sum(row.get("this_run") == "computed" for row in rows)
    moves = ", ".join(f"{change:.4g}" for change in changes)
    return [
        f"shape model of {len(meshes)} meshes: pivot {meshes[pivot][0]} (input {pivot}), "
        f"{len(changes)} pass{'es' if len(changes) > 1 else ''} "
        f"(template moved {moves} mm), {model['modes']} modes; cumulative variance (%): {shares}",
        f"{computed} steps computed, {len(rows) - computed} kept; model {os.path.join(outdir, 'model.h5')} "
        f"({os.path.join(outdir, 'model.json')}), corresponded meshes in {os.path.join(outdir, 'corresponded')}",
    ]


def build_model(meshes, args):
    """The `shape-model` command; returns the exit status (0 built, 1 a step failed, 130
    interrupted)."""
    signal.signal(signal.SIGTERM, raise_interrupt)
    run_id = time.strftime("%Y%m%dT%H%M%S") + "-" + uuid.uuid4().hex[:6]
    started = time.time()
    with exclusive(args.outdir):
        build = Build(meshes, args, run_id)
        build.say(f"shape model of {len(meshes)} meshes in {build.outdir} (build {run_id})")
        status, failures, model = "interrupted", [], None
        try:
            model = build.run()
            status = "ok"
        except BuildFailed as failure:
            status, failures = "failed", failure.args[0]
        except KeyboardInterrupt:
            pass
        finally:
            build.close(interrupted=status == "interrupted")
        rows = build.summary(status, "\n".join(failures) or None, model, started)
    if status == "ok":
        for line in _final_lines(meshes, model, rows, build.outdir, build.changes, build.pivot):
            say(line)
        return 0
    if status == "failed":
        say(f"the shape model cannot be built: {len(failures)} step(s) failed:")
        for line in failures:
            print(f"  {line}", flush=True)
        return 1
    say("interrupted; rerun the same command to resume")
    return 130
