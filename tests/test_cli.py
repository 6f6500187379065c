"""Tests of the command line (fastrest.cli): `e`, `info`, `build`.

Most tests call fastrest.cli.main([...]) in-process (capturing stdout/stderr); one runs
`python -m fastrest` in a subprocess to check the module entry point and the exit status.
Reference values: fastrest.Impact(...).e / omega_m (the direct solver).
"""
import json
import os
import subprocess
import sys
import warnings
from pathlib import Path

import h5py
import numpy as np
import pytest

import fastrest
from fastrest import cli, tables

REPO = Path(__file__).resolve().parents[1]
README_ARGS = ["e", "--E", "200e9", "--nu", "0.33", "--Sy", "1.12e9", "--R", "0.01", "--rho", "7800",
               "--V", "0.5", "1", "2", "5"]
README_V = [0.5, 1.0, 2.0, 5.0]


def readme_impact():
    return fastrest.Impact(fastrest.Material(E=200e9, nu=0.33, Sy=1.12e9, rho=7800), R=0.01)


def run(argv, capsys):
    code = cli.main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def parse_impact_rows(out):
    """Numeric rows of the `e` table: V, V1*, w_m*, e (JCG), e (Etsion), e (Brake)."""
    lines = out.splitlines()
    start = next(i for i, line in enumerate(lines) if "e (JCG)" in line) + 1
    rows = []
    for line in lines[start:]:
        parts = line.split()
        if len(parts) != 6:
            break
        rows.append([float(p) for p in parts])
    return np.array(rows)


def test_e_readme_example(capsys):
    code, out, err = run(README_ARGS, capsys)
    assert code == 0, err
    imp = readme_impact()
    assert "V_c" in out and "eps_y" in out
    # critical values printed to 6 significant digits
    crit = {line.split()[0]: float(line.split()[2]) for line in out.splitlines()
            if len(line.split()) >= 3 and line.split()[1] == "="}
    assert crit["V_c"] == pytest.approx(imp.V_c, rel=1e-5)
    assert crit["eps_y"] == pytest.approx(imp.eps_y, rel=1e-5)
    rows = parse_impact_rows(out)
    assert rows.shape == (4, 6)
    V = np.array(README_V)
    np.testing.assert_array_equal(rows[:, 0], V)
    np.testing.assert_allclose(rows[:, 1], V / imp.V_c, rtol=1e-3)                    # %10.4g
    np.testing.assert_allclose(rows[:, 2], imp.max_interference(V) / imp.omega_c, rtol=1e-4)                 # %10.5g
    np.testing.assert_allclose(rows[:, 3], imp.e(V, unloading="jcg"), rtol=0, atol=5.01e-7)   # %10.6f
    np.testing.assert_allclose(rows[:, 4], imp.e(V, unloading="etsion"), rtol=0, atol=5.01e-7)


def test_e_json(capsys):
    code, out, err = run(README_ARGS + ["--json"], capsys)
    assert code == 0, err
    doc = json.loads(out)
    imp = readme_impact()
    assert doc["critical"]["V_c"] == pytest.approx(imp.V_c, rel=1e-12)
    assert doc["critical"]["eps_y"] == pytest.approx(imp.eps_y, rel=1e-12)
    assert doc["warnings"] == []
    rows = doc["impacts"]
    assert [r["V"] for r in rows] == README_V
    V = np.array(README_V)
    for key, ref in (("V1_star", V / imp.V_c), ("omega_m_star", imp.max_interference(V) / imp.omega_c),
                     ("e_jcg", imp.e(V, unloading="jcg")), ("e_etsion", imp.e(V, unloading="etsion")),
                     ("V2_jcg", imp.rebound_velocity(V, unloading="jcg")),
                     ("V2_etsion", imp.rebound_velocity(V, unloading="etsion"))):
        np.testing.assert_allclose([r[key] for r in rows], ref, rtol=1e-12, atol=0, err_msg=key)


def test_e_elastic_flat_json(capsys):
    """Two materials: sphere on an elastic-plastic flat."""
    args = ["e", "--E", "200e9", "--nu", "0.3", "--Sy", "1e9", "--R", "0.005", "--rho", "7800",
            "--flat-E", "70e9", "--flat-nu", "0.33", "--flat-Sy", "2e8", "--V", "0.3", "--json"]
    code, out, err = run(args, capsys)
    assert code == 0, err
    doc = json.loads(out)
    imp = fastrest.Impact(fastrest.Material(200e9, 0.3, 1e9, rho=7800), 0.005,
                          flat=fastrest.Material(70e9, 0.33, 2e8))
    assert doc["impacts"][0]["e_jcg"] == pytest.approx(float(imp.e(0.3)), rel=1e-12)


@pytest.mark.parametrize("bad, name", [(["--nu", "0.7"], "nu"), (["--nu", "-0.1"], "nu"),
                                       (["--Sy", "-5"], "Sy"), (["--R", "0"], "R")])
def test_e_bad_input_names_parameter(capsys, bad, name):
    args = list(README_ARGS)
    i = args.index(bad[0])
    args[i + 1] = bad[1]
    code, out, err = run(args, capsys)
    assert code != 0
    assert name in err
    assert "Traceback" not in err


def test_e_past_425_is_an_error_unless_extrapolating(capsys):
    imp = readme_impact()
    v_lim = fastrest.limit(imp.eps_y, imp.nu).v1_star * imp.V_c
    args = README_ARGS[:README_ARGS.index("--V")] + ["--V", repr(v_lim * 1.2)]
    code, out, err = run(args, capsys)
    assert code != 0 and "425" in err
    code, out, err = run(args + ["--extrapolate", "--json"], capsys)
    assert code == 0, err
    doc = json.loads(out)
    assert any("425" in w for w in doc["warnings"])


def test_e_keeps_the_speeds_the_model_covers(capsys):
    """Speeds past the model's end among valid ones: every valid speed is printed (its e that of
    Impact.e alone), each refused one gets its own error line naming it, and the exit status is 1;
    in JSON the refused speeds are listed."""
    imp = readme_impact()
    v_lim = fastrest.limit(imp.eps_y, imp.nu).v1_star * imp.V_c
    past = [v_lim * 1.2, v_lim * 3.0]
    args = README_ARGS[:README_ARGS.index("--V")] + ["--V", "0.5", repr(past[0]), "2", repr(past[1])]
    code, out, err = run(args, capsys)
    assert code == 1
    assert [ln for ln in err.splitlines() if "error: --V" in ln] == [
        ln for ln in err.splitlines() if "error: --V " in ln and "425" in ln] and err.count("error: --V ") == 2
    assert f"--V {past[0]:g}:" in err and f"--V {past[1]:g}:" in err
    code, out, err = run(args + ["--json"], capsys)
    assert code == 1
    doc = json.loads(out)
    assert [r["V"] for r in doc["impacts"]] == [0.5, 2.0]
    assert [r["e_jcg"] for r in doc["impacts"]] == pytest.approx(list(imp.e([0.5, 2.0])), rel=1e-12)
    assert [r["V"] for r in doc["refused"]] == past and all("425" in r["error"] for r in doc["refused"])


def test_e_single_speed_no_numpy_warning(capsys):
    """One --V: no FutureWarning from NumPy's broadcast views reaches the user or the output."""
    args = README_ARGS[:README_ARGS.index("--V")] + ["--V", "1", "--json"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        code, out, err = run(args, capsys)
    assert code == 0, err
    doc = json.loads(out)
    assert doc["warnings"] == []
    assert doc["impacts"][0]["e_jcg"] == pytest.approx(readme_impact().e(1.0), rel=1e-12)


def test_e_errors_name_the_flags(capsys):
    base = README_ARGS[:README_ARGS.index("--rho")]
    code, out, err = run(base + ["--V", "1"], capsys)
    assert code == 2 and "--rho" in err and "--mass" in err
    code, out, err = run(README_ARGS[:README_ARGS.index("--V")] + ["--V", "1", "-2"], capsys)
    assert code == 2 and "--V" in err and "m/s" in err and "-2" in err
    imp = readme_impact()
    v = imp.V_max() * 2
    code, out, err = run(README_ARGS[:README_ARGS.index("--V")] + ["--V", repr(v)], capsys)
    assert code == 2 and "--V" in err and f"{imp.V_max():.10g} m/s" in err
    code, out, err = run(README_ARGS + ["--flat-E", "70e9"], capsys)
    assert code == 2 and "--flat-nu" in err
    code, out, err = run(README_ARGS + ["--flat-Sy", "1e8"], capsys)
    assert code == 2 and "--flat-E" in err


def test_e_missing_argument_exits_nonzero(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["e", "--E", "200e9"])
    assert exc.value.code != 0


def test_info_default_table(capsys):
    path = tables.default_table_path()
    code, out, err = run(["info", str(path)], capsys)
    assert code == 0, err
    assert f"version {fastrest.tables.hdf5.FORMAT_VERSION}" in out
    assert "fastrest-table" in out
    assert "max relative error" in out
    for q in ("omega_m_star", "e_jcg", "loss_jcg", "e_etsion", "loss_etsion", "e_brake", "loss_brake"):
        assert q in out
    code, out, err = run(["info", str(path), "--json"], capsys)
    assert code == 0, err
    doc = json.loads(out)
    assert doc["format_version"] == fastrest.tables.hdf5.FORMAT_VERSION
    assert set(doc["measured_error"]) == {"omega_m_star", "e_jcg", "loss_jcg", "e_etsion", "loss_etsion",
                                          "e_brake", "loss_brake"}


def test_info_invalid_files_exit_1(capsys, tmp_path):
    text = tmp_path / "text.h5"
    text.write_text("not hdf5")
    foreign = tmp_path / "foreign.h5"
    with h5py.File(foreign, "w") as f:
        f["x"] = np.arange(3.0)
    corrupt = tmp_path / "corrupt.h5"
    src = tables.default_table_path()
    corrupt.write_bytes(src.read_bytes())
    with h5py.File(corrupt, "r") as f:
        off = f["e_etsion_0"].id.get_offset()
    with open(corrupt, "r+b") as fh:
        fh.seek(off + 100)
        b = fh.read(1)
        fh.seek(off + 100)
        fh.write(bytes([b[0] ^ 0xFF]))
    for p in (text, foreign, corrupt, tmp_path / "missing.h5"):
        code, out, err = run(["info", str(p)], capsys)
        assert code == 1, p
        assert str(p) in err


def test_build_small_grid(capsys, tmp_path):
    (tmp_path / "sub").mkdir()  # --out's directory must exist (tests/test_cli_messages.py)
    out_path = tmp_path / "sub" / "t.h5"
    code, out, err = run(["build", "--out", str(out_path), "--n-eps-y", "6", "--n-nu", "6",
                          "--eps-y-blocks", "16:6", "--n-eps-y-energy", "4", "--no-progress"], capsys)
    assert code == 0, err
    assert out_path.exists()
    assert "wrote" in out and str(out_path) in out
    t = fastrest.load_table(out_path)
    assert t.grid["n_eps_y"] == 6 and t.grid["n_nu"] == 6
    assert t.grid["eps_y_blocks"] == [[16.0, 6]] and t.grid["n_eps_y_energy"] == 4
    assert t.grid["eps_y_min"] == tables.DEFAULT_GRID["eps_y_min"]
    ref = fastrest.direct.e_exact(5.0, 0.005, 0.33)
    assert t.e(5.0, 0.005, 0.33) == pytest.approx(ref, rel=1e-3)
    assert list(out_path.parent.glob("*.tmp")) == []
    code, out, err = run(["info", str(out_path)], capsys)
    assert code == 0, err


def test_build_bad_grid_is_an_error(capsys, tmp_path):
    code, out, err = run(["build", "--out", str(tmp_path / "t.h5"), "--n-eps-y", "2"], capsys)
    assert code != 0
    assert "n_eps_y" in err
    assert not (tmp_path / "t.h5").exists()
    code, out, err = run(["build", "--default", "--n-nu", "7"], capsys)
    assert code != 0


def test_build_default_targets_source_tree_not_cwd(capsys, tmp_path, monkeypatch):
    """`build --default` rebuilds the checkout's fastrest/tables/default.h5 from any working
    directory; an install without a source tree needs --out."""
    assert tables.source_tree_table_path() == REPO / "fastrest" / "tables" / "default.h5"
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(tables, "source_tree_table_path", lambda: None)
    code, out, err = run(["build", "--default", "--no-progress"], capsys)
    assert code == 2 and "--out" in err
    assert list(tmp_path.iterdir()) == []


def test_help_lists_commands_and_defaults(capsys):
    with pytest.raises(SystemExit):
        cli.main(["--help"])
    out = capsys.readouterr().out
    for cmd in ("e", "build", "info", "warmup", "figures"):
        assert f"    {cmd} " in out
    with pytest.raises(SystemExit):
        cli.main(["build", "--help"])
    out = capsys.readouterr().out
    assert f"[default: {tables.DEFAULT_GRID['n_eps_y']}]" in " ".join(out.split())


def test_module_entry_point_subprocess(tmp_path):
    env = dict(os.environ)
    env["PYTHONPATH"] = str(REPO) + os.pathsep + env.get("PYTHONPATH", "")
    r = subprocess.run([sys.executable, "-m", "fastrest"] + README_ARGS + ["--json"], cwd=tmp_path,
                       env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    np.testing.assert_allclose([x["e_jcg"] for x in doc["impacts"]],
                               readme_impact().e(README_V), rtol=1e-12, atol=0)
    r = subprocess.run([sys.executable, "-m", "fastrest", "e", "--E", "200e9", "--nu", "0.7", "--Sy",
                        "1.12e9", "--R", "0.01", "--rho", "7800", "--V", "1"], cwd=tmp_path,
                       env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode != 0 and "nu" in r.stderr and "Traceback" not in r.stderr
    bad = tmp_path / "bad.h5"
    bad.write_bytes(b"\x89HDF\r\n\x1a\n" + b"\0" * 64)
    r = subprocess.run([sys.executable, "-m", "fastrest", "info", str(bad)], cwd=tmp_path,
                       env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 1 and str(bad) in r.stderr


@pytest.mark.parametrize("argv", [["e"], ["build"], ["export", "c"]])
def test_help_names_every_registered_unloading_model(argv, capsys):
    """The help texts are generated from the unloading registry: every model is named, and no text
    speaks of "both" models (there are three)."""
    from fastrest.unloading import MODELS

    with pytest.raises(SystemExit) as exc:
        cli.main(argv + ["-h"])
    assert exc.value.code == 0
    text = " ".join(capsys.readouterr().out.split())  # argparse wraps lines
    assert "both" not in text
    for m in MODELS.values():
        assert m.short in text or m.short.upper() in text, m.short
    if argv != ["export", "c"]:
        assert f"the {['', 'one', 'two', 'three', 'four'][len(MODELS)]} unloading models" in text
