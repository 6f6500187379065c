"""pair_style jgm's per-contact and per-atom output, contacts per atom, units, walls, hybrid.

compute pair/local (LAMMPS's own, through Pair::single) and compute jgm/atom against compute pair
jgm and the atoms' forces; a sphere with hundreds of contacts migrating and restarting; the small
items a LAMMPS user meets (units with no meaning, a small periodic box, the wall's friction, the
first thermo line's energy) and pair_style hybrid with granular.
"""
import numpy as np
import pytest

import fastrest
from lammps_run import gas_lines, hertz_time, lmp, pairs_script, read_dump, results, wall_script

pytestmark = pytest.mark.lammps

STEEL = (200e9, 0.3, 1e9, 0.0)
R, RHO = 0.01, 7800.0
FRICTION = "pair_style jgm unloading jcg tangential mindlin 0.3"


def _imp():
    m = fastrest.Material(*STEEL[:3], rho=RHO)
    return fastrest.Impact.two_spheres(m, R, m, R)


def _read_local(path):
    lines = path.read_text().splitlines()
    start = lines.index(next(t for t in lines if t.startswith("ITEM: ENTRIES"))) + 1
    return np.array([[float(v) for v in t.split()] for t in lines[start:] if t.strip()]).reshape(-1, 9)


@pytest.mark.parametrize("np_", [1, 2])
def test_pair_local_gives_each_open_contact(tmp_path, np_):
    """Oblique pairs stopped mid-contact (no contact has ended): compute pair/local's p1..p7 (normal
    force, |F_t|, w*, w_max*, dissipated so far, contact radius, elastic energy held) add up to
    compute pair jgm's totals; |F| of each atom is hypot(p1, p2); w* is the geometry's."""
    imp = _imp()
    speeds = np.array([3.0, 10.0, 30.0, 100.0]) * imp.V_c
    c = imp.critical_values()
    dt = hertz_time(c["mass"], c["R_eff"], c["E_eff"], speeds[-1]) / 400
    pairs = [(1, 1, float(V)) for V in speeds]
    tang = "\n".join(f"set atom {2 * k + 1} vy {0.2 * float(V)!r}" for k, V in enumerate(speeds))
    extra = ("compute pj all pair jgm\ncompute pl all pair/local dist p1 p2 p3 p4 p5 p6 p7 cutoff radius\n"
             "compute ja all jgm/atom\ncompute a1 all reduce sum c_ja[1]\ncompute a2 all reduce sum c_ja[2]\n"
             "compute a3 all reduce sum c_ja[3]\nthermo_style custom step c_pj[1] c_pj[2] c_a1 c_a2 c_a3\nthermo 10")
    lines = ["run 140", 'print "RESULT e $(c_pj[1]:%.17g) $(c_pj[2]:%.17g) $(c_a1:%.17g) $(c_a2:%.17g) $(c_a3)"',
             "write_dump all local contacts.dump index c_pl[1] c_pl[2] c_pl[3] c_pl[4] c_pl[5] c_pl[6] c_pl[7] c_pl[8] "
             "modify format float %.17g",
             "write_dump all custom forces.dump id x y z fx fy fz modify sort id format float %.17g"]
    script = pairs_script({1: STEEL}, pairs, R, RHO, dt, 0, extra=extra, run_lines=lines,
                          processors="2 1 1" if np_ == 2 else "* * *").replace("pair_style jgm unloading jcg", FRICTION)
    _, out = lmp(script.replace("plugin load", tang + "\nplugin load"), tmp_path, np_=np_)
    diss, held, a1, a2, a3 = results(out)["e"]
    loc = _read_local(tmp_path / "contacts.dump")
    on = loc[:, 4] != 0.0  # touching pairs (p3 = w* of an open contact)
    assert on.sum() == 4 and held > 0 and diss > 0
    dist, fn, ft, w, wm, d, a, el = loc[on, 1:].T
    assert np.isclose(d.sum(), diss, rtol=1e-12, atol=0) and np.isclose(el.sum(), held, rtol=1e-12, atol=0)
    assert np.isclose(a1, diss, rtol=1e-12) and np.isclose(a2, held, rtol=1e-12) and a3 == 8
    assert np.allclose(w, (2 * R - dist) / imp.omega_c * 1.0, rtol=1e-9) and np.all(wm >= w) and np.all(ft > 0)
    assert np.all((a > 0) & (a < R))
    f = read_dump(tmp_path / "forces.dump")
    assert np.allclose(np.sort(np.hypot(f[0::2, 4], np.hypot(f[0::2, 5], f[0::2, 6]))), np.sort(np.hypot(fn, ft)),
                       rtol=1e-9)


def test_per_atom_energies_add_up_in_a_gas(tmp_path):
    """300 spheres colliding in a periodic box on 2 ranks (contacts open and ended): compute jgm/atom's
    dissipated and held energies sum to compute pair jgm's, and its contact counts to twice the
    open contacts compute pair/local lists."""
    r = 1e-3
    c = _imp().critical_values()
    dt = hertz_time(0.5 * 4 / 3 * np.pi * r ** 3 * RHO, r / 2, c["E_eff"], 3.0) / 100
    script = "\n".join(gas_lines(300, 0.3, FRICTION, STEEL, RHO, dt, r) + [
        "compute pj all pair jgm", "compute ja all jgm/atom",
        "compute pl all pair/local p3 cutoff radius", "compute a1 all reduce sum c_ja[1]",
        "compute a2 all reduce sum c_ja[2]", "compute a3 all reduce sum c_ja[3]",
        "thermo_style custom step c_pj[1] c_pj[2] c_a1 c_a2 c_a3", "thermo 1000", "run 3000",
        'print "RESULT e $(c_pj[1]:%.17g) $(c_pj[2]:%.17g) $(c_a1:%.17g) $(c_a2:%.17g) $(c_a3)"',
        "write_dump all local open.dump index c_pl modify format float %.17g"]) + "\n"
    _, out = lmp(script, tmp_path, np_=2)
    diss, held, a1, a2, a3 = results(out)["e"]
    assert diss > 0 and np.isclose(a1, diss, rtol=1e-11) and np.isclose(a2, held, rtol=1e-11, atol=1e-300)
    text = (tmp_path / "open.dump").read_text().splitlines()
    w = np.array([float(t.split()[1]) for t in text[text.index(next(t for t in text if t.startswith("ITEM: ENTRIES"))) + 1:]])
    assert a3 == 2 * np.count_nonzero(w)


def _shell(n_target=320):
    """Centres of small spheres (r) on a big one (R_b = 10 r): on the sphere of radius R_b + r - delta
    (a slight overlap with the big one), at least 2.02 r apart (no overlap with each other)."""
    r, rb = 5e-4, 5e-3
    m = fastrest.Material(*STEEL[:3], rho=RHO)
    omega_c = fastrest.Impact.two_spheres(m, rb, m, r).omega_c
    rc = rb + r - 2.0 * omega_c  # w* = 2
    for n in range(n_target, 0, -5):
        k = np.arange(n) + 0.5
        z = 1 - 2 * k / n
        phi = np.pi * (1 + 5 ** 0.5) * k
        p = rc * np.stack([np.sqrt(1 - z * z) * np.cos(phi), np.sqrt(1 - z * z) * np.sin(phi), z], 1)
        d = np.sqrt(((p[:, None] - p[None]) ** 2).sum(-1)) + np.eye(n)
        if d.min() > 2.02 * r:
            return p, r, rb
    raise AssertionError("no shell")


def test_hundreds_of_contacts_on_one_atom_migrate_and_restart(tmp_path):
    """A sphere 10x the radius of ~300 touching it (size ratio 10): the contact lists grow as needed;
    the cluster drifts across the ranks' boundary while contacts are open (every step rebuilds the
    lists, every atom migrates with its histories) and a restart in the middle repeats the
    uninterrupted run."""
    p, r, rb = _shell()
    n = len(p)
    assert n > 250
    dt = 2e-8
    drift = 0.5 * rb / (200 * dt)  # crosses x = 0 within the run
    head = ["units si", "atom_style sphere", "atom_modify map array", "boundary p p p", "newton on",
            "processors 2 1 1", "region box block -0.02 0.02 -0.02 0.02 -0.02 0.02", "create_box 2 box",
            f"create_atoms 1 single {-0.3 * rb!r} 0 0"]
    head += [f"create_atoms 2 single {float(x) - 0.3 * rb!r} {float(y)!r} {float(z)!r}" for x, y, z in p]
    head += [f"set type 1 diameter {2 * rb!r}", f"set type 2 diameter {2 * r!r}", f"set atom * density {RHO!r}",
             f"velocity all set {drift!r} 0 0", "plugin load @PLUGIN@", FRICTION, "pair_coeff * * 200e9 0.3 1e9",
             f"neighbor {0.1 * r!r} bin", "neigh_modify every 1 delay 0 check no", "fix 1 all nve/sphere",
             f"timestep {dt!r}", "compute ja all jgm/atom", "compute most all reduce max c_ja[3]", "thermo 0"]
    dump = "write_dump all custom final.dump id x y z vx vy vz omegax omegay omegaz modify sort id format float %.17g"
    whole = tmp_path / "whole"
    whole.mkdir()
    lmp("\n".join(head + ["run 100", 'print "RESULT contacts $(c_most)"', "run 100", dump]) + "\n", whole, np_=2)
    first = tmp_path / "first"
    first.mkdir()
    _, out = lmp("\n".join(head + ["run 100", 'print "RESULT contacts $(c_most)"', "write_restart mid.restart"])
                 + "\n", first, np_=2)
    assert results(out)["contacts"][0] >= 250
    again = tmp_path / "again"
    again.mkdir()
    lmp("\n".join([f"read_restart {first / 'mid.restart'}", "plugin load @PLUGIN@", FRICTION,
                   "pair_coeff * * 200e9 0.3 1e9", f"neighbor {0.1 * r!r} bin", "neigh_modify every 1 delay 0 check no",
                   "fix 1 all nve/sphere", f"timestep {dt!r}", "thermo 0", "run 100", dump]) + "\n", again, np_=2)
    a, b = read_dump(whole / "final.dump"), read_dump(again / "final.dump")
    assert np.abs(a[0, 1]) < 0.02 and a[0, 1] > 0.0  # the big sphere crossed x = 0
    # to rounding: the restarted run reads the atoms back in another order, so that the hundreds of
    # forces on the big sphere are summed in another order (one contact per atom elsewhere in the
    # tests: bit for bit there)
    scale = np.abs(a).max(axis=0)
    assert np.all(np.abs(a - b) <= 1e-12 * scale), (np.abs(a - b) / scale).max(axis=0)


@pytest.mark.parametrize("units", ["lj", "real", "metal", "electron"])
def test_units_with_no_meaning_are_refused(tmp_path, units):
    script = pairs_script({1: STEEL}, [(1, 1, 1.0)], R, RHO, 1e-8, 10).replace("units si", f"units {units}")
    rc, out = lmp(script, tmp_path, check=False)
    assert rc != 0 and f"units {units} have no meaning" in out and "use units si, cgs, micro or nano" in out


def test_a_periodic_box_too_small_for_one_partner_is_refused(tmp_path):
    script = pairs_script({1: STEEL}, [(1, 1, 1.0)], R, RHO, 1e-8, 10).replace(
        f"region box block {-10 * R} {10 * R} {-10 * R} {10 * R}", f"region box block {-10 * R} {10 * R} {-R} {R}")
    rc, out = lmp(script, tmp_path, check=False)
    assert rc != 0 and "the periodic box is 0.02 long in y but two atoms touch up to 0.02" in out, out[-800:]


def test_the_wall_takes_the_pairs_friction_unless_told(tmp_path):
    """fix wall/jgm without 'tangential' follows pair_style jgm's (mindlin 0.3 here): a sphere
    sliding on it turns exactly as with 'tangential mindlin 0.3' given; 'tangential none' is frictionless."""
    imp = fastrest.Impact(fastrest.Material(*STEEL[:3], rho=RHO), R, flat=fastrest.Material(*STEEL[:3], rho=RHO))
    V = 10 * imp.V_c
    c = imp.critical_values()
    dt = hertz_time(c["mass"], c["R_eff"], c["E_eff"], V) / 500
    dumps = {}
    for name, tang in (("default", None), ("given", "mindlin 0.3"), ("none", "none")):
        d = tmp_path / name
        d.mkdir()
        script = wall_script({1: STEEL}, STEEL, [(1, V, 2 * V)], R, RHO, dt, 1200, tangential=tang)
        lmp(script.replace("pair_style jgm unloading jcg", FRICTION), d)
        dumps[name] = read_dump(d / "final.dump")
    assert np.abs(dumps["default"][:, 7:10]).max() > 0
    assert np.array_equal(dumps["default"], dumps["given"])
    assert np.abs(dumps["none"][:, 7:10]).max() == 0


def test_a_runs_first_thermo_line_adds_no_work(tmp_path):
    """Contacts open across two runs: the second run's first line (its set-up) reports the energy
    the first run ended with, not one more step's work."""
    imp = _imp()
    c = imp.critical_values()
    V = 20 * imp.V_c
    dt = hertz_time(c["mass"], c["R_eff"], c["E_eff"], V) / 300
    extra = "compute pj all pair jgm\nthermo_style custom step c_pj[1]\nthermo_modify format float %.17g\nthermo 50"
    script = pairs_script({1: STEEL}, [(1, 1, V)], R, RHO, dt, 0, extra=extra, run_lines=["run 150", "run 100"])
    _, out = lmp(script.replace("pair_style jgm unloading jcg", FRICTION), tmp_path)
    rows = [t.split() for t in out.splitlines() if len(t.split()) == 2 and t.split()[0] == "150"]
    assert len(rows) == 2 and float(rows[0][1]) > 0 and rows[0][1] == rows[1][1], rows


def test_hybrid_with_granular(tmp_path):
    """pair_style hybrid jgm granular: type 1 pairs by jgm (its own histories), type 2 and the mixed
    pairs by granular (its own): each pair rebounds as its style says."""
    imp = _imp()
    speeds = [10 * imp.V_c, 10 * imp.V_c, 10 * imp.V_c]
    c = imp.critical_values()
    dt = hertz_time(c["mass"], c["R_eff"], c["E_eff"], speeds[0]) / 1000
    pairs = [(1, 1, speeds[0]), (2, 2, speeds[1]), (1, 2, speeds[2])]
    steps = int(3 * hertz_time(c["mass"], c["R_eff"], c["E_eff"], speeds[0]) / dt) + 40
    script = pairs_script({1: STEEL, 2: STEEL}, pairs, R, RHO, dt, steps)
    gran = f"hertz/material {STEEL[0]!r} 0.6 {STEEL[1]!r} tangential linear_nohistory 0 0 damping coeff_restitution"
    script = script.replace("pair_style jgm unloading jcg", "pair_style hybrid jgm granular").replace(
        f"pair_coeff 1 1 {STEEL[0]!r} {STEEL[1]!r} {STEEL[2]!r}", f"pair_coeff 1 1 jgm {STEEL[0]!r} {STEEL[1]!r} {STEEL[2]!r}")
    script = script.replace(f"pair_coeff 2 2 {STEEL[0]!r} {STEEL[1]!r} {STEEL[2]!r}",
                            f"pair_coeff 2 2 granular {gran}\npair_coeff 1 2 granular {gran}")
    lmp(script, tmp_path)
    v = read_dump(tmp_path / "final.dump")[:, 4]
    e = np.array([(v[2 * k + 1] - v[2 * k]) / V for k, (_, _, V) in enumerate(pairs)])
    assert abs(e[0] - imp.e(speeds[0])) <= 1e-5 and np.allclose(e[1:], 0.6, atol=1e-3), e


def test_more_material_pairs_than_laws_is_refused(tmp_path):
    """91 types of 91 materials: 4186 distinct pairs, past the 4096 laws one run builds: an error
    that says so and what to do, before fastrest is asked."""
    n = 91
    coeffs = "\n".join(f"pair_coeff {t} {t} {200e9 + t * 1e9!r} 0.3 1e9" for t in range(1, n + 1))
    script = pairs_script({1: STEEL}, [(1, 1, 1.0)], R, RHO, 1e-8, 10).replace("create_box 1 box", f"create_box {n} box")
    script = script.replace(f"pair_coeff 1 1 {STEEL[0]!r} {STEEL[1]!r} {STEEL[2]!r}", coeffs)
    rc, out = lmp(script, tmp_path, check=False)
    assert rc != 0 and "4186 distinct material pairs need a contact law each" in out and "at most 4096" in out, out[-800:]
