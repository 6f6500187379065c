"""Tests of fastrest.figures and of the CLI's ``figures`` subcommand and ``e --model`` option."""
import json
import math
import sys

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import fastrest  # noqa: E402
from fastrest import Impact, Material, cli  # noqa: E402
from fastrest import figures as F  # noqa: E402
from fastrest import models  # noqa: E402

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
EXPECTED = ["fig2_energy", "fig3_max_interference", "fig4_residual_interference",
            "fig5_e_vs_chang_ling", "fig6_unloading_models", "fig7_alumina_on_aluminium",
            "fig8_alumina_on_steel", "hardening_e"]
TABLE1_ARGS = ["--E", "200e9", "--nu", "0.33", "--Sy", "1.12e9", "--R", "0.01", "--rho", "7800"]


def test_figures_cli_writes_every_png(tmp_path, capsys):
    out = tmp_path / "figs"
    assert cli.main(["figures", "--out", str(out)]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == sorted(f"{s}.png" for s in EXPECTED)
    for s in EXPECTED:
        data = (out / f"{s}.png").read_bytes()
        assert len(data) > 10_000, s
        assert data[:8] == PNG_MAGIC, s
        assert b"Software" not in data[:4096], s  # metadata={"Software": None}
    text = capsys.readouterr().out
    assert text.count("wrote ") == len(EXPECTED)


def test_registry_matches_expected_files():
    assert list(F.FIGURES) == EXPECTED


@pytest.mark.parametrize("stem", EXPECTED)
def test_figure_accepts_existing_ax(stem):
    from matplotlib.figure import Figure

    fig = Figure()
    axes = fig.subplots(1, 2)
    got_fig, got_ax = F.FIGURES[stem](ax=axes[1])
    assert got_fig is fig and got_ax is axes[1]
    assert axes[1].lines, "nothing drawn into the given axes"
    assert not axes[0].lines, "drew into the wrong axes"
    assert axes[1].get_xlabel() and axes[1].get_ylabel()
    labels = [h.get_label() for h in axes[1].get_legend().legend_handles]
    assert labels and all(labels)


@pytest.mark.parametrize("stem", EXPECTED)
def test_figure_makes_own_figure(stem):
    fig, ax = F.FIGURES[stem]()
    assert ax.figure is fig and ax.lines


def test_figure_options_are_keyword_only(tmp_path):
    for fn in F.FIGURES.values():
        with pytest.raises(TypeError):
            fn(None)
    with pytest.raises(TypeError):
        F.write_all(tmp_path, 20)


def test_kharaz_impact_uses_alumina_mass_and_both_moduli():
    imp = F.kharaz_impact("aluminium")
    assert imp.mass == pytest.approx(4 / 3 * math.pi * 0.0025**3 * F.ALUMINA_DENSITY, rel=1e-14)
    e_eff = 1 / ((1 - 0.22**2) / 370e9 + (1 - 0.33**2) / 68e9)
    assert imp.E_eff == pytest.approx(e_eff, rel=1e-14)
    assert imp.nu == 0.33 and imp.Sy == 0.38e9
    steel = F.kharaz_impact("steel")
    assert steel.nu == 0.29 and steel.Sy == 1.03e9
    with pytest.raises(ValueError, match="flat"):
        F.kharaz_impact("copper")


def test_figure_curves_stay_in_domain():
    """Every JGM curve of Figs 3, 5, 6 ends at or below the w_m* = 425 limit's speed."""
    from fastrest import direct

    _, ax = F.figure3()
    for line in ax.lines:
        y = np.asarray(line.get_ydata(), dtype=float)
        if "JGM" in line.get_label():
            assert np.nanmax(y) <= 425.0 * (1 + 1e-9)
    _, ax = F.figure6()
    x = np.asarray(ax.lines[0].get_xdata())
    assert x.max() <= fastrest.limit(F.TABLE1_EPS_Y, F.TABLE1_NU).v1_star


def test_figures_cli_without_matplotlib(tmp_path, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib -> ImportError
    assert cli.main(["figures", "--out", str(tmp_path / "x")]) == 1
    err = capsys.readouterr().err
    assert "pip install fastrest[plot]" in err
    assert not (tmp_path / "x").exists()


def test_import_fastrest_does_not_import_matplotlib():
    import subprocess

    code = "import sys, fastrest, fastrest.figures; print('matplotlib' in sys.modules)"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "False"


# ---------------------------------------------------------------------------- e --model
def _table1_impact():
    return Impact(Material(E=200e9, nu=0.33, Sy=1.12e9, rho=7800.0), R=0.01)


def test_e_model_json_matches_evaluate(capsys):
    V = [0.5, 1.0, 2.0, 5.0]
    assert cli.main(["e", *TABLE1_ARGS, "--V", *map(str, V), "--model", "thornton", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["models"] == ["thornton"]
    expected = models.evaluate("thornton", _table1_impact(), np.array(V))
    got = [r["e_thornton"] for r in out["impacts"]]
    np.testing.assert_array_equal(got, expected)
    assert "e_wu" not in out["impacts"][0]


def test_e_model_repeatable_and_all(capsys):
    V = [0.3, 3.0]
    assert cli.main(["e", *TABLE1_ARGS, "--V", *map(str, V), "--model", "wu",
                     "--model", "weir_tallon,chang_ling", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["models"] == ["wu", "weir_tallon", "chang_ling"]
    imp = _table1_impact()
    for name in out["models"]:
        np.testing.assert_array_equal([r["e_" + name] for r in out["impacts"]],
                                      models.evaluate(name, imp, np.array(V)))
    assert cli.main(["e", *TABLE1_ARGS, "--V", "1", "--models", "all", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["models"] == list(models.MODELS)
    for name in models.MODELS:
        assert out["impacts"][0]["e_" + name] == models.evaluate(name, imp, 1.0)


def test_e_model_text_columns(capsys):
    assert cli.main(["e", *TABLE1_ARGS, "--V", "0.5", "2", "--model", "thornton"]) == 0
    text = capsys.readouterr().out
    assert "e (thornton)" in text
    row = [ln for ln in text.splitlines() if ln.split() and ln.split()[0] == "0.5"][0]
    assert float(row.split()[-1]) == pytest.approx(models.evaluate("thornton", _table1_impact(), 0.5), abs=1e-6)


def test_e_without_model_unchanged(capsys):
    assert cli.main(["e", *TABLE1_ARGS, "--V", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert "models" not in out
    assert set(out["impacts"][0]) == {"V", "V1_star", "omega_m_star", "e_jcg", "e_etsion", "e_brake",
                                         "V2_jcg", "V2_etsion", "V2_brake"}


def test_e_unknown_model_is_a_clear_error(capsys):
    assert cli.main(["e", *TABLE1_ARGS, "--V", "1", "--model", "nope"]) == 2
    err = capsys.readouterr().err
    assert "nope" in err and "thornton" in err
