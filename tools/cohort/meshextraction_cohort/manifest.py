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
"""

import csv
import hashlib
import json
import os
import re
import shlex
from dataclasses import dataclass, field

KEYS = ("case", "image", "iso", "inside", "label", "segmentation", "options")
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


def _case(entry, base, where):
    unknown = sorted(set(entry) - set(KEYS) - {"id"})
    if unknown:
        raise ManifestError(f"{where}: unknown field(s) {', '.join(unknown)} (known: {', '.join(KEYS)})")
    case_id = _text(entry.get("case", entry.get("id")))
    if case_id is None:
        raise ManifestError(f"{where}: no case identifier ('case')")
    if not _CASE_ID.match(case_id):
        raise ManifestError(f"{where}: case '{case_id}' may hold only letters, digits, '.', '_' and '-'")
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


def read_manifest(path):
    """The cases of a CSV or JSON manifest (by extension; .json is JSON, anything else CSV)."""
    if not os.path.isfile(path):
        raise ManifestError(f"{path}: no such manifest")
    entries = _read_json(path) if path.lower().endswith(".json") else _read_csv(path)
    base = os.path.dirname(os.path.abspath(path))
    cases, seen = [], set()
    for entry, where in entries:
        case = _case(entry, base, where)
        if case.case_id in seen:
            raise ManifestError(f"{where}: case '{case.case_id}' appears twice")
        seen.add(case.case_id)
        cases.append(case)
    if not cases:
        raise ManifestError(f"{path}: no cases")
    return cases
