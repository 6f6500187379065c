"""The scripts of docs/examples write their figures to the current directory (or --out), never into
the repository. The numbers of the examples are tested where their models are:
dem_wall.py in tests/test_force_law.py, rough_surface.py (slow) in tests/test_rough.py."""
import runpy
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "docs" / "examples"


def test_rough_surface_default_output_is_the_current_directory(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    mod = runpy.run_path(str(EXAMPLES / "rough_surface.py"))
    monkeypatch.chdir(tmp_path)
    assert mod["out_path"]() == tmp_path / "rough_surface.png"
    assert mod["out_path"]("x/y.png") == Path("x/y.png")


def test_contact_law_loop_writes_to_the_current_directory_or_out(tmp_path):
    """Run as a script from another directory: the PNG lands there; --out names another file."""
    pytest.importorskip("matplotlib")
    script = str(EXAMPLES / "contact_law_loop.py")
    r = subprocess.run([sys.executable, script], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "contact_law_loop.png").stat().st_size > 10_000
    assert "w_res*" in r.stdout
    mod = runpy.run_path(script)
    assert mod["out_path"](["x", "--out", str(tmp_path / "b.png")]) == tmp_path / "b.png"
    assert mod["out_path"](["x", str(tmp_path / "c.png")]) == tmp_path / "c.png"  # the old positional form


def test_topography_summits_writes_its_figure(tmp_path):
    """docs/examples/topography_summits.py (the docs' figure of a map's summits and e(V)) runs from
    another directory and writes its PNG there; its printed counts name every summit kept."""
    pytest.importorskip("matplotlib")
    pytest.importorskip("SurfaceTopography")
    script = str(EXAMPLES / "topography_summits.py")
    r = subprocess.run([sys.executable, script], cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "topography_summits.png").stat().st_size > 10_000
    assert "'n_summits'" in r.stdout and "e explicit" in r.stdout
