"""The command line as a user meets it: warnings and errors as one line under the subcommand's
prefix, help texts for every command, the --pairs columns as the code reads them, the rule for a
missing --out directory, errors naming the option (and the --materials entry) at fault, and
``fastrest e`` for two free spheres against the Python API (fastrest.Impact.two_spheres).
"""
import json
import re
import warnings
from pathlib import Path

import pytest

import fastrest
from fastrest import cli
from fastrest.export import velocity

REPO = Path(__file__).resolve().parents[1]
STEEL = ["--E", "200e9", "--nu", "0.33", "--Sy", "1.12e9", "--R", "0.01", "--rho", "7800"]


def run(argv, capsys):
    code = cli.main(argv)
    out, err = capsys.readouterr()
    return code, out, err


# --- warnings -----------------------------------------------------------------------------------

def test_a_warning_is_one_line_under_the_command_prefix(capsys):
    """A Material in the wrong units warns when built: one stderr line per warning, no file, line
    number or source of Python's default format."""
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        code, out, err = run(["e", "--E", "200", "--nu", "0.3", "--Sy", "1e9", "--R", "0.01", "--rho", "7800",
                              "--V", "1e-9"], capsys)
    assert code == 0, err
    lines = err.splitlines()
    assert lines and all(x.startswith("fastrest e: warning: ") for x in lines), err
    assert any("E = 200.0 Pa" in x and "check the units" in x for x in lines), err
    assert "ValidityWarning" not in err and ".py:" not in err and "sys.exit" not in err


def test_unit_slip_warnings_name_the_options_not_objects(capsys):
    """A modulus in GPa on the command line: the warnings name --E (and --flat-E for the flat), not
    the Material or Impact (or its sphere.E) the user never made; the units hint stays as it is."""
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        code, out, err = run(["e", "--E", "200", "--nu", "0.3", "--Sy", "1e9", "--R", "0.01", "--rho", "7800",
                              "--flat-E", "70", "--flat-nu", "0.3", "--V", "1e-9"], capsys)
    assert code == 0, err
    assert "--E = 200.0 Pa is below" in err and "--flat-E = 70.0 Pa is below" in err, err
    assert "Material:" not in err and "Impact:" not in err and "sphere.E" not in err and "flat.E" not in err, err
    assert "check the units: E and Sy in Pa" in err


def test_the_warning_format_is_restored_after_main(capsys):
    before = warnings.showwarning
    run(["e"] + STEEL + ["--V", "1"], capsys)
    assert warnings.showwarning is before


# --- errors -------------------------------------------------------------------------------------

def test_an_unwritable_out_has_the_subcommand_prefix_and_no_errno(capsys, tmp_path):
    out = tmp_path / "missing" / "x"
    code, _, err = run(["export", "velocity"] + STEEL + ["--V-max", "2", "--out", str(out)], capsys)
    assert code == 1
    assert err.startswith("fastrest export velocity: error: --out: "), err
    assert "[Errno" not in err and str(tmp_path / "missing") in err and len(err.splitlines()) == 1


@pytest.mark.parametrize("argv, prefix", [
    (["export", "c", "--materials", "0.005:0.33", "--out", "{missing}/x.h"], "fastrest export c: error: --out: "),
    (["export", "grid", "--out", "{missing}/x.nc"], "fastrest export grid: error: --out: "),
    (["build", "--out", "{missing}/t.h5", "--n-nu", "6"], "fastrest build: error: --out: "),
])
def test_every_file_writer_refuses_a_missing_directory_before_writing(argv, prefix, capsys, tmp_path):
    """One rule (docs/export.md, docs/tables.md): a file's directory must exist; nothing is created."""
    missing = tmp_path / "new" / "dir"
    code, _, err = run([a.format(missing=missing) for a in argv], capsys)
    assert code == 1 and err.startswith(prefix), err
    assert "does not exist" in err or "No such file or directory" in err, err
    assert not (tmp_path / "new").exists()


def test_flat_errors_name_the_flat_options(capsys):
    code, _, err = run(["e"] + STEEL + ["--V", "1", "--flat-E", "nan", "--flat-nu", "0.3"], capsys)
    assert code == 2 and "--flat-E must be finite" in err, err
    code, _, err = run(["e"] + STEEL + ["--V", "1", "--flat-E", "2e11", "--flat-nu", "0.7"], capsys)
    assert code == 2 and "--flat-nu (Poisson's ratio) must be in [0, 0.5)" in err, err
    code, _, err = run(["e", "--E", "nan", "--nu", "0.3", "--Sy", "1e9", "--R", "0.01", "--rho", "7800",
                        "--V", "1"], capsys)
    assert code == 2 and "--E must be finite" in err, err


@pytest.mark.parametrize("entries, bad, k", [(["0.005:0.33", "nan:0.3"], "nan:0.3", 1),
                                             (["0.005:0.5"], "0.005:0.5", 0),
                                             (["0.005:0.3", "0.004:0.3:1.5"], "0.004:0.3:1.5", 1)])
def test_export_c_names_the_material_entry(entries, bad, k, capsys, tmp_path):
    code, _, err = run(["export", "c", "--materials", *entries, "--out", str(tmp_path / "x.h")], capsys)
    assert code == 2 and f"--materials entry {bad!r} (material {k})" in err, err
    assert not (tmp_path / "x.h").exists()


# --- help ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("cmd", [["e"], ["build"], ["info"], ["warmup"], ["figures"], ["export"],
                                 ["export", "grid"], ["export", "velocity"], ["export", "c"]])
def test_every_command_has_a_description(cmd, capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(cmd + ["-h"])
    assert exc.value.code == 0
    text = capsys.readouterr().out
    body = text.split("\n\n")[1]  # after the usage paragraph: the description, not the options
    assert not body.lstrip().startswith(("options:", "positional")) and len(body.split()) >= 8, text


def _columns(spec):
    """``a,b[,c,d]`` -> ["a", "b", "c", "d"]."""
    return [c for c in re.split(r"[,\[\]]+", spec) if c]


def test_pairs_columns_in_help_and_docs_are_those_the_code_reads(capsys):
    with pytest.raises(SystemExit):
        cli.main(["export", "velocity", "-h"])
    help_text = " ".join(capsys.readouterr().out.split())
    # argparse may wrap inside the column list: compare with the spaces taken out
    m = re.search(r"--pairs PAIRS CSV file .*?\(in any order\): ([\w,\[\] ]+?);", help_text)
    assert m, help_text
    assert _columns(m[1].replace(" ", "")) == list(velocity.PAIR_KEYS)
    doc = (REPO / "docs" / "export.md").read_text()
    m = re.search(r"`--pairs pairs\.csv` with a header row\s+`([^`]+)`", doc)
    assert m, "docs/export.md: the --pairs header row"
    assert _columns(m[1]) == list(velocity.PAIR_KEYS)


def test_pairs_columns_are_read_by_name_in_any_order(tmp_path):
    """What the help says: the columns in another order give the same pairs."""
    keys = list(velocity.PAIR_KEYS)
    vals = {"name": "s", "E": "2e11", "nu": "0.3", "Sy": "1e9", "R": "0.01", "rho": "7800", "V_max": "2"}
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    a.write_text(",".join(keys) + "\n" + ",".join(vals.get(k, "") for k in keys) + "\n")
    rev = keys[::-1]
    b.write_text(",".join(rev) + "\n" + ",".join(vals.get(k, "") for k in rev) + "\n")
    assert velocity.read_pairs(a) == velocity.read_pairs(b)


# --- fastrest e: two free spheres ---------------------------------------------------------------

def test_e_two_spheres_matches_impact_two_spheres(capsys):
    steel = fastrest.Material(200e9, 0.33, 1.12e9, rho=7800)
    alu = fastrest.Material(70e9, 0.33, 3e8, rho=2700)
    imp = fastrest.Impact.two_spheres(steel, 0.01, alu, 0.02)
    V = [0.5, 1.0, 3.0]
    code, out, err = run(["e"] + STEEL + ["--sphere2-E", "70e9", "--sphere2-nu", "0.33", "--sphere2-Sy", "3e8",
                                          "--sphere2-R", "0.02", "--sphere2-rho", "2700", "--json",
                                          "--V", *map(str, V)], capsys)
    assert code == 0, err
    doc = json.loads(out)
    assert doc["bodies"] == "two spheres"
    for k, v in imp.critical_values().items():
        assert doc["critical"][k] == pytest.approx(v, rel=1e-15, abs=0.0), k
    for m in fastrest.unloading.NAMES:
        got = [r["e_" + m] for r in doc["impacts"]]
        assert got == pytest.approx(list(imp.e(V, m)), rel=1e-14), m
    # the text output says which body yields (aluminium: the smaller C(nu) Sy)
    code, out, err = run(["e"] + STEEL + ["--sphere2-E", "70e9", "--sphere2-nu", "0.33", "--sphere2-Sy", "3e8",
                                          "--sphere2-R", "0.02", "--sphere2-rho", "2700", "--V", "1"], capsys)
    assert code == 0 and "two free spheres" in out and "sphere 2 (--sphere2-*) yields first" in out, out


def test_e_two_spheres_with_masses(capsys):
    steel = fastrest.Material(200e9, 0.3, 1e9)
    imp = fastrest.Impact.two_spheres(steel, 0.01, steel, 0.005, 0.03, 0.01)
    code, out, err = run(["e", "--E", "200e9", "--nu", "0.3", "--Sy", "1e9", "--R", "0.01", "--mass", "0.03",
                          "--sphere2-E", "200e9", "--sphere2-nu", "0.3", "--sphere2-Sy", "1e9", "--sphere2-R",
                          "0.005", "--sphere2-mass", "0.01", "--json", "--V", "2"], capsys)
    assert code == 0, err
    doc = json.loads(out)
    assert doc["critical"]["mass"] == pytest.approx(imp.mass, rel=1e-15)
    assert doc["critical"]["R_eff"] == pytest.approx(imp.R_eff, rel=1e-15)
    assert doc["impacts"][0]["e_jcg"] == pytest.approx(float(imp.e(2.0)), rel=1e-14)


@pytest.mark.parametrize("extra, needle", [
    (["--sphere2-E", "70e9", "--sphere2-nu", "0.33", "--sphere2-rho", "2700"], "--sphere2-R"),
    (["--sphere2-E", "70e9", "--sphere2-nu", "0.33", "--sphere2-R", "0.02"], "--sphere2-rho"),
    (["--sphere2-E", "70e9", "--sphere2-nu", "0.33", "--sphere2-R", "-1", "--sphere2-rho", "2700"],
     "--sphere2-R must be finite and > 0"),
    (["--sphere2-E", "-1", "--sphere2-nu", "0.33", "--sphere2-R", "0.02", "--sphere2-rho", "2700"],
     "--sphere2-E must be finite and > 0"),
    (["--sphere2-E", "70e9", "--sphere2-nu", "0.33", "--sphere2-R", "0.02", "--sphere2-rho", "2700",
      "--flat-E", "2e11"], "exclude each other"),
])
def test_e_two_spheres_errors_name_the_option(extra, needle, capsys):
    code, _, err = run(["e"] + STEEL + extra + ["--V", "1"], capsys)
    assert code == 2 and err.startswith("fastrest e: error: ") and needle in err, err


def test_e_two_spheres_is_documented(capsys):
    with pytest.raises(SystemExit):
        cli.main(["e", "-h"])
    text = capsys.readouterr().out
    for opt in ("--sphere2-E", "--sphere2-nu", "--sphere2-Sy", "--sphere2-Et", "--sphere2-R", "--sphere2-rho",
                "--sphere2-mass"):
        assert opt in text
    assert "--sphere2-E" in (REPO / "docs" / "getting-started.md").read_text()


def test_info_prints_each_error_figure_rounded_up(capsys):
    """`fastrest info` prints the stored measured errors to 3 digits, never below the stored value
    (a figure rounded to nearest could state less than the worst found)."""
    import fastrest
    from fastrest import cli

    assert cli.main(["info"]) == 0
    out = capsys.readouterr().out
    stored = fastrest.load_table().attrs["measured_error"]
    for name, err in stored.items():
        line = next(l for l in out.splitlines() if l.strip().startswith(f"max relative error {name} "))
        printed = float(line.split()[4])
        assert err["max_rel_error"] <= printed <= err["max_rel_error"] * (1 + 2e-2), (name, line)
