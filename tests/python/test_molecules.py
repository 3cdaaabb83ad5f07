"""Molecule files from Python (issue 40): the keywords model, waters and
hydrogens are the scene's spheres keys, for molecule files only."""
import numpy as np
import pytest

import zsweep

PDB = (
    "MODEL        1\n"
    "ATOM      1  N   ALA A   1       0.000   0.000   0.000  1.00 10.00           N\n"
    "ATOM      2  CA  ALA A   1       1.400   0.000   0.000  1.00 11.00           C\n"
    "ATOM      3  H   ALA A   1      -0.800   0.600   0.000  1.00 12.00           H\n"
    "HETATM    4  O   HOH B 101       3.500   1.000   0.000  1.00 20.00           O\n"
    "ENDMDL\nMODEL        2\n"
    "ATOM      1  N   ALA A   1       0.000   1.000   0.000  1.00 10.00           N\n"
    "ENDMDL\nEND\n"
)


def write(tmp_path):
    p = tmp_path / "m.pdb"
    p.write_text(PDB)
    return str(p)


def test_keywords_match_the_scene_keys(tmp_path):
    path = write(tmp_path)
    for kw in (dict(waters=False), dict(hydrogens=False), dict(model=2), dict(model="2")):
        a = zsweep.render(path, width=48, height=32, **kw)
        assert a.shape == (32, 48, 4)
        b = zsweep.render({"spheres": dict(kw, path=path), "image": {"width": 48, "height": 32}})
        assert np.array_equal(a, b), kw


def test_choices_change_what_is_drawn(tmp_path):
    path = write(tmp_path)
    full = zsweep.render({"spheres": path, "image": {"width": 48, "height": 32}})
    dry = zsweep.render({"spheres": {"path": path, "waters": False}, "image": {"width": 48, "height": 32}})
    assert not np.array_equal(full, dry)
    res = zsweep.render({"spheres": {"path": path, "color": "residue"}, "image": {"width": 48, "height": 32}})
    chain = zsweep.render({"spheres": {"path": path, "color": "chain"}, "image": {"width": 48, "height": 32}})
    assert not np.array_equal(res, chain)


def test_errors(tmp_path):
    path = write(tmp_path)
    with pytest.raises(RuntimeError, match="no model 3"):
        zsweep.render(path, width=8, height=8, model=3)
    with pytest.raises(TypeError, match="waters must be True or False"):
        zsweep.render(path, width=8, height=8, waters="no")
    sph = tmp_path / "s.sph"
    sph.write_text("0 0 0 1\n")
    with pytest.raises(ValueError, match="waters applies to molecule files"):
        zsweep.render(str(sph), width=8, height=8, waters=False)
    with pytest.raises(ValueError, match="model applies to molecule files"):
        zsweep.render({"spheres": {"centres": np.zeros((1, 3)), "radii": np.ones(1)}}, model=1)
    with pytest.raises(RuntimeError, match="spheres.model applies to molecule files"):
        zsweep.render({"spheres": {"path": str(sph), "model": 1}})
