"""Multi-material tables, old code against new code in the same run: ``python -m bench.multi_material_ab``.

The target allows no more than 10 % slowdown. ``fastrest.e_star(v, eps_y, nu)`` with every point its own
material is timed against the closed-form fit kernel (JGM eqs 42-44, per-point eps_y) in the same
subprocess, for two versions of fastrest, each in its own interpreter (``--old`` and ``--new``: the
python of a venv with that version installed). Subprocesses alternate old, new, old, new, ... so that
the machine's drift hits both alike. Each subprocess loads the same fixed-seed points, warms up, then
runs ``--inner`` rounds of (e_star with the default Numba threads, e_star on 1 thread, the fit) in a
shuffled order and reports medians; the report gives, per version, the median over subprocesses of
ns per point and of the ratio to the fit, and new/old of those ratios.

Point sets (V1* log-uniform, points shuffled, points either version's table refuses dropped):

* ``random``: every point its own material, eps_y uniform in [0.0005, 0.01], nu in [0.2, 0.45],
  V1* in [1, V1*_max(eps_y, nu)] (V1*_max: w_m* = 425);
* ``bench``: the points of ``bench.modes.multi_material`` (16 materials, 1e6 points).

Only public names present in both versions are used (``fastrest.e_star``, ``fastrest.jit.e_table``,
``fastrest.models.jgm_fit_jcg_scalar``, ``fastrest.models.jgm_fit_jcg_array``, called
``jgm_fit_jcg_kernel`` in older versions).
Writes bench/MULTI_MATERIAL_AB.md.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from .points import SEED, point_set
from .report import REPO, machine
from .timing import cpu_counters

__all__ = ["make_points", "run_worker", "main"]

OLD_DEFAULT = "/work/wt-old/.venv/bin/python"
NEW_DEFAULT = str(REPO / ".venv" / "bin" / "python")

# runs in the version's own interpreter, cwd outside any source tree (so it imports that version)
WORKER = r'''
import json, sys, time
import numpy as np, numba
import fastrest, fastrest.models as m
from fastrest import jit as frj
mode, path = sys.argv[1], sys.argv[2]
d = np.load(path)
fit = getattr(m, "jgm_fit_jcg_array", None) or m.jgm_fit_jcg_kernel
fit1 = m.jgm_fit_jcg_scalar

@numba.njit
def jit_loop(tab, v, e, nu, out):
    for i in range(v.size):
        out[i] = frj.e_table(tab, v[i], e[i], nu[i], frj.JCG)

@numba.njit
def jit_chain(tab, v, e, nu):
    x = 0.0
    for i in range(v.size):
        x = frj.e_table(tab, v[i] - 1e-9 * x, e[i], nu[i], frj.JCG)
    return x

@numba.njit
def fit_chain(v, e):
    x = 0.0
    for i in range(v.size):
        x = fit1(v[i] - 1e-9 * x, e[i])
    return x

tab = fastrest.load_table().data
if mode == "mask":
    for s in ("random", "bench"):
        v, e, nu = d[s + "_v"], d[s + "_e"], d[s + "_nu"]
        o = np.empty(v.size)
        jit_loop(tab, v, e, nu, o)
        np.save(path[:-4] + "_" + s + "_keep.npy", np.isfinite(o))
    print(json.dumps({"file": fastrest.__file__}))
    sys.exit()
inner = int(sys.argv[3])
nmax = numba.config.NUMBA_NUM_THREADS
out = {"file": fastrest.__file__, "threads": nmax}

def run(cases, n, refs):
    for f in cases.values():  # warm-up (and compilation)
        f(); f()
    t = {k: [] for k in cases}
    order = np.random.default_rng(7)
    for r in range(inner):
        for k in order.permutation(list(cases)):
            t0 = time.perf_counter()
            cases[k]()
            t[k].append((time.perf_counter() - t0) / n)
    res = {k: float(np.median(x)) * 1e9 for k, x in t.items()}
    for k, ref in refs.items():
        res[k + "_ratio"] = float(np.median(np.array(t[k]) / np.array(t[ref])))
    return res

for s in ("random", "bench"):
    keep = d[s + "_keep"]
    v, e, nu = (np.ascontiguousarray(d[s + k][keep]) for k in ("_v", "_e", "_nu"))
    o = np.empty(v.size)
    def one():
        numba.set_num_threads(1)
        try:
            return fastrest.e_star(v, e, nu)
        finally:
            numba.set_num_threads(nmax)
    cases = {"e_star": lambda: fastrest.e_star(v, e, nu), "e_star_1thread": one, "fit": lambda: fit(v, e, o),
             "jit_loop": lambda: jit_loop(tab, v, e, nu, o), "jit_chain": lambda: jit_chain(tab, v, e, nu),
             "fit_chain": lambda: fit_chain(v, e)}
    res = run(cases, v.size, {"e_star": "fit", "e_star_1thread": "fit", "jit_loop": "fit", "jit_chain": "fit_chain"})
    if not np.isfinite(jit_chain(tab, v, e, nu)):
        raise RuntimeError("the latency chain left the table's domain")
    res["n"] = int(v.size)
    res["checksum"] = float(np.sum(fastrest.e_star(v, e, nu)))
    out[s] = res
# scalar calls from Python: ns per call
K = 20000
cases = {"scalar": lambda: [fastrest.e_star(5.0, 0.005, 0.33) for _ in range(K)],
         "fit_scalar": lambda: [fit1(5.0, 0.005) for _ in range(K)]}
out["scalar"] = run(cases, K, {"scalar": "fit_scalar"})
print(json.dumps(out))
'''

#: (key, label, reference label) of the cases in the report, per point set.
CASES = [("e_star", "fastrest.e_star, {threads} threads", "fit kernel"),
         ("e_star_1thread", "fastrest.e_star, 1 thread", "fit kernel"),
         ("jit_loop", "jit.e_table in an @njit loop (throughput)", "fit kernel"),
         ("jit_chain", "jit.e_table, dependent chain (latency)", "fit chain")]


def make_points(n, seed=SEED):
    """The two point sets as a dict of arrays (see the module docstring)."""
    import fastrest
    rng = np.random.default_rng(seed + 40)
    e = rng.uniform(0.0005, 0.01, n)
    nu = rng.uniform(0.2, 0.45, n)
    # V1*_max on a coarse material grid, bilinear: only sets the speed range (refused points are dropped)
    ge, gn = np.linspace(0.0005, 0.01, 20), np.linspace(0.2, 0.45, 11)
    lim = np.array([[fastrest.limit(a, b).v1_star for b in gn] for a in ge])
    ie = np.clip(np.searchsorted(ge, e) - 1, 0, ge.size - 2)
    jn = np.clip(np.searchsorted(gn, nu) - 1, 0, gn.size - 2)
    te, tn = (e - ge[ie]) / (ge[1] - ge[0]), (nu - gn[jn]) / (gn[1] - gn[0])
    vmax = ((1 - te) * (1 - tn) * lim[ie, jn] + te * (1 - tn) * lim[ie + 1, jn]
            + (1 - te) * tn * lim[ie, jn + 1] + te * tn * lim[ie + 1, jn + 1])
    v = np.exp(rng.uniform(0.0, 1.0, n) * np.log(vmax))
    ps = point_set(16, n // 16, seed=SEED + 3)  # bench.modes.multi_material's points
    bv, be, bn = ps.shuffled(SEED + 4)
    return {"random_v": v, "random_e": e, "random_nu": nu, "bench_v": bv, "bench_e": be, "bench_nu": bn}


def run_worker(python, args, cwd):
    r = subprocess.run([python, "-c", WORKER, *args], cwd=cwd, capture_output=True, text=True, timeout=900)
    if r.returncode != 0:
        raise RuntimeError(f"{python} failed:\n{r.stderr[-3000:]}")
    return json.loads(r.stdout.strip().splitlines()[-1])


def _commit(file):
    root = Path(file).resolve().parent.parent
    rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=root, capture_output=True, text=True).stdout
    dirty = subprocess.run(["git", "status", "--porcelain", "--", "fastrest"], cwd=root, capture_output=True,
                           text=True).stdout.strip()
    return f"{rev.strip()}{' + uncommitted changes' if dirty else ''} ({root})"


def _write(path, rows, meta):
    def med(ver, s, k):
        return float(np.median([r[s][k] for r in rows[ver]]))

    lines = ["# Multi-material tables: old code against new code, same run", "",
             "`python -m bench.multi_material_ab` (" + meta["args"] + "): every point its own material; each "
             "case timed against a closed-form fit of JGM eqs (42)-(44) with per-point eps_y in the same "
             "subprocess (the fit kernel `jgm_fit_jcg_array`, or a dependent chain of `jgm_fit_jcg_scalar` "
             "for the latency case); old and new versions in alternating subprocesses; medians over "
             f"{meta['rounds']} subprocesses per version ({meta['inner']} rounds each). The last column is "
             "the slowdown criterion (<= 1.10).", "",
             f"* old: {meta['old_commit']}", f"* new: {meta['new_commit']}",
             f"* machine: {meta['cpu']}, {meta['nproc']} CPUs, Numba threads {meta['threads']}",
             f"* load average before / after: {meta['load0']} / {meta['load1']}; other processes kept "
             f"{meta['other_cores']:.2f} cores busy on average (2-thread figures need an idle second core)", ""]
    summary = {}
    for s, title in (("random", "every point its own random material"),
                     ("bench", "bench.modes.multi_material's points (16 materials, shuffled)")):
        n = rows["new"][0][s]["n"]
        lines += [f"## {title} (n = {n})", "",
                  "| case | old ns/point | new ns/point | old / ref | new / ref | new/old of ratios |",
                  "|---|---|---|---|---|---|"]
        for k, label, _ in CASES:
            ro, rn = med("old", s, k + "_ratio"), med("new", s, k + "_ratio")
            summary[s, k] = (ro, rn)
            lines.append(f"| {label.format(threads=meta['threads'])} | {med('old', s, k):.1f} | "
                         f"{med('new', s, k):.1f} | {ro:.2f} | {rn:.2f} | **{rn / ro:.3f}** |")
        for k, label in (("fit", "fit kernel (reference)"), ("fit_chain", "fit chain (reference)")):
            lines.append(f"| {label} | {med('old', s, k):.1f} | {med('new', s, k):.1f} | | | |")
        lines.append("")
    ro, rn = med("old", "scalar", "scalar_ratio"), med("new", "scalar", "scalar_ratio")
    summary["scalar", "scalar"] = (ro, rn)
    lines += ["## scalar call from Python", "",
              "| case | old ns/call | new ns/call | old / ref | new / ref | new/old of ratios |",
              "|---|---|---|---|---|---|",
              f"| fastrest.e_star(5.0, 0.005, 0.33) | {med('old', 'scalar', 'scalar'):.0f} | "
              f"{med('new', 'scalar', 'scalar'):.0f} | {ro:.2f} | {rn:.2f} | **{rn / ro:.3f}** |",
              f"| jgm_fit_jcg_scalar(5.0, 0.005) (reference) | {med('old', 'scalar', 'fit_scalar'):.0f} | "
              f"{med('new', 'scalar', 'fit_scalar'):.0f} | | | |", "",
              "Per subprocess, random set, fastrest.e_star / fit kernel (default threads / 1 thread):", ""]
    for ver in ("old", "new"):
        lines.append(f"* {ver}: " + ", ".join(f"{r['random']['e_star_ratio']:.2f}/"
                                               f"{r['random']['e_star_1thread_ratio']:.2f}" for r in rows[ver]))
    lines.append("")
    Path(path).write_text("\n".join(lines))
    return summary


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--old", default=OLD_DEFAULT, help="python of the old version's venv")
    ap.add_argument("--new", default=NEW_DEFAULT, help="python of the new version's venv")
    ap.add_argument("--n", type=int, default=10**6, help="points per set")
    ap.add_argument("--rounds", type=int, default=5, help="subprocesses per version (alternating)")
    ap.add_argument("--inner", type=int, default=7, help="timing rounds inside each subprocess")
    ap.add_argument("--out", default=str(REPO / "bench" / "MULTI_MATERIAL_AB.md"))
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "points.npz")
        pts = make_points(a.n)
        np.savez(path, **pts)
        keep = {s: np.ones(a.n if s == "random" else pts["bench_v"].size, bool) for s in ("random", "bench")}
        files = {}
        for ver, py in (("old", a.old), ("new", a.new)):
            files[ver] = run_worker(py, ["mask", path], tmp)["file"]
            for s in keep:
                keep[s] &= np.load(path[:-4] + f"_{s}_keep.npy")
        print(f"old: {files['old']}\nnew: {files['new']}\nkept: " +
              ", ".join(f"{s} {k.sum()}/{k.size}" for s, k in keep.items()), flush=True)
        np.savez(path, **pts, random_keep=keep["random"], bench_keep=keep["bench"])
        rows = {"old": [], "new": []}
        load0 = " ".join(f"{x:.2f}" for x in os.getloadavg())
        c0, t0 = cpu_counters(), time.perf_counter()
        for r in range(a.rounds):
            for ver in (("old", "new") if r % 2 == 0 else ("new", "old")):
                res = run_worker(getattr(a, ver), ["time", path, str(a.inner)], tmp)
                rows[ver].append(res)
                print(f"round {r} {ver}: " + "  ".join(
                    f"{s}: " + ", ".join(f"{k} {res[s][k]:.1f} ns ({res[s][k + '_ratio']:.2f}x)" for k, _, _ in CASES)
                    + f", fit {res[s]['fit']:.1f}" for s in ("random", "bench"))
                    + f"  scalar {res['scalar']['scalar']:.0f} ns ({res['scalar']['scalar_ratio']:.2f}x)", flush=True)
        c1, wall = cpu_counters(), time.perf_counter() - t0
        other = ((c1[0] - c0[0]) - (c1[1] - c0[1])) / wall if c0 and c1 else float("nan")
    for s in ("random", "bench"):
        cs = {ver: rows[ver][0][s]["checksum"] for ver in rows}
        if abs(cs["old"] - cs["new"]) > 1e-6 * abs(cs["old"]):
            raise RuntimeError(f"old and new e_star disagree on the {s} points: {cs}")
    mach = machine()
    meta = {"args": " ".join(argv if argv is not None else sys.argv[1:]) or "defaults", "rounds": a.rounds,
            "inner": a.inner, "old_commit": _commit(files["old"]), "new_commit": _commit(files["new"]),
            "cpu": mach.get("cpu"), "nproc": mach.get("nproc"), "threads": rows["new"][0]["threads"],
            "load0": load0, "load1": " ".join(f"{x:.2f}" for x in os.getloadavg()), "other_cores": other}
    summary = _write(a.out, rows, meta)
    for (s, k), (ro, rn) in summary.items():
        print(f"{s:6s} {k:15s} old {ro:.2f}x  new {rn:.2f}x  new/old {rn / ro:.3f}")
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
