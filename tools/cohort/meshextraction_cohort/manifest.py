"""The cohort's cases, read from a CSV or a JSON manifest.

A case is one scan and what to extract from it:

  case          identifier, unique in the manifest; names the case's output folder
                (letters, digits, '.', '_', '-')
  image         an image file ITK reads, or a DICOM series directory; a relative path is
                taken relative to the manifest's folder
  iso           the iso-value of the object's boundary (greyscale images)
  inside        above or below: which side of iso is the object (default: above)
  label         label value(s): the object is the voxels equal to the label; several labels
                (separated by ';' or spaces in CSV, a list in JSON) give one mesh each
  segmentation  a label image whose label voxels give the net, relaxed toward the image's
                iso surface (extract --labels)
  options       further `meshextraction extract` options (a string, split like a shell
                does, or a JSON list), e.g. "--quality high --sigma 1"

CSV: a header row with these column names ('id' is accepted for 'case'). JSON: a list of
objects with these keys, or {"defaults": {...}, "cases": [...]} where defaults apply to
every case that does not set the key itself.

The training meshes of a shape model (`meshextraction-cohort shape-model`) are given as mesh
files, as a manifest of the same two forms with the fields case and mesh, or as the OUTDIR
of a `run` (the mesh of every case that succeeded).
"""

import csv
import hashlib
import json
import os
import re
import shlex
from dataclasses import dataclass, field

from . import outputs

KEYS = ("case", "image", "iso", "inside", "label", "segmentation", "options")
MESH_KEYS = ("case", "mesh")
MESH_EXTENSIONS = (".ply", ".vtk", ".vtp", ".stl", ".obj", ".off")
_CASE_ID = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]*$")


class ManifestError(ValueError):
    """The manifest cannot be read or has a case that cannot be run."""


@dataclass(frozen=True)
class Surface:
    """One mesh of a case: its file stem and the extract options that select it."""

    name: str
    arguments: tuple


@dataclass(frozen=True)
class Case:
    case_id: str
    image: str
    iso: str = None
    inside: str = None
    labels: tuple = ()
    segmentation: str = None
    options: tuple = field(default_factory=tuple)

    def surfaces(self):
        """The meshes of this case: one for an iso-value, one per label."""
        common = []
        if self.iso is not None:
            common += ["--iso", self.iso]
        if self.inside is not None:
            common += ["--inside", self.inside]
        if self.segmentation is not None:
            common += ["--labels", self.segmentation]
        if not self.labels:
            return [Surface(self.case_id, tuple(common))]
        if len(self.labels) == 1:
            return [Surface(self.case_id, tuple(common + ["--label", self.labels[0]]))]
        return [Surface(f"{self.case_id}.label-{label}", tuple(common + ["--label", label])) for label in self.labels]

    def as_dict(self):
        return {
            "case": self.case_id,
            "image": self.image,
            "iso": self.iso,
            "inside": self.inside,
            "label": list(self.labels),
            "segmentation": self.segmentation,
            "options": list(self.options),
        }

    def fingerprint(self, common_options):
        """A digest of everything that determines the case's outputs: the case's fields, the
        options given to every case, and the size and modification time of the image file
        (so a replaced scan is recomputed). A rerun skips a case only if it matches."""
        spec = self.as_dict()
        spec["common_options"] = list(common_options)
        try:
            status = os.stat(self.image)
            spec["image_stat"] = [status.st_size, status.st_mtime_ns] if not os.path.isdir(self.image) else "directory"
        except OSError:
            spec["image_stat"] = None
        return hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()


def _text(value):
    if value is None:
        return None
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    text = str(value).strip()
    return text or None


def _labels(value):
    if value is None:
        return ()
    if isinstance(value, (list, tuple)):
        return tuple(t for t in (_text(v) for v in value) if t)
    return tuple(t for t in re.split(r"[;\s]+", str(value).strip()) if t)


def _options(value):
    if value is None:
        return ()
    if isinstance(value, (list, tuple)):
        return tuple(str(v) for v in value)
    return tuple(shlex.split(str(value)))


def _resolve(path, base):
    if path is None:
        return None
    path = os.path.expanduser(path)
    return os.path.normpath(path if os.path.isabs(path) else os.path.join(base, path))


def _case_id(entry, keys, where):
    """The entry's case identifier, after checking that it has only the known fields."""
    unknown = sorted(set(entry) - set(keys) - {"id"})
    if unknown:
        raise ManifestError(f"{where}: unknown field(s) {', '.join(unknown)} (known: {', '.join(keys)})")
    case_id = _text(entry.get("case", entry.get("id")))
    if case_id is None:
        raise ManifestError(f"{where}: no case identifier ('case')")
    if not _CASE_ID.match(case_id):
        raise ManifestError(f"{where}: case '{case_id}' may hold only letters, digits, '.', '_' and '-'")
    return case_id


def _case(entry, base, where):
    case_id = _case_id(entry, KEYS, where)
    image = _text(entry.get("image"))
    if image is None:
        raise ManifestError(f"{where}: case '{case_id}' has no image")
    inside = _text(entry.get("inside"))
    if inside is not None and inside not in ("above", "below"):
        raise ManifestError(f"{where}: case '{case_id}': inside must be above or below, not '{inside}'")
    return Case(
        case_id=case_id,
        image=_resolve(image, base),
        iso=_text(entry.get("iso")),
        inside=inside,
        labels=_labels(entry.get("label")),
        segmentation=_resolve(_text(entry.get("segmentation")), base),
        options=_options(entry.get("options")),
    )


def _read_csv(path):
    with open(path, newline="", encoding="utf-8") as stream:
        rows = list(csv.DictReader(row for row in stream if row.strip() and not row.lstrip().startswith("#")))
    return [
        ({k.strip(): v for k, v in row.items() if k is not None}, f"{path}: row {i + 2}") for i, row in enumerate(rows)
    ]


def _read_json(path):
    with open(path, encoding="utf-8") as stream:
        try:
            document = json.load(stream)
        except json.JSONDecodeError as error:
            raise ManifestError(f"{path}: not valid JSON: {error}") from None
    defaults = {}
    if isinstance(document, dict):
        defaults = document.get("defaults", {})
        document = document.get("cases")
    if not isinstance(document, list) or not all(isinstance(e, dict) for e in document):
        raise ManifestError(f'{path}: expected a list of cases or {{"defaults": {{...}}, "cases": [...]}}')
    return [({**defaults, **entry}, f"{path}: case {i + 1}") for i, entry in enumerate(document)]


def _read_entries(path, read_entry, case_id_of):
    """read_entry(entry, folder of the manifest, where) of every entry of a CSV or JSON
    manifest (by extension; .json is JSON, anything else CSV), in order; case_id_of(result)
    must be unique in the manifest."""
    if not os.path.isfile(path):
        raise ManifestError(f"{path}: no such manifest")
    entries = _read_json(path) if path.lower().endswith(".json") else _read_csv(path)
    base = os.path.dirname(os.path.abspath(path))
    results, seen = [], set()
    for entry, where in entries:
        result = read_entry(entry, base, where)
        case_id = case_id_of(result)
        if case_id in seen:
            raise ManifestError(f"{where}: case '{case_id}' appears twice")
        seen.add(case_id)
        results.append(result)
    if not results:
        raise ManifestError(f"{path}: no cases")
    return results


def read_manifest(path):
    """The cases of a CSV or JSON manifest (by extension; .json is JSON, anything else CSV)."""
    return _read_entries(path, _case, lambda case: case.case_id)


def _mesh_entry(entry, base, where):
    case_id = _case_id(entry, MESH_KEYS, where)
    mesh = _resolve(_text(entry.get("mesh")), base)
    if mesh is None:
        raise ManifestError(f"{where}: case '{case_id}' has no mesh")
    return case_id, mesh


def _meshes_of_run(outdir):
    """(name, mesh) of every case of a run's OUTDIR that succeeded; and the cases left out."""
    summary = outputs.read_json(os.path.join(outdir, "summary.json"))
    if not isinstance(summary, dict) or not isinstance(summary.get("cases"), list):
        raise ManifestError(f"{outdir}: not the OUTDIR of a meshextraction-cohort run (no summary.json)")
    meshes, left_out, several = [], [], []
    for row in summary["cases"]:
        record = outputs.read_json(outputs.record_path(outdir, row["case"])) if row.get("status") == "ok" else None
        if record is None or record.get("status") != "ok":
            left_out.append(row["case"])
            continue
        surfaces = record.get("surfaces", [])
        if len(surfaces) > 1:
            several.append(f"{row['case']} ({', '.join(s['mesh'] for s in surfaces)})")
        directory = outputs.case_dir(outdir, row["case"])
        meshes += [(s["name"], os.path.join(directory, s["mesh"])) for s in surfaces]
    if several:
        raise ManifestError(
            f"{outdir}: a shape model is of one structure, but {len(several)} case(s) have a mesh per label: "
            f"{'; '.join(several[:3])}{' ...' if len(several) > 3 else ''}. Give the meshes of one label "
            f"instead, e.g. {os.path.join(outdir, 'cases', '*', '*.label-L.vtk')}, or a manifest (case, mesh)"
        )
    return meshes, left_out


def _mesh_file(path):
    stem, extension = os.path.splitext(os.path.basename(path))
    if extension.lower() not in MESH_EXTENSIONS:
        raise ManifestError(
            f"{path}: not a mesh file ({', '.join(MESH_EXTENSIONS)}); the inputs are mesh files, or one "
            "manifest (.csv, .json), or one meshextraction-cohort run's OUTDIR"
        )
    if not _CASE_ID.match(stem):
        raise ManifestError(
            f"{path}: its name '{stem}' may hold only letters, digits, '.', '_' and '-'; give a manifest "
            "(case, mesh) to name it"
        )
    return stem, os.path.normpath(os.path.abspath(path))


def read_training_meshes(inputs):
    """The training meshes of a shape model, as (name, absolute path) in input order, and the
    cases of a run that are left out (they failed). `inputs` is mesh files (named by their
    file stem), or one CSV or JSON manifest with the fields case and mesh (paths relative to
    the manifest's folder), or one run's OUTDIR. Names must be unique and the meshes exist."""
    left_out = []
    if len(inputs) == 1 and os.path.isdir(inputs[0]):
        meshes, left_out = _meshes_of_run(inputs[0])
    elif len(inputs) == 1 and os.path.splitext(inputs[0])[1].lower() in (".csv", ".json"):
        meshes = _read_entries(inputs[0], _mesh_entry, lambda named: named[0])
    else:
        meshes = [_mesh_file(path) for path in inputs]
    first = {}
    for name, mesh in meshes:
        if name in first:
            raise ManifestError(
                f"two inputs are named '{name}': {first[name]} and {mesh}; give a manifest (case, mesh) "
                "with distinct case names"
            )
        first[name] = mesh
        if not os.path.isfile(mesh):
            raise ManifestError(f"{name}: {mesh}: no such mesh file")
    if len(meshes) < 2:
        raise ManifestError(f"a shape model needs at least two meshes; the input gives {len(meshes)}")
    return [(name, os.path.abspath(mesh)) for name, mesh in meshes], left_out
