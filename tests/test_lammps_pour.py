"""fix pour and fix deposit with pair_style jgm, against pair_style granular in the same test.

The pair's neighbour cutoff must cover every radius that will be inserted (the fixes' answers to
``extract("radius")``): otherwise an empty box gets a cutoff of its own choosing (ghost-atom
blow-up) and large spheres poured onto small ones are found only deep inside them.
"""
import numpy as np
import pytest

from lammps_run import POUR_MATERIAL, deepest_overlap, lmp, plugin, pour_script, results, run_stats

pytestmark = pytest.mark.lammps


def _pour(tmp_path, style, units="si", bed=False):
    d = tmp_path / f"{style}_{units}_{int(bed)}"
    d.mkdir()
    _, out = lmp(pour_script(style, units, bed), d)
    res = results(out)
    ghosts, mem, cut = run_stats(out)
    box = 0.02 * (1e6 if units == "micro" else 1.0)
    return {"n": int(res["n"][0]), "z": res["z"][0], "ghosts": ghosts, "mem": mem, "cut": cut,
            "overlap": deepest_overlap(d / "final.dump", box), "out": out}


def test_pour_into_an_empty_box_as_granular(tmp_path):
    jgm, gran = _pour(tmp_path, "jgm"), _pour(tmp_path, "granular")
    assert jgm["n"] == gran["n"] == 300
    assert jgm["cut"] == pytest.approx(0.0022, rel=1e-12)  # 2 mm + 0.2 mm skin, as granular's
    assert jgm["ghosts"] <= 2 * gran["ghosts"] and jgm["mem"] <= 2 * gran["mem"], (jgm, gran)
    assert abs(jgm["z"] - gran["z"]) <= 0.05 * gran["z"], (jgm["z"], gran["z"])
    assert jgm["overlap"] < 0.05  # settled: no sphere inside another


def test_pour_in_micro_units_settles_as_in_si(tmp_path):
    micro, si = _pour(tmp_path, "jgm", "micro"), _pour(tmp_path, "jgm", "si")
    assert micro["n"] == si["n"] == 300
    assert micro["cut"] == pytest.approx(2200.0, rel=1e-12)  # micrometres
    assert abs(micro["z"] - si["z"]) <= 0.05 * si["z"], (micro["z"], si["z"])
    assert micro["overlap"] < 0.05
    assert "WARNING: fastrest" not in micro["out"]  # the material was read in Pa: in range


def test_pour_of_large_spheres_onto_a_bed_of_small_ones_as_granular(tmp_path):
    """1 mm spheres poured first, then 1.5-2 mm ones onto them: the second run's cutoff covers the
    large spheres the pour will insert (1 mm + 1 mm + skin), not only the small ones present."""
    jgm, gran = _pour(tmp_path, "jgm", bed=True), _pour(tmp_path, "granular", bed=True)
    assert jgm["n"] == gran["n"] == 400
    assert jgm["ghosts"] <= 2 * gran["ghosts"] and jgm["mem"] <= 2 * gran["mem"], (jgm, gran)
    assert abs(jgm["z"] - gran["z"]) <= 0.05 * gran["z"], (jgm["z"], gran["z"])
    assert jgm["overlap"] < 0.05  # a contact found only when the spheres overlap deeply fails here


def test_deposit_of_molecule_spheres(tmp_path):
    """fix deposit with a one-sphere molecule template (its Diameters section): the cutoff is that
    diameter plus the skin before any atom exists, and every deposited sphere lands."""
    (tmp_path / "sphere.mol").write_text("# one sphere\n\n1 atoms\n\nCoords\n\n1 0 0 0\n\nTypes\n\n1 1\n\n"
                                         "Diameters\n\n1 0.002\n\nMasses\n\n1 1.0471975511965976e-05\n")
    E, nu, Sy = POUR_MATERIAL
    script = "\n".join([
        "units si", "atom_style sphere", "boundary p p fm", "comm_modify vel yes",
        "region box block 0 0.02 0 0.02 0 0.03 units box", "create_box 1 box", "neighbor 0.0002 bin",
        "neigh_modify delay 0", "plugin load @PLUGIN@", "pair_style jgm tangential mindlin 0.3",
        f"pair_coeff * * {E!r} {nu!r} {Sy!r}", f"fix wall all wall/jgm zplane 0.0 NULL {E!r} {nu!r} {Sy!r}",
        "timestep 4e-6", "fix 1 all nve/sphere", "fix 2 all gravity 9.81 vector 0 0 -1",
        "region slab block 0 0.02 0 0.02 0.012 0.028 units box", "molecule sph sphere.mol",
        "fix ins all deposit 40 0 250 4767 region slab near 0.0021 mol sph vz -0.3 -0.3 units box",
        "run 25000", 'print "RESULT n $(count(all))"',
        "write_dump all custom final.dump id type radius x y z modify sort id format float %.17g"]) + "\n"
    _, out = lmp(script, tmp_path)
    assert results(out)["n"][0] == 40
    assert run_stats(out)[2] == pytest.approx(0.0022, rel=1e-12)
    assert deepest_overlap(tmp_path / "final.dump", 0.02) < 0.05


def test_an_atom_larger_than_its_cutoff_stops_the_run(tmp_path):
    """A radius grown after the run's set-up (here by fix adapt) would miss contacts: an error
    names the atom and the radius the cutoff was set for."""
    script = "\n".join([
        "units si", "atom_style sphere 1", "boundary p p f", "region box block 0 0.1 0 0.1 0 0.1",
        "create_box 1 box", "create_atoms 1 single 0.05 0.05 0.05", "create_atoms 1 single 0.053 0.05 0.05",
        "set atom * diameter 0.002", "set atom * density 2500", "plugin load @PLUGIN@", "pair_style jgm",
        f"pair_coeff * * {POUR_MATERIAL[0]!r} {POUR_MATERIAL[1]!r} {POUR_MATERIAL[2]!r}", "neighbor 0.0002 bin",
        "variable d equal 0.002+elapsed*1e-5", "fix grow all adapt 1 atom diameter v_d", "fix 1 all nve/sphere",
        "timestep 1e-6", "run 200"]) + "\n"
    rc, out = lmp(script, tmp_path, check=False)
    assert rc != 0 and "pair jgm: atom 1 (type 1) has radius" in out and "larger than the 0.001" in out, out[-1500:]
