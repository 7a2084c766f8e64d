"""The output layout, atomic writes, and the verification that lets a rerun resume.

OUTDIR/
  cases/CASE/SURFACE.vtk            the mesh (one per surface: the case, or CASE.label-L)
  cases/CASE/SURFACE.quality.json   `meshextraction quality --json` of that mesh file
  cases/CASE/CASE.log               the commands, their output, status, time and memory
  cases/CASE/CASE.result.json       the case's record, written last: its presence says the
                                    case is complete (status ok) or failed (with message)
  cases/CASE/.attempt-*/            a running attempt's files under their final names;
                                    moved into place when complete, removed otherwise
  summary.csv, summary.json         one row per case; the totals
  report.html                       the cohort report

The shape model (`shape-model`, model_runner) writes its steps' outputs (prepared/,
pass-P/, model.h5, model.json; see model_runner) and, per step, the record and the log:

  steps/STEP/STEP.result.json       the step's record, written last: the fingerprint of
                                    its command and inputs, the SHA-256 of its outputs
  steps/STEP/STEP.log               the command, its output, status, time and memory

Every file is written in a temporary place and renamed into place (os.replace, atomic on
POSIX file systems), so a reader never sees half a file, and the record is renamed last.
"""

import contextlib
import glob
import hashlib
import json
import os
import shutil

RECORD_VERSION = 1


def case_dir(outdir, case_id):
    return os.path.join(outdir, "cases", case_id)


def record_path(outdir, case_id):
    return os.path.join(case_dir(outdir, case_id), f"{case_id}.result.json")


def log_path(outdir, case_id):
    return os.path.join(case_dir(outdir, case_id), f"{case_id}.log")


def step_dir(outdir, step):
    return os.path.join(outdir, "steps", step)


def step_record_path(outdir, step):
    return os.path.join(step_dir(outdir, step), f"{step}.result.json")


def link_atomically(source, path):
    """Makes `path` the same file as `source` (a hard link; a copy where the file system
    has none), replacing what was there in one rename."""
    temporary = f"{path}.tmp-{os.getpid()}"
    try:
        os.link(source, temporary)
    except OSError:
        shutil.copyfile(source, temporary)
    os.replace(temporary, path)


def remove_partial_files(path):
    """Removes the partial files the command-line tool leaves for `path` when it is killed
    while writing it (.STEM.partial-TAG.EXT, renamed to `path` when complete)."""
    folder, name = os.path.split(path)
    stem, extension = os.path.splitext(name)
    for partial in glob.glob(os.path.join(glob.escape(folder), f".{glob.escape(stem)}.partial-*{extension}")):
        with contextlib.suppress(FileNotFoundError):
            os.unlink(partial)


def write_json_atomically(path, document):
    temporary = f"{path}.tmp-{os.getpid()}"
    with open(temporary, "w", encoding="utf-8") as stream:
        json.dump(document, stream, indent=1, sort_keys=True)
        stream.write("\n")
        stream.flush()
        os.fsync(stream.fileno())
    os.replace(temporary, path)


def read_json(path):
    try:
        with open(path, encoding="utf-8") as stream:
            return json.load(stream)
    except (OSError, ValueError):
        return None


def sha256(path):
    digest = hashlib.sha256()
    with open(path, "rb") as stream:
        for block in iter(lambda: stream.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _vtk_counts(path):
    """Points and polygons declared by a legacy VTK file's header, or None."""
    points = polygons = None
    with open(path, "rb") as stream:
        if not stream.readline().startswith(b"# vtk DataFile"):
            return None
        for line in stream:
            words = line.split()
            if len(words) >= 2 and words[0] == b"POINTS":
                points = int(words[1])
            elif len(words) >= 2 and words[0] == b"POLYGONS":
                polygons = int(words[1])
                break
    return points, polygons


def _obj_counts(path):
    points = polygons = 0
    with open(path, "rb") as stream:
        for line in stream:
            if line.startswith(b"v "):
                points += 1
            elif line.startswith(b"f "):
                polygons += 1
    return points, polygons


def mesh_reads(mesh, quality):
    """Whether the mesh file parses and holds the points and triangles its quality JSON
    counted (VTK and OBJ; other formats are trusted to their checksum)."""
    counter = {".vtk": _vtk_counts, ".obj": _obj_counts}.get(os.path.splitext(mesh)[1].lower())
    if counter is None:
        return True
    try:
        counts = counter(mesh)
    except (OSError, ValueError):
        return False
    return counts == (quality.get("points"), quality.get("triangles"))


def quality_of(quality_json):
    """The quality report of the single mesh in a `meshextraction quality --json` file."""
    document = read_json(quality_json)
    if not isinstance(document, list) or len(document) != 1 or not isinstance(document[0], dict):
        return None
    return document[0].get("quality")


def _current_record(path, fingerprint, changed):
    """(the record at path, None) when it says ok and has this fingerprint and version;
    otherwise (None, why not: `changed` for another fingerprint)."""
    record = read_json(path)
    if record is None:
        return None, "no result"
    if record.get("status") != "ok":
        return None, f"last run {record.get('status')}"
    if record.get("fingerprint") != fingerprint or record.get("version") != RECORD_VERSION:
        return None, changed
    return record, None


def verify(outdir, case_id, fingerprint):
    """(record, None) when the case's outputs are complete and sound: the record says ok,
    was made from the same case specification, every mesh's quality JSON says valid, and
    every mesh has the checksum it had when it was measured and reads back. Otherwise
    (None, why not)."""
    record, why = _current_record(record_path(outdir, case_id), fingerprint, "the case or its options changed")
    if record is None:
        return None, why
    directory = case_dir(outdir, case_id)
    for surface in record.get("surfaces", []):
        mesh = os.path.join(directory, surface["mesh"])
        quality = quality_of(os.path.join(directory, surface["quality_json"]))
        if quality is None or quality.get("valid_closed_surface") is not True:
            return None, f"{surface['quality_json']} missing or not valid"
        try:
            if os.path.getsize(mesh) != surface["mesh_bytes"] or sha256(mesh) != surface["mesh_sha256"]:
                return None, f"{surface['mesh']} changed since it was measured"
        except OSError:
            return None, f"{surface['mesh']} missing"
        if not mesh_reads(mesh, quality):
            return None, f"{surface['mesh']} does not read"
    return record, None


def verify_step(outdir, step, fingerprint):
    """(record, None) when a shape model step's outputs are complete and current: its record
    says ok, has the fingerprint of the step's command and inputs, and every output has the
    checksum it had when the step wrote it (and so reads as it did then). Otherwise (None,
    why not)."""
    record, why = _current_record(step_record_path(outdir, step), fingerprint, "its command or inputs changed")
    if record is None:
        return None, why
    for name, digest in record.get("outputs", {}).items():
        try:
            if sha256(os.path.join(outdir, name)) != digest:
                return None, f"{name} changed since it was written"
        except OSError:
            return None, f"{name} missing"
    return record, None
