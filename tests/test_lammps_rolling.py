"""Rolling and twisting resistance of pair_style jgm and fix wall/jgm against closed forms.

A steel sphere resting on the wall at Hertz's static overlap (elastic: w* ~ 0.02, F_n = m g):
* rolling without slip at speed v with ``rolling sds K 0 MU`` (the slider engaged) decelerates at
  (5/7) MU g (the torque R MU m g against I + m R^2 = (7/5) m R^2), and keeps rolling;
* spinning about the normal with ``twisting sds K 0 MU`` loses spin at MU m g / I;
* with ``twisting marshall`` at (2/3) mu a m g / I, a = sqrt(R delta) (Hertz's contact radius);
* none of them: no deceleration.
Pairs with rolling and twisting conserve linear and angular momentum; the gas's energy balance
with them is in tests/test_lammps.py.
"""
import numpy as np
import pytest

import fastrest
from lammps_run import lmp, pairs_script, read_dump

pytestmark = pytest.mark.lammps

STEEL = (200e9, 0.3, 1e9)
R, RHO, G = 0.01, 7800.0, 9.81
M = float(4 / 3 * np.pi * R ** 3 * RHO)
INERTIA = 0.4 * M * R ** 2
E_EFF = 1 / (2 * (1 - STEEL[1] ** 2) / STEEL[0])  # sphere on a flat of the same steel
DELTA = float((3 * M * G / (4 * E_EFF * np.sqrt(R))) ** (2 / 3))  # Hertz's static overlap


def _resting(tmp_path, pair_extra, v=0.0, spin=(0.0, 0.0, 0.0), steps=20000, dt=1e-6, every=1000):
    """The sphere resting on the wall (z = R - DELTA), moving at v along x with spin; thermo every
    ``every`` steps: step vx omegax omegay omegaz."""
    script = "\n".join([
        "units si", "atom_style sphere", "atom_modify map array", "boundary p p f",
        "region box block -1 1 -0.05 0.05 -0.01 0.05",
        "create_box 1 box", f"create_atoms 1 single 0 0 {R - DELTA!r}", f"set atom 1 diameter {2 * R!r}",
        f"set atom 1 density {RHO!r}", f"velocity all set {v!r} 0 0",
        f"set atom 1 omega {spin[0]!r} {spin[1]!r} {spin[2]!r}", "plugin load @PLUGIN@",
        f"pair_style jgm tangential mindlin 0.3 {pair_extra}", f"pair_coeff 1 1 {STEEL[0]!r} {STEEL[1]!r} {STEEL[2]!r}",
        f"fix w all wall/jgm zplane 0.0 NULL {STEEL[0]!r} {STEEL[1]!r} {STEEL[2]!r}", "fix g all gravity 9.81 vector 0 0 -1",
        "fix 1 all nve/sphere", f"timestep {dt!r}", "variable vx equal vx[1]", "compute om all property/atom omegax omegay omegaz",
        "compute w all reduce sum c_om[1] c_om[2] c_om[3]", "variable fz equal f_w[1]",
        "thermo_style custom step v_vx c_w[1] c_w[2] c_w[3] v_fz", "thermo_modify format float %.17g", f"thermo {every}",
        f"run {steps}"]) + "\n"
    _, out = lmp(script, tmp_path)
    rows = [t.split() for t in out.splitlines()]
    rows = np.array([[float(x) for x in t] for t in rows if len(t) == 6 and t[0].isdigit()])
    return rows[:, 0] * dt, rows[:, 1:]


def _slope(t, y, t0):
    keep = t >= t0
    return np.polyfit(t[keep], y[keep], 1)[0]


def test_static_overlap_carries_the_weight(tmp_path):
    t, y = _resting(tmp_path, "", steps=2000, every=100)
    assert np.allclose(-y[:, 4], M * G, rtol=1e-3)  # the force on the wall: Hertz's at DELTA is m g


@pytest.mark.parametrize("mu_r", [0.02, 0.05])
def test_rolling_sphere_decelerates_at_five_sevenths_mu_g(tmp_path, mu_r):
    v0 = 0.01
    t, y = _resting(tmp_path, f"rolling sds 1e5 0 {mu_r}", v=v0, spin=(0, v0 / R, 0))
    a = _slope(t, y[:, 0], 0.002)
    assert abs(a / (-5 / 7 * mu_r * G) - 1) < 0.01, a
    # rolls without slip, to the undamped Mindlin spring's oscillation (~1e-5 m/s; sliding at the
    # Coulomb limit would part them by ~0.1 m/s)
    assert np.allclose(y[t >= 0.002, 2] * R, y[t >= 0.002, 0], rtol=0, atol=0.01 * v0)


def test_rolling_sphere_without_resistance_keeps_rolling(tmp_path):
    v0 = 0.01
    t, y = _resting(tmp_path, "", v=v0, spin=(0, v0 / R, 0))
    assert np.allclose(y[:, 0], v0, rtol=1e-6)


def test_spinning_sphere_twisting_sds(tmp_path):
    mu_t = 1e-4  # m: the limit torque is MU F_n
    t, y = _resting(tmp_path, f"twisting sds 1.0 0 {mu_t}", spin=(0, 0, 1.0))
    alpha = _slope(t, y[:, 3], 0.002)
    assert abs(alpha / (-mu_t * M * G / INERTIA) - 1) < 0.01, alpha


def test_spinning_sphere_twisting_marshall(tmp_path):
    t, y = _resting(tmp_path, "twisting marshall", spin=(0, 0, 1.0), steps=30000)
    alpha = _slope(t, y[:, 3], 0.01)
    a = np.sqrt(R * DELTA)  # Hertz's contact radius (JGM's A* = w* below w* = 1)
    assert abs(alpha / (-2 / 3 * 0.3 * a * M * G / INERTIA) - 1) < 0.01, alpha


def test_rolling_and_twisting_bad_input(tmp_path):
    for extra, message in (("rolling sds 1e5 0", "'rolling sds' needs K GAMMA MU"),
                           ("rolling sds -1 0 0.1", "rolling K = -1 must be >= 0"),
                           ("rolling foo", "rolling model 'foo' is not one of none, sds"),
                           ("twisting sds 1 0 abc", "instead of 'abc'")):
        rc, out = lmp(pairs_script({1: STEEL + (0.0,)}, [(1, 1, 1.0)], R, RHO, 1e-8, 10).replace(
            "pair_style jgm unloading jcg", f"pair_style jgm unloading jcg tangential mindlin 0.3 {extra}"), tmp_path,
            check=False)
        assert rc != 0 and message in out, (extra, out[-800:])
    rc, out = lmp(pairs_script({1: STEEL + (0.0,)}, [(1, 1, 1.0)], R, RHO, 1e-8, 10).replace(
        "pair_style jgm unloading jcg", "pair_style jgm twisting marshall"), tmp_path, check=False)
    assert rc != 0 and "give 'tangential mindlin MU' too" in out


def test_pairs_with_rolling_and_twisting_conserve_momenta(tmp_path):
    m = fastrest.Material(*STEEL, rho=RHO)
    imp = fastrest.Impact.two_spheres(m, R, m, R)
    speeds = np.array([2.0, 10.0, 40.0]) * imp.V_c
    pairs = [(1, 1, float(V)) for V in speeds]
    dt = 2e-8
    spins = "\n".join(f"set atom {2 * k + 1} omega {3 * float(V) / R!r} {2 * float(V) / R!r} {float(V) / R!r}\n"
                      f"set atom {2 * k + 2} vy {0.3 * float(V)!r}" for k, V in enumerate(speeds))
    script = pairs_script({1: STEEL + (0.0,)}, pairs, R, RHO, dt, 3000).replace(
        "pair_style jgm unloading jcg",
        "pair_style jgm unloading jcg tangential mindlin 0.3 rolling sds 1e6 0 0.05 twisting sds 10 0 1e-3")
    script = script.replace("plugin load", spins + "\nplugin load").replace(
        "id x y z vx vy vz", "id x y z vx vy vz omegax omegay omegaz")
    lmp(script, tmp_path)
    d0 = tmp_path / "start"
    d0.mkdir()
    lmp(script.replace("run 3000", "run 0"), d0)
    end, start = read_dump(tmp_path / "final.dump"), read_dump(d0 / "final.dump")

    def momenta(d):
        x, v, w = d[:, 1:4], d[:, 4:7], d[:, 7:10]
        lin = M * (v[0::2] + v[1::2])
        ang = M * (np.cross(x[0::2], v[0::2]) + np.cross(x[1::2], v[1::2])) + INERTIA * (w[0::2] + w[1::2])
        return lin, ang
    (p1, l1), (p0, l0) = momenta(end), momenta(start)
    assert np.allclose(p1, p0, rtol=0, atol=1e-12 * M * speeds.max())
    assert np.allclose(l1, l0, rtol=0, atol=1e-9 * np.abs(l0).max()), (l1, l0)
    assert not np.allclose(end[0::2, 7:10], start[0::2, 7:10], rtol=1e-3)  # the contacts changed the spins
