"""Tests of meshextraction-cohort on a LocalCluster: a synthetic cohort of random phantoms plus
one corrupt image; a worker killed by pid in the middle of a run; the client interrupted and
rerun; the same outputs for 1 and 2 workers; the manifest reader.

  python3 test_cohort.py MESHEXTRACTION WORKDIR [unittest arguments, e.g. WorkerKilledTest]

Exits 77 (CTest's skip code here) with a message when this Python has no dask.distributed.
"""

import csv
import glob
import json
import os
import shutil
import signal
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
    def test_shape_model_is_not_yet(self):
        result = subprocess.run(cohort_command("shape-model", "manifest.csv"), capture_output=True, text=True)
        self.assertEqual(result.returncode, 2)
        self.assertIn("not yet on Dask", result.stderr)
        self.assertIn("meshextraction shape-model MESH... --output MODEL.h5", result.stderr)

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
