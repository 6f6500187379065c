"""`fastrest export velocity`: rows of e, 1 - e^2, w_m against impact speed V for DEM codes.
Reference: the direct solver (fastrest.direct through fastrest.Impact) at points between rows."""
import csv
import json
import os

import numpy as np
import pytest

import fastrest
from fastrest import cli
from fastrest.export import velocity

STEEL = ["--E", "200e9", "--nu", "0.33", "--Sy", "1.12e9", "--R", "0.01", "--rho", "7800"]


def _read_csv(path):
    lines = path.read_text().splitlines()
    head = {}
    for line in lines:
        if line.startswith("# "):
            k, v = line[2:].split(": ", 1)
            head[k] = json.loads(v)
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    return head, {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def test_single_pair_rows_meet_tol(tmp_path, capsys):
    out = tmp_path / "steel"
    tol = 1e-4
    assert cli.main(["export", "velocity"] + STEEL + ["--V-max", "5", "--tol", str(tol), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "worst error" in printed
    head, cols = _read_csv(tmp_path / "steel.csv")
    imp = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, rho=7800), 0.01)
    assert head["critical"]["V_c"] == pytest.approx(imp.V_c, rel=1e-15)
    assert cols["V_m_s"][0] == 0.0 and cols["V_m_s"][-1] == pytest.approx(5.0, rel=1e-12)
    assert np.all(np.diff(cols["V_m_s"]) > 0)
    assert max(head["measured_max_interpolation_error"].values()) <= tol
    # the rows are the exact solution
    for m in fastrest.unloading.NAMES:
        np.testing.assert_allclose(cols[f"e_{m}"][1:], imp.e(cols["V_m_s"][1:], m), rtol=1e-12)
    # independent check between the rows: linear interpolation vs the direct solver
    rng = np.random.default_rng(3)
    V = np.sort(rng.uniform(1e-3, 5.0, 4000))
    jump = velocity.JUMP[0] * imp.V_c
    V = V[np.abs(V - jump) > 1e-6 * jump]  # the model's own jump at V1* = 1.9^1.25
    for m in fastrest.unloading.NAMES:
        lin = np.interp(V, cols["V_m_s"], cols[f"e_{m}"])
        assert np.max(np.abs(lin - imp.e(V, m))) <= tol
    with open(tmp_path / "steel.json") as fh:
        doc = json.load(fh)
    assert doc["rows"]["V_m_s"] == list(cols["V_m_s"])
    assert doc["critical"]["eps_y"] == pytest.approx(imp.eps_y)


def test_pairs_file(tmp_path, capsys):
    pairs = tmp_path / "pairs.csv"
    pairs.write_text("# materials\nname,E,nu,Sy,R,rho,flat_E,flat_nu,V_max\n"
                     "steel,200e9,0.33,1.12e9,0.01,7800,,,3\n"
                     "al_on_steel,70e9,0.33,2.8e8,0.005,2700,200e9,0.3,2\n")
    out = tmp_path / "dem"
    assert cli.main(["export", "velocity", "--pairs", str(pairs), "--tol", "1e-3", "--out", str(out)]) == 0
    assert sorted(os.listdir(tmp_path)) == ["dem.json", "dem_al_on_steel.csv", "dem_steel.csv", "pairs.csv"]
    doc = json.loads((tmp_path / "dem.json").read_text())
    assert set(doc["pairs"]) == {"steel", "al_on_steel"}
    assert doc["pairs"]["al_on_steel"]["rows"]["V_m_s"][-1] == pytest.approx(2.0)
    # one pair of the file
    assert cli.main(["export", "velocity", "--pairs", str(pairs), "--pair", "steel", "--tol", "1e-3",
                     "--out", str(tmp_path / "one")]) == 0
    assert (tmp_path / "one.csv").exists()


@pytest.mark.parametrize("extra, option", [
    (STEEL + ["--V-max", "500", "--tol", "1e-4"], "--V-max"),
    (STEEL + ["--V-max", "5", "--tol", "1e-14"], "--tol"),
    (STEEL + ["--V-max", "5", "--tol", "0"], "--tol"),
    (STEEL + ["--tol", "1e-3"], "--V-max"),
    (["--E", "200e9", "--nu", "0.33", "--Sy", "1.12e9", "--R", "0.01", "--V-max", "1"], "--rho"),
    (STEEL[:2] + ["--nu", "0.7"] + STEEL[4:] + ["--V-max", "1"], "nu"),
])
def test_bad_input(tmp_path, capsys, extra, option):
    out = tmp_path / "x"
    assert cli.main(["export", "velocity"] + extra + ["--out", str(out)]) == 2
    assert option in capsys.readouterr().err
    assert os.listdir(tmp_path) == []


def test_bad_pairs(tmp_path, capsys):
    pairs = tmp_path / "p.csv"
    pairs.write_text("name,E,nu,Sy,R,rho,colour\nsteel,200e9,0.33,1.12e9,0.01,7800,red\n")
    assert cli.main(["export", "velocity", "--pairs", str(pairs), "--V-max", "1", "--out", str(tmp_path / "o")]) == 2
    assert "--pairs" in capsys.readouterr().err
    pairs.write_text("name,E,nu,Sy,R,rho\nsteel,200e9,0.33,1.12e9,0.01,7800\nbad,2e11,0.33,1e9,0.01,-1\n")
    assert cli.main(["export", "velocity", "--pairs", str(pairs), "--V-max", "1", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "'bad'" in err and "rho" in err
    assert cli.main(["export", "velocity", "--pairs", str(pairs), "--pair", "brass", "--V-max", "1",
                     "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "--pair" in err and "brass" in err
    assert sorted(os.listdir(tmp_path)) == ["p.csv"]
    assert cli.main(["export", "velocity", "--pairs", str(tmp_path / "missing.csv"), "--V-max", "1",
                     "--out", str(tmp_path / "o")]) == 2


def test_unwritable(tmp_path, capsys):
    """A missing directory is a file-system error (exit 1, as `build`), naming --out and the file."""
    assert cli.main(["export", "velocity"] + STEEL + ["--V-max", "1", "--out", str(tmp_path / "no" / "x")]) == 1
    err = capsys.readouterr().err
    assert "--out" in err and str(tmp_path / "no" / "x") in err


def test_damaged_pairs_file_in_subprocess(tmp_path):
    """A hostile --pairs file (random bytes) gives an error naming --pairs, no crash or hang."""
    import subprocess
    import sys
    bad = tmp_path / "pairs.csv"
    bad.write_bytes(np.random.default_rng(5).integers(0, 256, 4096, dtype=np.uint8).tobytes())
    r = subprocess.run([sys.executable, "-m", "fastrest", "export", "velocity", "--pairs", str(bad), "--V-max", "1",
                        "--out", str(tmp_path / "o")], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and "--pairs" in r.stderr
    assert sorted(os.listdir(tmp_path)) == ["pairs.csv"]
