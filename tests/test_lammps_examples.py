"""docs/examples/lammps_pour_*.in: LAMMPS's granular pour examples as pair_style jgm inputs.

Each example runs as documented (its ``${plugin}`` given) and again with its contact lines swapped
for LAMMPS's ``pair_style granular`` (``hertz/material`` with the same E and nu, the same Mindlin
friction, a constant coefficient of restitution) and ``fix wall/gran``: every ball must be inserted,
the bed must settle (kinetic energy down by orders of magnitude from its peak), rest at the height of
granular's bed within a few per cent, and hold no sphere deep inside another.
"""
import re
from pathlib import Path

import numpy as np
import pytest

from lammps_run import deepest_overlap, lmp

pytestmark = pytest.mark.lammps

EXAMPLES = Path(__file__).resolve().parents[1] / "docs" / "examples"
#: granular's constant e per Young's modulus of the examples' materials (Pa): fastrest's e of the
#: pair at ~1 m/s, roughly (brass 0.43, aluminium 6061-T6 0.73; the steel plate under brass 0.46).
E_CONST = {"110e9": 0.45, "70e9": 0.7, "200e9": 0.5}


def _granular(text):
    """The example with pair_style jgm, its pair_coeff and fix wall/jgm lines swapped for granular's."""
    mu = re.search(r"^pair_style\s+jgm.*tangential mindlin (\S+)", text, re.M).group(1)

    def model(E, nu):
        return (f"hertz/material {E} {E_CONST[E]} {nu} tangential mindlin NULL 1.0 {mu} "
                "damping coeff_restitution")

    out = []
    for line in text.splitlines():
        f = line.split("#")[0].split()
        if f[:2] == ["plugin", "load"]:
            continue
        if f[:1] == ["pair_style"]:
            line = "pair_style granular"
        elif f[:1] == ["pair_coeff"]:
            line = f"pair_coeff {f[1]} {f[2]} {model(f[3], f[4])}"
        elif len(f) > 3 and f[0] == "fix" and f[3] == "wall/jgm":
            assert f[4] == "zplane"
            line = f"fix {f[1]} {f[2]} wall/gran granular {model(f[7], f[8])} zplane {f[5]} {f[6]}"
        out.append(line)
    assert any("wall/gran" in line for line in out) and not any("jgm" in line.split("#")[0] for line in out)
    return "\n".join(out) + "\n"


def _numbers(line):
    """The floats of a thermo row, or None."""
    try:
        return [float(v) for v in line.split()]
    except ValueError:
        return None


def _run(name, style, tmp_path):
    text = (EXAMPLES / f"lammps_{name}.in").read_text()
    text = text.replace("${plugin}", "@PLUGIN@") if style == "jgm" else _granular(text)
    d = tmp_path / style
    d.mkdir()
    _, out = lmp(text, d)
    rows = np.array([r[:5] for r in map(_numbers, out.splitlines()) if r and len(r) >= 5])  # step atoms ke erot zc
    inserted, wanted = map(int, re.search(r"^atoms inserted: (\d+) of (\d+)", out, re.M).groups())
    return {"out": out, "rows": rows, "inserted": inserted, "wanted": wanted, "dir": d,
            "ke": float(re.search(r"^kinetic energy: (\S+) J", out, re.M).group(1)),
            "z": float(re.search(r"^bed height \(centre of mass\): (\S+) m", out, re.M).group(1))}


def _check_settled_bed(jgm, gran, dump, box):
    for r in (jgm, gran):
        assert r["inserted"] == r["wanted"], (r["inserted"], r["wanted"])
    peak = jgm["rows"][:, 2].max()
    assert jgm["ke"] < 1e-3 * peak, (jgm["ke"], peak)  # settled: the balls' kinetic energy fell >1000x
    assert abs(jgm["z"] - gran["z"]) <= 0.05 * gran["z"], (jgm["z"], gran["z"])
    # no ball found only deep inside another (plastic dents leave ~1e-3 of the reduced radius)
    assert deepest_overlap(jgm["dir"] / dump, box) < 0.01
    assert "WARNING: fastrest" not in jgm["out"]  # the materials lie in the model's validated range


def test_pour_flatwall_example(tmp_path):
    """in.pour.flatwall's two types, brass and aluminium balls from two cylinders onto a steel plate."""
    jgm, gran = _run("pour_flatwall", "jgm", tmp_path), _run("pour_flatwall", "granular", tmp_path)
    assert jgm["wanted"] == 400
    _check_settled_bed(jgm, gran, "pour_flatwall.dump", 0.12)
    d = np.loadtxt(jgm["dir"] / "pour_flatwall.dump", skiprows=9)
    assert sorted(set(d[:, 1])) == [1.0, 2.0] and (d[:, 1] == 1).sum() == 200  # both types, 200 each
    assert d[:, 2].min() >= 0.004 - 1e-12 and d[:, 2].max() <= 0.006 + 1e-12  # radii of diam range 8-12 mm
    assert (d[:, 5] - d[:, 2]).min() > -1e-4  # every ball above the plate


def test_pour_chute_example(tmp_path):
    """in.pour's pour then chute: the settled bed flows down the plate once gravity tilts by 26 deg."""
    jgm, gran = _run("pour_chute", "jgm", tmp_path), _run("pour_chute", "granular", tmp_path)
    assert jgm["wanted"] == 400
    _check_settled_bed(jgm, gran, "pour_chute.dump", 0.08)
    vx = {}
    for style, r in (("jgm", jgm), ("granular", gran)):
        m = re.search(r"^chute: mean velocity down the slope after (\S+) s: (\S+) m/s "
                      r"\(free fall along it: (\S+) m/s\)", r["out"], re.M)
        t, v, free = map(float, m.groups())
        assert free == pytest.approx(9.81 * np.sin(np.radians(26.0)) * t, rel=1e-5)
        # gravity drives it and the plate's friction holds it back: flowing, slower than sliding freely
        assert 0.2 * free < v < free, (style, v, free)
        vx[style] = v
    assert abs(vx["jgm"] - vx["granular"]) <= 0.25 * vx["granular"], vx
