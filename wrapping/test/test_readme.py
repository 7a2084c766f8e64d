"""README.md's Python quick start, run as it is written, on a CT-like image made here."""
import os
import re

import itk
import numpy as np
import pytest

README = os.path.join(os.path.dirname(__file__), "..", "..", "README.md")


def python_quick_start():
    with open(README, encoding="utf-8") as f:
        text = f.read()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert blocks, "README.md has no Python code block"
    return blocks[0]


def test_quick_start_runs_verbatim(tmp_path, monkeypatch, capsys):
    # "ct.nrrd": a 1 mm grid in Hounsfield units, air at -1000 and a ball of bone
    # (1000 HU) of radius 12 mm, its edge blurred like a scanner's.
    z, y, x = np.mgrid[0:40, 0:40, 0:40]
    radius = np.sqrt((x - 19.5) ** 2 + (y - 19.5) ** 2 + (z - 19.5) ** 2)
    hu = -1000 + 2000 / (1 + np.exp((radius - 12.0) / 0.6))
    image = itk.image_from_array(hu.astype(np.int16))
    itk.imwrite(image, str(tmp_path / "ct.nrrd"))
    monkeypatch.chdir(tmp_path)
    exec(compile(python_quick_start(), "README.md", "exec"), {})
    printed = capsys.readouterr().out.split()
    assert printed[-1] == "True"  # valid_closed_surface
    assert float(printed[-2]) > 0.75  # the mean q_angle of the high-quality surface
    assert (tmp_path / "bone.vtk").stat().st_size > 0
