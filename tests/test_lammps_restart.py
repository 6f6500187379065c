"""Restart files read by pair_style jgm as hostile bytes: every history row read back is checked
against its law, counts against the record, and the model a restart was written with against the
run that continues it; no damage gives a crash, an uncaught exception or a silent wrong force.

Damage that LAMMPS's own reader meets first (the header, the atoms' own fields) is LAMMPS's
error, named here as such."""
import os
import struct
import subprocess

import numpy as np
import pytest

import fastrest
from lammps_run import BIN, hertz_time, lmp, pairs_script, plugin, read_dump, run_limited

pytestmark = pytest.mark.lammps

STEEL = (200e9, 0.3, 1e9, 0.0)
R, RHO = 0.01, 7800.0
PAIR = "pair_style jgm unloading jcg tangential mindlin 0.3"
COEFF = f"pair_coeff 1 1 {STEEL[0]!r} {STEEL[1]!r} {STEEL[2]!r}"


@pytest.fixture(scope="module")
def restart(tmp_path_factory):
    """Two head-on pairs (10 and 40 V_c, with friction and a tangential speed) written mid-contact,
    and the time step; the uninterrupted run's final dump."""
    d = tmp_path_factory.mktemp("restart")
    m = fastrest.Material(*STEEL[:3], rho=RHO)
    imp = fastrest.Impact.two_spheres(m, R, m, R)
    c = imp.critical_values()
    speeds = [10 * imp.V_c, 40 * imp.V_c]
    dt = hertz_time(c["mass"], c["R_eff"], c["E_eff"], speeds[0]) / 200
    pairs = [(1, 1, float(V)) for V in speeds]
    script = pairs_script({1: STEEL}, pairs, R, RHO, dt, 0, run_lines=["run 120", "write_restart mid.restart"])
    script = script.replace("pair_style jgm unloading jcg", PAIR).replace("plugin load", "set atom 1 vz 0.01\nplugin load")
    lmp(script, d)
    return d / "mid.restart", dt


def _continue(path, dt, pair=PAIR, coeff=COEFF, steps=300):
    return (f"read_restart {path}\nplugin load @PLUGIN@\n{pair}\n{coeff}\nneighbor 0.0005 bin\n"
            "neigh_modify every 1 delay 0 check yes\ncomm_modify vel yes\nfix 1 all nve/sphere\n"
            f"timestep {dt!r}\nthermo 0\nrun {steps}\n"
            "write_dump all custom final.dump id x y z vx vy vz modify sort id format float %.17g\n")


#: Values of a contact's history row with friction, no rolling or twisting (PairJGM::NHIST_SLIDE).
NHIST = 15


def _rows(data):
    """Offsets of the history rows in a restart file's bytes: each atom's record of one contact,
    [2 + 1 + NHIST (its length), 0 (energy of ended contacts), partner ID, w_max*, ...]."""
    out = []
    size = 3.0 + NHIST
    for partner in (1.0, 2.0, 3.0, 4.0):
        at = data.find(struct.pack("<3d", size, 0.0, partner))
        while at >= 0:
            out.append(at)
            at = data.find(struct.pack("<3d", size, 0.0, partner), at + 1)
    assert len(out) == 4, out  # both atoms of both contacts
    return sorted(out)


def _run_damaged(tmp_path, data, dt, **kw):
    (tmp_path / "damaged.restart").write_bytes(bytes(data))
    return lmp(_continue(tmp_path / "damaged.restart", dt, **kw), tmp_path, check=False)


def test_the_restart_has_open_contacts_and_continues(tmp_path, restart):
    path, dt = restart
    data = path.read_bytes()
    for at in _rows(data):
        assert struct.unpack("<d", data[at + 24:at + 32])[0] > 1.0  # w_max* of a plastic contact
    lmp(_continue(path, dt), tmp_path)
    assert np.isfinite(read_dump(tmp_path / "final.dump")).all()


@pytest.mark.parametrize("w_max", [500.0, 1e300])
def test_a_row_past_the_laws_end_is_refused(tmp_path, restart, w_max):
    path, dt = restart
    data = bytearray(path.read_bytes())
    for at in _rows(bytes(data)):
        data[at + 24:at + 32] = struct.pack("<d", w_max)
    rc, out = _run_damaged(tmp_path, data, dt)
    assert rc != 0 and "is no history of their law: w_max* = " in out and "is not in (0, 425]" in out, out[-1500:]


def test_a_row_that_is_not_the_laws_is_refused(tmp_path, restart):
    path, dt = restart
    data = bytearray(path.read_bytes())
    at = _rows(bytes(data))[0]
    p = struct.unpack("<d", data[at + 32:at + 40])[0]
    data[at + 32:at + 40] = struct.pack("<d", 1.5 * p)  # P*(w_max) of another contact
    rc, out = _run_damaged(tmp_path, data, dt)
    assert rc != 0 and "P*(w_max) = " in out and "where the law gives" in out, out[-1500:]


@pytest.mark.parametrize("size", [1e6, 4.0 + NHIST, -1.0, 2.5])
def test_a_contact_count_past_the_record_is_refused(tmp_path, restart, size):
    path, dt = restart
    data = bytearray(path.read_bytes())
    at = _rows(bytes(data))[0]
    data[at:at + 8] = struct.pack("<d", size)
    rc, out = _run_damaged(tmp_path, data, dt)
    assert rc != 0 and "ERROR" in out, out[-1500:]
    assert "fix jgm/history: restart file holds a" in out or "Invalid" in out or "corrupted" in out, out[-1500:]


def test_a_changed_material_for_open_contacts_is_refused(tmp_path, restart):
    path, dt = restart
    rc, out = lmp(_continue(path, dt, coeff=COEFF.replace("1000000000.0", "900000000.0")), tmp_path, check=False)
    assert rc != 0 and "atom type 1 has open contacts in the restart file with material" in out, out[-1500:]
    assert "Sy 1000000000" in out and "Sy 900000000" in out
    rc, out = lmp(_continue(path, dt, pair=PAIR.replace("jcg", "brake")), tmp_path, check=False)
    assert rc != 0 and "open contacts follow unloading jcg, this run gives unloading brake" in out, out[-1500:]
    # another friction coefficient is a choice the model allows: the run goes on
    lmp(_continue(path, dt, pair=PAIR.replace("0.3", "0.5")), tmp_path)


def _fails_without_plugin(folder, name, script):
    """Whether LAMMPS, without the plugin, fails or hangs on ``script`` (written to ``name`` in
    ``folder``)."""
    (folder / name).write_text(script)
    try:
        run = run_limited([str(BIN / "lmp"), "-in", name, "-log", "none", "-nocite"], folder, 15)
    except subprocess.TimeoutExpired:
        return True
    return run.returncode != 0


def _reader_alone_fails(folder):
    """Whether LAMMPS's read_restart alone fails or hangs on damaged.restart."""
    return _fails_without_plugin(folder, "alone.lmp", "read_restart damaged.restart\n")


def _granular_run_fails(folder, dt):
    """Whether the continuation of damaged.restart with pair_style granular fails or hangs too."""
    script = _continue("damaged.restart", dt, steps=50).replace("plugin load @PLUGIN@\n", "")
    script = script.replace(PAIR, "pair_style granular").replace(
        COEFF, "pair_coeff * * hertz/material 2e11 0.5 0.3 tangential linear_nohistory 0 0 damping coeff_restitution")
    return _fails_without_plugin(folder, "granular.lmp", script)


def test_random_damage_never_crashes(tmp_path, restart):
    """Random bytes, truncations and planted doubles (1e300, -1, 500, 1e6, NaN, 0.5) anywhere in
    the file: each run ends with a LAMMPS error or runs to its end, within a time limit, never
    with a signal, an uncaught C++ exception or a NaN in the final state. (LAMMPS's own reader
    aborts on some damage with "C++ memory allocation failed", or hangs, before the plugin is
    loaded: that file then fails or hangs in ``read_restart`` alone too; on some damaged headers
    its comm set-up segfaults when the run starts: that file then crashes a run with pair_style
    granular, without the plugin, too.)"""
    path, dt = restart
    good = path.read_bytes()
    script = tmp_path / "in.lmp"
    script.write_text(_continue("damaged.restart", dt, steps=50).replace("@PLUGIN@", plugin()))
    rng = np.random.default_rng(20261201)
    seen = {"error": 0, "ran": 0, "lammps reader": 0, "lammps crash": 0}
    for k in range(36):
        data = bytearray(good)
        if k % 3 == 0:
            for _ in range(rng.integers(1, 9)):
                data[rng.integers(0, len(data))] = rng.integers(0, 256)
        elif k % 3 == 1:
            data = data[:rng.integers(0, len(data))]
        else:
            at = rng.integers(0, len(data) - 8)
            data[at:at + 8] = struct.pack("<d", rng.choice([1e300, -1.0, 500.0, 1e6, np.nan, 0.5]))
        (tmp_path / "damaged.restart").write_bytes(bytes(data))
        (tmp_path / "final.dump").unlink(missing_ok=True)
        try:
            run = run_limited([str(BIN / "lmp"), "-in", str(script), "-log", "none", "-nocite"], tmp_path, 30,
                              dict(os.environ, OMP_NUM_THREADS="1"))
        except subprocess.TimeoutExpired:
            assert _reader_alone_fails(tmp_path), k  # LAMMPS's reader hangs on its own
            seen["lammps reader"] += 1
            continue
        out = (run.stdout + run.stderr).decode(errors="replace")
        if run.returncode not in (0, 1):
            # a signal: LAMMPS's own (its comm set-up segfaults on some damaged headers) only if
            # the same file crashes pair_style granular's run without the plugin too
            assert _granular_run_fails(tmp_path, dt), (k, run.returncode, out[-1500:])
            seen["lammps crash"] += 1
            continue
        assert "terminate called" not in out and "Segmentation" not in out, (k, out[-1500:])
        if run.returncode == 1 and "ERROR" not in out:
            # LAMMPS's own reader aborts on some damage (a bad_alloc from a count in the atoms'
            # section) before the plugin is loaded: read_restart alone must fail the same way
            assert _reader_alone_fails(tmp_path), (k, out[-1500:])
            seen["lammps reader"] += 1
        elif run.returncode == 1:
            seen["error"] += 1
        else:
            final = read_dump(tmp_path / "final.dump")
            assert not np.isnan(final[:, 4:7]).any(), k
            seen["ran"] += 1
    assert seen["error"] >= 12 and seen["ran"] >= 3, seen


@pytest.mark.parametrize("before,after", [("", " rolling sds 1e6 0 0.05 twisting sds 10 0 1e-3"),
                                          (" rolling sds 1e6 0 0.05 twisting sds 10 0 1e-3", "")])
def test_rolling_switched_at_a_restart_keeps_the_open_contacts(tmp_path, before, after):
    """Head-on pairs (no spin: rolling and twisting exert nothing) written mid-contact with rolling
    and twisting off and read back with them on, or the reverse: the history rows change length
    (PairJGM::nhist) and keep their normal and sliding state, so the run ends as the uninterrupted
    one does. A contact whose history was lost would restart as a new, elastic one."""
    m = fastrest.Material(*STEEL[:3], rho=RHO)
    imp = fastrest.Impact.two_spheres(m, R, m, R)
    speeds = [10 * imp.V_c, 40 * imp.V_c]
    dt = hertz_time(imp.critical_values()["mass"], R / 2, imp.critical_values()["E_eff"], speeds[0]) / 200
    pairs = [(1, 1, float(V)) for V in speeds]
    steps, half = 400, 120

    def head(extra, **kw):
        return pairs_script({1: STEEL}, pairs, R, RHO, dt, steps, **kw).replace(
            "pair_style jgm unloading jcg", PAIR + extra)
    whole = tmp_path / "whole"
    whole.mkdir()
    lmp(head(after), whole)
    first = tmp_path / "first"
    first.mkdir()
    lmp(head(before, run_lines=[f"run {half}", "write_restart mid.restart"]), first)
    mid = read_dump(first / "final.dump")
    assert np.all(np.abs(mid[1::2, 1] - mid[0::2, 1]) < 2 * R)  # both pairs in contact there
    again = tmp_path / "again"
    again.mkdir()
    lmp(_continue(first / "mid.restart", dt, pair=PAIR + after, steps=steps - half), again)
    assert np.allclose(read_dump(again / "final.dump"), read_dump(whole / "final.dump"), rtol=1e-12, atol=0)
    # the same switch between two runs of one input
    once = tmp_path / "once"
    once.mkdir()
    lmp(head(before, run_lines=[f"run {half}", PAIR + after, COEFF, f"run {steps - half}"]), once)
    assert np.allclose(read_dump(once / "final.dump"), read_dump(whole / "final.dump"), rtol=1e-12, atol=0)
