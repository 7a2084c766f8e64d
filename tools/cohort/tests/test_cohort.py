"""Tests of meshextraction-cohort on a LocalCluster: a synthetic cohort of random phantoms plus
one corrupt image; a worker killed by pid in the middle of a run; the client interrupted and
rerun; the same outputs for 1 and 2 workers; the manifest reader; the shape model of a
population of meshes against the in-process build, resumed, and with a bad input.

  python3 test_cohort.py MESHEXTRACTION WORKDIR [unittest arguments, e.g. WorkerKilledTest]

Exits 77 (CTest's skip code here) with a message when this Python has no dask.distributed.
"""

import csv
import glob
import json
import os
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
COHORT = os.path.dirname(HERE)
sys.path.insert(0, COHORT)
sys.path.insert(0, HERE)

import synthetic  # noqa: E402
from meshextraction_cohort import manifest, outputs  # noqa: E402

TOOL = None
WORK = None


def cohort_command(*arguments):
    return [sys.executable, os.path.join(COHORT, "meshextraction-cohort")] + list(arguments)


def run_cohort(manifest_path, outdir, *options, timeout=240):
    """Runs `meshextraction-cohort run`; returns (exit status, output)."""
    command = cohort_command("run", manifest_path, outdir, "--meshextraction", TOOL, *options)
    result = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    return result.returncode, result.stdout + result.stderr


def fresh_dir(name):
    path = os.path.join(WORK, name)
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


def summary(outdir):
    with open(os.path.join(outdir, "summary.json")) as stream:
        return json.load(stream)


def file_digests(outdir):
    """sha256 of every mesh and quality JSON of the run, by path relative to OUTDIR."""
    digests = {}
    for path in sorted(glob.glob(os.path.join(outdir, "cases", "*", "*"))):
        if path.endswith((".vtk", ".quality.json")):
            digests[os.path.relpath(path, outdir)] = outputs.sha256(path)
    return digests


class CohortAssertions(unittest.TestCase):
    def assert_cohort_complete(self, outdir, cases, common_options=(), expect_failed=("corrupt",)):
        """Every case exactly once in the summary; the good ones valid with one mesh each that
        verifies and that the tool itself reads as a valid closed surface; the failed ones
        with their message; no attempt folder or temporary file left."""
        rows = summary(outdir)["cases"]
        self.assertEqual(sorted(r["case"] for r in rows), sorted(c.case_id for c in cases))
        for case in cases:
            row = next(r for r in rows if r["case"] == case.case_id)
            if case.case_id in expect_failed:
                self.assertEqual(row["status"], "failed", row)
                continue
            self.assertEqual(row["status"], "ok", row)
            record, why = outputs.verify(outdir, case.case_id, case.fingerprint(list(common_options)))
            self.assertIsNotNone(record, f"{case.case_id}: {why}")
            meshes = glob.glob(os.path.join(outputs.case_dir(outdir, case.case_id), "*.vtk"))
            self.assertEqual(len(meshes), len(case.surfaces()), meshes)
        leftovers = glob.glob(os.path.join(outdir, "cases", "*", ".attempt-*"))
        leftovers += glob.glob(os.path.join(outdir, "**", "*.tmp-*"), recursive=True)
        self.assertEqual(leftovers, [])
        meshes = sorted(glob.glob(os.path.join(outdir, "cases", "*", "*.vtk")))
        check = subprocess.run([TOOL, "quality", *meshes, "--require-valid"], capture_output=True, text=True)
        self.assertEqual(check.returncode, 0, check.stdout[-2000:] + check.stderr[-2000:])


class SyntheticCohortTest(CohortAssertions):
    """~20 random phantoms and one corrupt image on 2 workers: every good case valid, the bad
    one reported with its message, in the summary, the records and the report."""

    def test_synthetic_cohort(self):
        work = fresh_dir("synthetic")
        manifest_path = synthetic.make_cohort(TOOL, work, count=20)
        cases = manifest.read_manifest(manifest_path)
        outdir = os.path.join(work, "out")
        status, output = run_cohort(manifest_path, outdir, "--workers", "2")
        self.assertEqual(status, 1, output)
        self.assertIn("20 succeeded (0 kept from earlier runs), 1 failed, 0 retried, 0 not run", output)
        self.assertEqual(output.count("] ok case-"), 20, output)
        self.assert_cohort_complete(outdir, cases)
        failed = next(r for r in summary(outdir)["cases"] if r["case"] == "corrupt")
        self.assertIn("cannot read image", failed["message"])
        self.assertRegex(failed["message"], r"expected \d+ bytes but received \d+")
        self.assertRegex(output, r"FAILED corrupt: extract corrupt: meshextraction extract: error: cannot read image")
        with open(os.path.join(outdir, "report.html")) as stream:
            page = stream.read()
        self.assertIn("<svg", page)
        self.assertIn("cannot read image", page)
        self.assertIn("q_angle of every triangle of the cohort", page)
        with open(os.path.join(outdir, "summary.csv"), newline="") as stream:
            rows = list(csv.DictReader(stream))
        self.assertEqual([r["case"] for r in rows], [c.case_id for c in cases])
        self.assertIn("expected", next(r for r in rows if r["case"] == "corrupt")["message"])


def attempt_files(outdir):
    return glob.glob(os.path.join(outdir, "cases", "*", ".attempt-*", "attempt.json"))


def processes_in(folder):
    """Pids of the processes whose working directory is FOLDER (the tool runs in its attempt
    folder)."""
    pids = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                if os.readlink(f"/proc/{entry}/cwd") == folder:
                    pids.append(int(entry))
            except OSError:
                pass
    return pids


def alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as stream:
            return stream.read().split(")")[-1].split()[0] != "Z"
    except OSError:
        return False


class WorkerKilledTest(CohortAssertions):
    """A worker process killed (SIGKILL, by pid) while it runs a case: every case completes,
    each exactly once, none corrupt; the killed case is retried and its extraction does not
    outlive the worker."""

    def test_worker_killed(self):
        work = fresh_dir("worker-killed")
        manifest_path = synthetic.make_cohort(TOOL, work, count=20, size_range=(44, 60), seed=7)
        cases = manifest.read_manifest(manifest_path)
        outdir = os.path.join(work, "out")
        command = cohort_command("run", manifest_path, outdir, "--meshextraction", TOOL, "--workers", "2")
        command += ["--options", "--quality high"]
        client = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        killed = self.kill_a_busy_worker(outdir)
        output, _ = client.communicate(timeout=240)
        self.assertIsNotNone(killed, "no case was seen running: the kill did not happen\n" + output)
        case_id, worker_pid, tool_pids = killed
        self.assertEqual(client.returncode, 1, output)
        self.assert_cohort_complete(outdir, cases, ["--quality", "high"])
        totals = summary(outdir)["totals"]
        self.assertEqual((totals["succeeded"], totals["failed"], totals["not_run"]), (20, 1, 0), output)
        self.assertGreaterEqual(totals["retried"], 1, output)
        row = next(r for r in summary(outdir)["cases"] if r["case"] == case_id)
        self.assertEqual(row["attempts"], 2, row)
        self.assertRegex(output, rf"ok {case_id}: .*attempt 2")
        self.assertFalse(alive(worker_pid))
        self.assertTrue(tool_pids, "the killed worker's extraction was not seen")
        self.assertFalse([p for p in tool_pids if alive(p)], "the killed worker's extraction outlived it")
        print(
            f"killed worker pid {worker_pid} while it ran {case_id} (tool processes {tool_pids}); "
            f"retried {totals['retried']}, succeeded {totals['succeeded']}, failed {totals['failed']}"
        )

    def kill_a_busy_worker(self, outdir):
        """Waits until a few cases are done and another one is running, then kills the
        worker process running it; returns (case, worker pid, the tool's pids) or None."""
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            done = glob.glob(os.path.join(outdir, "cases", "*", "*.result.json"))
            running = attempt_files(outdir) if len(done) >= 4 else []
            for path in running:
                case_id = os.path.basename(os.path.dirname(os.path.dirname(path)))
                if case_id == synthetic.CORRUPT_CASE:
                    continue  # it fails on every attempt: its retry could not succeed
                attempt = outputs.read_json(path)
                tools = processes_in(os.path.dirname(path))
                if attempt is None or not tools:
                    continue
                os.kill(attempt["pid"], signal.SIGKILL)
                time.sleep(1.0)  # time for the kernel to deliver the death signal to the tool
                return case_id, attempt["pid"], tools
            time.sleep(0.005)
        return None


class InterruptAndResumeTest(CohortAssertions):
    """The client interrupted in the middle of a run (SIGINT to its process group, as Ctrl-C
    sends it), then rerun: only the remainder is computed, the finished cases are kept
    untouched; a damaged mesh is recomputed."""

    def test_interrupt_and_resume(self):
        work = fresh_dir("interrupt")
        manifest_path = synthetic.make_cohort(TOOL, work, count=20, seed=11)
        cases = manifest.read_manifest(manifest_path)
        outdir = os.path.join(work, "out")
        command = cohort_command("run", manifest_path, outdir, "--meshextraction", TOOL, "--workers", "1")
        client = subprocess.Popen(
            command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True
        )
        deadline = time.monotonic() + 120
        while len(glob.glob(os.path.join(outdir, "cases", "*", "*.result.json"))) < 6:
            self.assertLess(time.monotonic(), deadline)
            self.assertIsNone(client.poll(), "the run ended before it was interrupted")
            time.sleep(0.02)
        os.killpg(client.pid, signal.SIGINT)  # as Ctrl-C in a terminal: the client, its workers, the tool
        output, _ = client.communicate(timeout=120)
        self.assertEqual(client.returncode, 130, output)
        self.assertNotIn("Traceback", output)
        self.assertNotIn("killed by SIGINT", output)
        self.assertIn("rerun the same command to compute the rest", output)
        self.assertEqual(glob.glob(os.path.join(outdir, "cases", "*", ".attempt-*")), [])
        first = summary(outdir)
        finished = {r["case"] for r in first["cases"] if r["status"] == "ok"}
        self.assertGreaterEqual(len(finished), 5)
        self.assertGreater(first["totals"]["not_run"], 0, output)
        stamps = {c: os.stat(outputs.record_path(outdir, c)).st_mtime_ns for c in finished}

        # Damage one finished mesh: the rerun must not trust it.
        damaged = sorted(finished)[0]
        mesh = glob.glob(os.path.join(outputs.case_dir(outdir, damaged), "*.vtk"))[0]
        with open(mesh, "r+b") as stream:
            stream.truncate(os.path.getsize(mesh) // 2)
        status, output = run_cohort(manifest_path, outdir, "--workers", "1")
        self.assertEqual(status, 1, output)
        kept = finished - {damaged}
        self.assertIn(f"21 cases; {len(kept)} with verified outputs kept, {21 - len(kept)} to run", output)
        second = summary(outdir)
        computed = {r["case"] for r in second["cases"] if r["this_run"] == "computed"}
        self.assertEqual(computed, {c.case_id for c in cases} - kept)
        for case_id in kept:
            self.assertEqual(os.stat(outputs.record_path(outdir, case_id)).st_mtime_ns, stamps[case_id])
        self.assert_cohort_complete(outdir, cases)
        print(f"interrupted after {len(finished)} cases; the rerun kept {len(kept)} and computed {len(computed)}")


class SameOutputsTest(unittest.TestCase):
    """1 and 2 workers write byte-identical meshes and quality reports."""

    def test_one_and_two_workers(self):
        work = fresh_dir("one-two")
        manifest_path = synthetic.make_cohort(TOOL, work, count=20, seed=5)
        digests = {}
        for workers in ("1", "2"):
            outdir = os.path.join(work, f"out-{workers}")
            status, output = run_cohort(manifest_path, outdir, "--workers", workers)
            self.assertEqual(status, 1, output)
            digests[workers] = file_digests(outdir)
        self.assertEqual(len(digests["1"]), 40)
        self.assertEqual(digests["1"], digests["2"])


class ExternalSchedulerTest(CohortAssertions):
    """--scheduler-file: a scheduler and a worker started apart, as dask-jobqueue or dask-ssh
    start them, whose worker does not have this package on its Python path (the tasks carry
    their code)."""

    def test_scheduler_file(self):
        work = fresh_dir("external")
        manifest_path = synthetic.make_cohort(TOOL, work, count=6, seed=3)
        cases = manifest.read_manifest(manifest_path)
        scheduler_file = os.path.join(work, "scheduler.json")
        environment = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        started = []
        try:
            started.append(
                self.start(
                    [
                        sys.executable,
                        "-m",
                        "distributed.cli.dask_scheduler",
                        "--host",
                        "127.0.0.1",
                        "--port",
                        "0",
                        "--no-dashboard",
                        "--scheduler-file",
                        scheduler_file,
                    ],
                    environment,
                    work,
                )
            )
            deadline = time.monotonic() + 60
            while not os.path.exists(scheduler_file):
                self.assertLess(time.monotonic(), deadline, "the scheduler did not start")
                time.sleep(0.1)
            started.append(
                self.start(
                    [
                        sys.executable,
                        "-m",
                        "distributed.cli.dask_worker",
                        "--scheduler-file",
                        scheduler_file,
                        "--nworkers",
                        "1",
                        "--nthreads",
                        "1",
                        "--no-dashboard",
                    ],
                    environment,
                    work,
                )
            )
            status, output = run_cohort(manifest_path, os.path.join(work, "out"), "--scheduler-file", scheduler_file)
        finally:
            for process in reversed(started):
                process.terminate()
                process.wait(timeout=60)
        self.assertEqual(status, 1, output)
        self.assertIn("6 succeeded (0 kept from earlier runs), 1 failed", output)
        self.assert_cohort_complete(os.path.join(work, "out"), cases)

    @staticmethod
    def start(command, environment, work):
        with open(os.path.join(work, f"{command[2].rsplit('.', 1)[-1]}.log"), "w") as log:
            return subprocess.Popen(command, cwd="/", env=environment, stdout=log, stderr=subprocess.STDOUT)


class TimeoutTest(unittest.TestCase):
    """--timeout stops a case that takes too long and records why; the others go on."""

    def test_timeout(self):
        work = fresh_dir("timeout")
        for name, size in (("small", "16"), ("large", "160")):
            subprocess.run(
                [TOOL, "phantom", "torus", os.path.join(work, f"{name}.nrrd"), "--size", size],
                check=True,
                capture_output=True,
            )
        path = os.path.join(work, "m.csv")
        with open(path, "w") as stream:
            stream.write(
                "case,image,iso,inside,options\nsmall,small.nrrd,0,below,\nlarge,large.nrrd,0,below,--quality high\n"
            )
        status, output = run_cohort(path, os.path.join(work, "out"), "--workers", "1", "--timeout", "0.3")
        self.assertEqual(status, 1, output)
        self.assertIn("FAILED large: extract large: stopped after the time limit of 0.3 s (--timeout)", output)
        self.assertIn("1 succeeded", output)


class CommandLineTest(unittest.TestCase):
    def test_shape_model_usage(self):
        result = subprocess.run(cohort_command("shape-model", "a.ply"), capture_output=True, text=True)
        self.assertEqual(result.returncode, 2)
        self.assertIn("required: OUTDIR", result.stderr)
        result = subprocess.run(
            cohort_command("shape-model", "a.ply", "b.ply", "--meshextraction", TOOL), capture_output=True, text=True
        )
        self.assertEqual(result.returncode, 2)
        self.assertIn("OUTDIR b.ply is a file or named like a mesh: give the output folder last", result.stderr)

    def test_bad_manifest(self):
        work = fresh_dir("bad-manifest")
        path = os.path.join(work, "m.csv")
        with open(path, "w") as stream:
            stream.write("case,image,colour\na,a.nrrd,red\n")
        status, output = run_cohort(path, os.path.join(work, "out"))
        self.assertEqual(status, 2, output)
        self.assertIn("unknown field(s) colour", output)

    def test_missing_tool(self):
        command = cohort_command("run", "m.csv", "out", "--meshextraction", "/nonexistent/meshextraction")
        result = subprocess.run(command, capture_output=True, text=True)
        self.assertEqual(result.returncode, 2)
        self.assertIn("is not an executable file", result.stderr)


class ManifestTest(unittest.TestCase):
    def write(self, name, text):
        path = os.path.join(self.directory, name)
        with open(path, "w") as stream:
            stream.write(text)
        return path

    def setUp(self):
        self.directory = tempfile.mkdtemp(prefix="cohort-manifest-")

    def tearDown(self):
        shutil.rmtree(self.directory)

    def test_csv(self):
        path = self.write(
            "m.csv",
            "# a comment\ncase,image,iso,inside,label,options\n"
            "ct-1,scans/ct1.nrrd,300,,,--quality high --sigma 1\n"
            "seg-2,/data/seg2.nii.gz,,,1;3,\n",
        )
        ct, seg = manifest.read_manifest(path)
        self.assertEqual(ct.image, os.path.join(self.directory, "scans", "ct1.nrrd"))
        self.assertEqual(ct.options, ("--quality", "high", "--sigma", "1"))
        self.assertEqual([s.name for s in ct.surfaces()], ["ct-1"])
        self.assertEqual(ct.surfaces()[0].arguments, ("--iso", "300"))
        self.assertEqual(seg.labels, ("1", "3"))
        self.assertEqual([s.name for s in seg.surfaces()], ["seg-2.label-1", "seg-2.label-3"])
        self.assertEqual(seg.surfaces()[1].arguments, ("--label", "3"))
        self.assertNotEqual(ct.fingerprint([]), ct.fingerprint(["--quality", "high"]))

    def test_json_with_defaults(self):
        document = {
            "defaults": {"iso": 300, "options": ["--quality", "high"]},
            "cases": [{"case": "a", "image": "a.nrrd"}, {"case": "b", "image": "b", "iso": 250.0, "label": [2]}],
        }
        a, b = manifest.read_manifest(self.write("m.json", json.dumps(document)))
        self.assertEqual((a.iso, a.options), ("300", ("--quality", "high")))
        self.assertEqual((b.iso, b.labels), ("250", ("2",)))
        self.assertEqual(b.surfaces()[0].arguments, ("--iso", "250", "--label", "2"))

    def test_errors(self):
        for text, message in (
            ("case,image\na,x\na,y\n", "appears twice"),
            ("case,image\n../a,x\n", "may hold only"),
            ("case,image\na,\n", "has no image"),
            ("case,image,inside\na,x,left\n", "inside must be above or below"),
            ("case,image\n", "no cases"),
        ):
            with self.assertRaisesRegex(manifest.ManifestError, message):
                manifest.read_manifest(self.write("m.csv", text))
        with self.assertRaisesRegex(manifest.ManifestError, "not valid JSON"):
            manifest.read_manifest(self.write("m.json", "{"))

    def test_training_meshes(self):
        """A shape model's inputs: mesh files, a manifest (case, mesh), a run's OUTDIR."""
        for name in ("a.ply", "b.vtk", "sub/c.stl", "d.ply", "other/a.ply"):
            os.makedirs(os.path.dirname(os.path.join(self.directory, name)), exist_ok=True)
            self.write(name, "")
        meshes, left_out = manifest.read_training_meshes([self.write("a.ply", ""), self.write("b.vtk", "")])
        here = self.directory
        self.assertEqual(meshes, [("a", os.path.join(here, "a.ply")), ("b", os.path.join(here, "b.vtk"))])
        self.assertEqual(left_out, [])
        path = self.write("m.csv", "case,mesh\nx,sub/c.stl\ny,a.ply\n")
        meshes, _ = manifest.read_training_meshes([path])
        self.assertEqual(meshes, [("x", os.path.join(here, "sub", "c.stl")), ("y", os.path.join(here, "a.ply"))])
        document = {"cases": [{"case": "p", "mesh": "d.ply"}, {"case": "q", "mesh": "b.vtk"}]}
        meshes, _ = manifest.read_training_meshes([self.write("m.json", json.dumps(document))])
        self.assertEqual([name for name, _ in meshes], ["p", "q"])
        for inputs, message in (
            (["a.ply"], "needs at least two meshes; the input gives 1"),
            (["a.ply", "other/a.ply"], "two inputs are named 'a'"),
            (["a.ply", "missing.ply"], "missing: .*missing.ply: no such mesh file"),
            (["a.ply", "m.txt"], "not a mesh file"),
        ):
            with self.assertRaisesRegex(manifest.ManifestError, message):
                manifest.read_training_meshes([os.path.join(self.directory, i) for i in inputs])
        with self.assertRaisesRegex(manifest.ManifestError, "unknown field.*image"):
            manifest.read_training_meshes([self.write("n.csv", "case,image\nx,a.ply\n")])

    def test_training_meshes_of_a_run(self):
        """A run's OUTDIR: the mesh of every case that succeeded; a case with a mesh per label
        is refused."""
        outdir = os.path.join(self.directory, "run")
        surfaces = {"c1": ["c1"], "c2": ["c2"], "c3": ["c3"], "bad": []}
        rows = []
        for case, names in surfaces.items():
            status = "ok" if names else "failed"
            rows.append({"case": case, "status": status})
            os.makedirs(outputs.case_dir(outdir, case))
            record = {"case": case, "status": status, "surfaces": [{"name": n, "mesh": f"{n}.vtk"} for n in names]}
            outputs.write_json_atomically(outputs.record_path(outdir, case), record)
            for name in names:
                self.write(os.path.join("run", "cases", case, f"{name}.vtk"), "")
        outputs.write_json_atomically(os.path.join(outdir, "summary.json"), {"cases": rows, "totals": {}})
        meshes, left_out = manifest.read_training_meshes([outdir])
        self.assertEqual([name for name, _ in meshes], ["c1", "c2", "c3"])
        self.assertEqual(meshes[1][1], os.path.join(outputs.case_dir(outdir, "c2"), "c2.vtk"))
        self.assertEqual(left_out, ["bad"])
        record = outputs.read_json(outputs.record_path(outdir, "c3"))
        record["surfaces"] = [{"name": f"c3.label-{k}", "mesh": f"c3.label-{k}.vtk"} for k in (1, 2)]
        outputs.write_json_atomically(outputs.record_path(outdir, "c3"), record)
        with self.assertRaisesRegex(manifest.ManifestError, r"c3 \(c3.label-1.vtk, c3.label-2.vtk\).*label-L.vtk"):
            manifest.read_training_meshes([outdir])
        with self.assertRaisesRegex(manifest.ManifestError, "not the OUTDIR of a meshextraction-cohort run"):
            manifest.read_training_meshes([self.directory])


def run_model(inputs, outdir, *options, timeout=240):
    """Runs `meshextraction-cohort shape-model`; returns (exit status, output)."""
    command = cohort_command("shape-model", *inputs, outdir, "--meshextraction", TOOL, *options)
    result = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    return result.returncode, result.stdout + result.stderr


def ply_points(path):
    """The vertices of a PLY file of the module's writer (binary little endian, double or
    float x y z first) or ASCII, as a list of (x, y, z)."""
    with open(path, "rb") as stream:
        header = []
        while not header or header[-1] != "end_header":
            header.append(stream.readline().decode().strip())
        count = next(int(line.split()[2]) for line in header if line.startswith("element vertex"))
        kinds = []
        for line in header[header.index(next(h for h in header if h.startswith("element vertex"))) + 1 :]:
            if not line.startswith("property"):
                break
            kinds.append(line.split()[1])
        if "format ascii 1.0" in header:
            return [tuple(float(v) for v in stream.readline().split()[:3]) for _ in range(count)]
        codes = {"double": "d", "float": "f", "float64": "d", "float32": "f"}
        layout = "<" + "".join(codes[k] for k in kinds)
        size = struct.calcsize(layout)
        return [struct.unpack(layout, stream.read(size))[:3] for _ in range(count)]


def shape_population(work):
    """The population of make_shape_population and, as a sixth mesh, an ellipsoid phantom
    extracted by the tool (a VTK file: another reader)."""
    meshes = synthetic.make_shape_population(os.path.join(work, "meshes"))
    image, mesh = os.path.join(work, "ellipsoid.nrrd"), os.path.join(work, "meshes", "phantom.vtk")
    subprocess.run([TOOL, "phantom", "ellipsoid", image, "--size", "26"], check=True, capture_output=True)
    subprocess.run([TOOL, "extract", image, mesh, "--iso", "0", "--inside", "below"], check=True, capture_output=True)
    return meshes + [mesh]


def model_steps(outdir):
    """{step: this_run} of the last build in OUTDIR."""
    with open(os.path.join(outdir, "shape-model.json")) as stream:
        return {row["step"]: row.get("this_run") for row in json.load(stream)["steps"]}


def to_float(value):
    """A double rounded to the nearest float (32 bits), as a cast in C++ rounds it."""
    return struct.unpack("f", struct.pack("f", value))[0]


def largest_relative_difference(a, b):
    return max(abs(x - y) / max(abs(x), abs(y), 1e-300) for x, y in zip(a, b))


class ShapeModelTest(unittest.TestCase):
    """The shape model of six meshes on 2 and on 1 workers, and by the in-process `meshextraction
    shape-model build`: the same model (the steps are the in-process build's, bit for bit)."""

    def test_against_the_in_process_build(self):
        work = fresh_dir("shape-model")
        meshes = shape_population(work)
        names = [os.path.splitext(os.path.basename(m))[0] for m in meshes]
        outputs_of = {}
        for workers in ("2", "1"):
            outdir = os.path.join(work, f"out-{workers}")
            status, output = run_model(meshes, outdir, "--workers", workers)
            self.assertEqual(status, 0, output)
            self.assertRegex(output, r"pass 1: matched 6/6 \S+ \(e2 [0-9.e+-]+ mm²; ")
            self.assertIn("pivot: shape-1 (input 1, 866 points)", output)  # the first of two with the most
            self.assertIn(f"corresponded meshes in {os.path.join(outdir, 'corresponded')}", output)
            self.assertTrue(os.path.isfile(os.path.join(outdir, "model.h5")))
            self.assertEqual(set(model_steps(outdir).values()), {"computed"})
            outputs_of[workers] = outdir
        one, two = (outputs.read_json(os.path.join(outputs_of[w], "model.json")) for w in ("1", "2"))
        self.assertEqual(one, two)
        for name in names:
            digests = {outputs.sha256(os.path.join(outputs_of[w], "corresponded", f"{name}.ply")) for w in ("1", "2")}
            self.assertEqual(len(digests), 1, name)
        counts = {name: len(ply_points(os.path.join(outputs_of["2"], "corresponded", f"{name}.ply"))) for name in names}
        self.assertEqual(set(counts.values()), {866}, counts)
        self.assertFalse(glob.glob(os.path.join(work, "out-*", "**", ".*partial*"), recursive=True))
        self.assertFalse(glob.glob(os.path.join(work, "out-*", "steps", "*", ".attempt-*")))

        build_json, corresponded = os.path.join(work, "build.json"), os.path.join(work, "build-corresponded")
        command = [TOOL, "shape-model", "build", *meshes, "--output", os.path.join(work, "build.h5")]
        command += ["--corresponded", corresponded, "--json", build_json]
        result = subprocess.run(command, capture_output=True, text=True)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        build = outputs.read_json(build_json)
        for key in ("modes", "pivot", "passes"):
            self.assertEqual(two[key], build[key], key)
        difference = largest_relative_difference(two["all_variances"], build["all_variances"])
        print(f"largest relative difference of the variances, Dask steps vs in-process build: {difference:.3g}")
        # The build writes its corresponded meshes with float coordinates (for PLY inputs, as
        # PLY), the steps with double ones: rounded to float, they must be the build's.
        moved = 0.0
        for name in names[:-1]:
            ours = ply_points(os.path.join(outputs_of["2"], "corresponded", f"{name}.ply"))
            theirs = ply_points(os.path.join(corresponded, f"{name}.ply"))
            moved = max([moved] + [abs(to_float(a) - b) for p, q in zip(ours, theirs) for a, b in zip(p, q)])
        print(f"largest coordinate difference of the corresponded meshes (as floats): {moved:.3g} mm")
        self.assertLessEqual(difference, 1e-9, (two["all_variances"], build["all_variances"]))
        self.assertLessEqual(largest_relative_difference(two["variances"], build["variances"]), 1e-9)
        self.assertEqual(moved, 0.0)


class ShapeModelResumeTest(unittest.TestCase):
    """A state of the last pass and the model deleted: the rerun computes that match and the
    reduction, keeps every other step, and gives the same model; a rerun of a complete build
    computes nothing; a rerun with other inputs and options recomputes what depends on them."""

    def test_resume(self):
        work = fresh_dir("shape-model-resume")
        meshes = synthetic.make_shape_population(os.path.join(work, "meshes"))
        outdir = os.path.join(work, "out")
        status, output = run_model(meshes, outdir, "--workers", "2")
        self.assertEqual(status, 0, output)
        model = outputs.read_json(os.path.join(outdir, "model.json"))
        last = model["passes"]
        os.unlink(os.path.join(outdir, f"pass-{last}", "shape-3.state.json"))
        os.unlink(os.path.join(outdir, "model.h5"))
        status, output = run_model(meshes, outdir, "--workers", "2")
        self.assertEqual(status, 0, output)
        computed = {step for step, this_run in model_steps(outdir).items() if this_run == "computed"}
        self.assertIn(f"pass-{last}-match-shape-3", computed)
        self.assertIn("finish", computed)
        self.assertLessEqual(computed, {f"pass-{last}-match-shape-3", f"pass-{last}-renew", "finish"})
        self.assertIn(f"pass {last}: 4 of 5 matches kept from an earlier build", output)
        self.assertIn(f"pass {last}: matched 1/1 shape-3", output)
        self.assertIn("prepare: 5 of 5 prepared meshes kept from an earlier build", output)
        self.assertEqual(outputs.read_json(os.path.join(outdir, "model.json")), model)
        self.assertTrue(os.path.isfile(os.path.join(outdir, "model.h5")))
        print(f"the rerun computed {sorted(computed)}")

        status, output = run_model(meshes, outdir, "--workers", "2")
        self.assertEqual(status, 0, output)
        self.assertEqual(set(model_steps(outdir).values()), {"kept"}, output)
        build = outputs.read_json(os.path.join(outdir, "shape-model.json"))
        self.assertEqual(build["cluster"], "no cluster (every step was kept)")
        with open(os.path.join(outdir, "shape-model.log")) as stream:
            log = stream.read()
        self.assertEqual(log.count("shape-model match"), 5 * last + 1, "the log has each match command run")

        # One mesh fewer, one pass: the pivot and so the first pass's matches stay; the
        # renewal and the model are new; what only the earlier build had is gone.
        status, output = run_model(meshes[:-1], outdir, "--workers", "2", "--passes", "1")
        self.assertEqual(status, 0, output)
        steps = model_steps(outdir)
        self.assertEqual({s for s, this_run in steps.items() if this_run == "computed"}, {"pass-1-renew", "finish"})
        self.assertEqual(len(steps), 4 + 4 + 2)
        self.assertEqual(sorted(os.listdir(os.path.join(outdir, "steps"))), sorted(steps))
        self.assertFalse(glob.glob(os.path.join(outdir, "pass-2")) + glob.glob(os.path.join(outdir, "*", "shape-4*")))
        self.assertEqual(len(os.listdir(os.path.join(outdir, "corresponded"))), 4)
        self.assertEqual(outputs.read_json(os.path.join(outdir, "model.json"))["passes"], 1)


class ShapeModelBadInputTest(unittest.TestCase):
    """An open mesh among the inputs: the build stops, naming it, with the tool's message;
    fewer than two meshes: a usage error."""

    def test_open_mesh(self):
        work = fresh_dir("shape-model-bad")
        meshes = synthetic.make_shape_population(os.path.join(work, "meshes"), cells=(6, 7, 6))
        triangle = os.path.join(work, "meshes", "triangle.ply")
        synthetic.write_ply(triangle, [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [(0, 1, 2)])
        outdir = os.path.join(work, "out")
        status, output = run_model(meshes[:2] + [triangle] + meshes[2:], outdir, "--workers", "2")
        self.assertEqual(status, 1, output)
        self.assertIn("the shape model cannot be built: 1 step(s) failed:", output)
        self.assertRegex(output, rf"prepare triangle \({triangle}\): .*error")
        self.assertEqual(output.count("prepare: prepared "), 3, output)  # the others (a rerun keeps them)
        self.assertNotIn("pass 1", output)
        self.assertFalse(os.path.exists(os.path.join(outdir, "model.h5")))
        self.assertEqual(outputs.read_json(os.path.join(outdir, "shape-model.json"))["status"], "failed")

        status, output = run_model(meshes[:1], os.path.join(work, "out-1"), "--workers", "1")
        self.assertEqual(status, 2, output)
        self.assertIn("a shape model needs at least two meshes; the input gives 1", output)


def main():
    global TOOL, WORK
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    TOOL, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    try:
        import distributed  # noqa: F401
    except ImportError:
        print(
            f"SKIPPED: {sys.executable} has no dask.distributed (Debian: apt-get install python3-distributed; "
            "scripts/install-dependencies.sh installs it)"
        )
        sys.exit(77)
    os.makedirs(WORK, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + sys.argv[3:], verbosity=2)


if __name__ == "__main__":
    main()
