"""The time-domain contact law: cost per force call against Hertz, and the time-step rule.

``python -m bench.force_law [--quick]`` writes bench/FORCE_LAW.md:

1. ns per call of :func:`fastrest.jit.contact_force` in a user's ``@njit`` loop over contacts and
   time steps (paths of real impacts: Hertz, JG loading, unloading and gaps), against a plain
   Hertz force ``w^1.5`` evaluated in the same loop and run (interleaved rounds; the ratio is the
   median of per-round ratios), and the exact JG law (:func:`fastrest.loading.jackson_green.p_star_kernel`);
   also with strain hardening (Ghaednia et al.'s law, Et/E = 0.01, Brake unloading: its loading
   reads the same cell rows as JG's, so it should cost the same);
2. the time of one time-stepped impact (:meth:`fastrest.ContactLaw.impact`) at the step count
   docs/model.md quotes;
3. the convergence table behind the time-step rule: worst relative error of e from velocity
   Verlet against the energy balance (:func:`fastrest.curve`) for three unloading models, four
   materials and V1* from 1.01 to the w_m* = 425 speed, by steps per Hertz contact duration (from
   the 20-50 of DEM codes to 64000), with and without locating the crossing of w* = 1.9.

``python -m bench.force_law --convergence-only [--steps N ...]`` runs only part 3 and prints its
rows (Markdown, as in docs/model.md section 10) without writing the file; ``--cost-only`` only
part 1, printed.
"""
import argparse
import datetime
import math
import os
import sys
import warnings
from pathlib import Path

import numba
import numpy as np

import fastrest
from fastrest import direct
from fastrest.energy import V_SWITCH
from fastrest import jit as frj
from fastrest.loading.jackson_green import p_star_kernel

from . import report
from .timing import fmt_err, fmt_time, interleaved

HERE = Path(__file__).resolve().parent
NAMES = ("jcg", "etsion", "brake")
MATERIALS = [(0.0005, 0.2), (0.005, 0.33), (0.01, 0.45), (0.002, 0.45)]
STEPS = [20, 50, 100, 200, 500, 1000, 2000, 4000, 8000, 16000, 32000, 64000]
#: The observed order is fitted from here on (coarser steps are not yet in the asymptotic range).
ORDER_FROM = 500
#: The step count docs/model.md and tests/test_force_law.py quote for 1e-8.
STEPS_1E8 = 40000


@numba.njit
def _loop_law(law, states, w, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(w.shape[0]):
            st = states[k]
            for j in range(4):
                st[j] = 0.0
            for i in range(w.shape[1]):
                s += frj.contact_force(law, st, w[k, i])
    return s


@numba.njit
def _loop_hertz(w, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(w.shape[0]):
            for i in range(w.shape[1]):
                x = w[k, i]
                s += x * math.sqrt(x) if x > 0.0 else 0.0
    return s


@numba.njit
def _loop_exact(w, eps_y, nu, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(w.shape[0]):
            for i in range(w.shape[1]):
                x = w[k, i]
                s += p_star_kernel(x, eps_y, nu) if x > 0.0 else 0.0
    return s


def impact_paths(n_contacts, n_steps, seed=0):
    """Interference histories of real impacts (V1* log-uniform in [1.01, 100], JCG), each sampled
    at n_steps points from first touch to past separation: what a DEM force loop sees."""
    rng = np.random.default_rng(seed)
    law = fastrest.contact_law(0.005, 0.33, "jcg")
    out = np.empty((n_contacts, n_steps))
    for k in range(n_contacts):
        v = math.exp(rng.uniform(math.log(1.01), math.log(100.0)))
        tau = frj.hertz_contact_time(v) * 1.3  # the plastic contact lasts a little longer
        dt = tau / n_steps
        w, vel, a = 0.0, v, 0.0
        state = np.zeros(frj.STATE_SIZE)
        for i in range(n_steps):
            w += vel * dt + 0.5 * a * dt * dt
            a_new = -1.25 * frj.contact_force(law.data, state, w)
            vel += 0.5 * (a + a_new) * dt
            a = a_new
            out[k, i] = w
    return out


def cost(cfg, log):
    w = impact_paths(cfg["contacts"], cfg["path_steps"])
    n = w.size
    laws = {m: fastrest.contact_law(0.005, 0.33, m) for m in NAMES}
    states = np.zeros((w.shape[0], frj.STATE_SIZE))
    cases = {"hertz": (lambda: _loop_hertz(w, 1), n)}
    for m in NAMES:
        cases[f"contact_force ({m})"] = (lambda m=m: _loop_law(laws[m].data, states, w, 1), n)
    hard = fastrest.contact_law(0.005, 0.33, "brake", et_ratio=0.01)  # Ghaednia et al. (2019)
    cases["contact_force (brake, Et/E = 0.01)"] = (lambda: _loop_law(hard.data, states, w, 1), n)
    cases["exact JG law, no history"] = (lambda: _loop_exact(w, 0.005, 0.33, 1), n)
    t = interleaved(cases, cfg["rounds"], ref="hertz")
    frac = {"gap (w <= 0)": float(np.mean(w <= 0)), "Hertz (0 < w <= 1.9)": float(np.mean((w > 0) & (w <= 1.9))),
            "beyond 1.9": float(np.mean(w > 1.9))}
    law = laws["jcg"]
    imp = {f"V1* = {v:g}": interleaved({"impact": (lambda v=v: law.impact(v, steps_per_contact=STEPS_1E8), 1)}, cfg["rounds"])["impact"]
           for v in (1.5, 30.0)} if cfg.get("impacts", True) else {}
    log(f"  contact_force / hertz: {t['contact_force (jcg)'].ratio:.2f}")
    return t, frac, imp


#: Speeds of the time-step table besides the log-uniform and switch-region grids: a coarse sample and
#: a known worst point (Brake, eps_y = 0.0005, nu = 0.2, N = 1000, plain).
FIXED_SPEEDS = (1.01, 1.5, 2.2, 2.3, 5.0, 40.0, 3.207520047637879)


def speeds(top, n_log, n_switch, n_top=0):
    """V1* of the time-step table for one material: ``n_log`` log-uniform in [1.01, top), ``n_top``
    uniform in [top / 2, top) (where the error of the located scheme peaks, oscillating with V1*), ``n_switch``
    uniform over the region just past the switch (1.9^1.25 ... 3.5, where the JG force's jump at
    w* = 1.9 is crossed on loading), 1 - 10^-k (k = 1 ... 12) times the switch speed and just above
    it, the fixed speeds, and ``top`` (the w_m* = 425 speed x (1 - 1e-6)) last."""
    vs = V_SWITCH
    grid = np.concatenate([np.exp(np.linspace(math.log(1.01), math.log(top), n_log, endpoint=False)),
                           np.linspace(top / 2, top, n_top, endpoint=False)])
    sw = np.linspace(vs * (1 + 1e-9), 3.5, n_switch)
    below = vs * (1 - 10.0 ** -np.arange(1.0, 13.0))  # how far below the switch the band reaches
    v = np.concatenate([grid, sw, FIXED_SPEEDS, below, [vs * (1 + 1e-12)]])
    return [float(x) for x in np.unique(v[v < top])] + [top]


def convergence(cfg, log):
    """Worst |e / e_curve - 1| per step count, located and plain: a dense pass over the speeds, then
    around the worst speed of every (step count, located) a finer pass (``refine`` speeds over the
    neighbouring grid interval either side, then twice more over the finer interval either side of
    the new worst) from the ``starts`` worst of the dense pass, since the error jumps with where the
    steps fall."""
    steps = cfg["steps"]
    worst = {True: np.zeros(len(steps)), False: np.zeros(len(steps))}
    below = {True: np.zeros(len(steps)), False: np.zeros(len(steps))}
    at = {True: [None] * len(steps), False: [None] * len(steps)}
    seen = {k: [[] for _ in steps] for k in (True, False)}  # (error, case, V1*) of the dense pass
    band = {k: {"width": np.zeros(len(steps)), "error": np.zeros(len(steps))} for k in (True, False)}
    n_speeds = 0
    cases = {}
    for m in NAMES:
        for eps, nu in MATERIALS:
            law, c = fastrest.contact_law(eps, nu, m), fastrest.curve(eps, nu, m)
            top = fastrest.limit(eps, nu).v1_star * (1 - 1e-6)
            cases[(m, eps, nu)] = (law, c, top)

    def measure(key, locate, j, v):
        law, c, top = cases[key]
        n = steps[j]
        try:
            r = law.impact(v, steps_per_contact=n, locate_switch=locate)
            err = abs(r["e"] / c.e(v) - 1)
        except ValueError:  # a coarse step overshoots w_m* = 425 at the limit speed
            r, err = None, math.inf
        if r is not None and v < V_SWITCH and r["omega_m_star"] > 1.9:
            # just below the switch speed the stepped peak passes w* = 1.9 where the exact one does
            # not: e is off by the model's jump there (the band is reported, not the table)
            b = band[locate]
            b["width"][j] = max(b["width"][j], 1.0 - v / V_SWITCH)
            b["error"][j] = max(b["error"][j], err)
            return 0.0
        if err > worst[locate][j]:
            worst[locate][j], at[locate][j] = err, [key[0], key[1], key[2], v]
        if v != top and err > below[locate][j]:
            below[locate][j] = err
        return err

    for key, (law, c, top) in cases.items():
        vs = speeds(top, cfg["n_log"], cfg["n_switch"], cfg.get("n_top", 0))
        n_speeds = max(n_speeds, len(vs))
        for v in vs:
            for locate in (True, False):
                for j in range(len(steps)):
                    seen[locate][j].append((measure(key, locate, j, v), key, v))
    for locate in (True, False):
        for j in range(len(steps)):
            for err0, (m, eps, nu), v in sorted(seen[locate][j], reverse=True)[:cfg["starts"]]:
                top = cases[(m, eps, nu)][2]
                vs = np.array(speeds(top, cfg["n_log"], cfg["n_switch"], cfg.get("n_top", 0)))
                i = int(np.searchsorted(vs, v))
                lo, hi = vs[max(i - 1, 0)], vs[min(i + 1, len(vs) - 1)]
                for _ in range(3):  # each round: the interval either side of the best, finer
                    xs = [float(x) for x in np.linspace(lo, hi, cfg["refine"]) if x < top]
                    errs = [measure((m, eps, nu), locate, j, x) for x in xs]
                    k = int(np.argmax(errs))
                    h = (hi - lo) / (cfg["refine"] - 1)
                    lo, hi = max(xs[k] - h, 1.01), min(xs[k] + h, top)
        log(f"  locate={locate}: " + " ".join(f"{x:.1e}" for x in worst[locate]))
    rows = dict(worst)
    rows["below"] = below
    rows["at"] = at
    rows["n_speeds"] = n_speeds
    rows["band"] = band
    return rows


def section3(conv, cfg):
    """Part 3 of FORCE_LAW.md as lines (from its heading on)."""
    L = ["## 3. Steps per contact against the error in e", "",
         "Worst |e_Verlet / e_energy balance - 1| over 3 unloading models (JCG, Etsion, Brake), "
         f"materials (eps_y, nu) = {MATERIALS}, and per material {conv['n_speeds']} speeds: "
         f"{cfg['n_log']} log-uniform from 1.01 to the w_m* = 425 speed, {cfg.get('n_top', 0)} uniform over its "
         f"upper half (where the located scheme's error peaks, oscillating with V1*), {cfg['n_switch']} uniform over "
         "1.9^1.25 ... 3.5 (the crossing of w* = 1.9 on loading), both sides of the switch, "
         f"V1* = {', '.join(f'{v:g}' for v in FIXED_SPEEDS)} and the w_m* = 425 speed (x (1 - 1e-6)); "
         f"then, from the {cfg['starts']} worst speeds of every row and column, {cfg['refine']} more over "
         "the grid interval either side, three times, each time over the finer interval around the "
         "new worst. "
         "N = steps per Hertz contact duration tau_c(V1*) = 2.943 V1*^-0.2 "
         "(normalised time; in seconds 2.868 (m'^2/(R' E'^2 V1))^(1/5)).", "",
         "| N | w* = 1.9 crossing located | not located | worst located at (model, eps_y, nu, V1*) | "
         "worst not located at |", "|---|---|---|---|---|"]

    def cell(locate, j):
        x = conv[locate][j]
        if math.isinf(x):
            return f"{conv['below'][locate][j]:.2e} (the 425 speed refused: overshoot)"
        return f"{x:.2e}"

    def where(locate, j):
        m, eps, nu, v = conv["at"][locate][j]
        return f"{m}, {eps:g}, {nu:g}, {v!r}"

    for j, n in enumerate(cfg["steps"]):
        L.append(f"| {n} | {cell(True, j)} | {cell(False, j)} | {where(True, j)} | {where(False, j)} |")
    L += ["", "Excluded above (every other speed is in): speeds just below the switch speed 1.9^1.25 whose "
          "time-stepped peak passes w* = 1.9 while the exact one stays below it; there e is off by the "
          "model's jump in e at the switch. How far below the switch speed the band reached (relative: the "
          "farthest of the speeds (1 - 10^-k) x 1.9^1.25 that fell in it) and the error in it:", "", "| N | band, located | error in it | band, not located | error in it |",
          "|---|---|---|---|---|"]
    for j, n in enumerate(cfg["steps"]):
        bt, bf = conv["band"][True], conv["band"][False]
        L.append(f"| {n} | {bt['width'][j]:.1e} | {bt['error'][j]:.1e} | {bf['width'][j]:.1e} | {bf['error'][j]:.1e} |")
    L += ["", "\"Refused\": at the w_m* = 425 speed a coarse step overshoots the maximum interference past "
          "the law's end, which the law refuses (NaN, `ValueError` from `ContactLaw.impact`) rather than "
          "extrapolate; the figure given is the worst over the other speeds."]
    for locate in (True, False):
        e = conv[locate]
        fin = [k for k, x in enumerate(e) if math.isfinite(x) and cfg["steps"][k] >= ORDER_FROM]
        e = [e[k] for k in fin]
        first = cfg["steps"][fin[0]]
        order = math.log(e[0] / e[-1]) / math.log(cfg["steps"][-1] / first)
        L.append("")
        L.append(f"Observed order ({'located' if locate else 'not located'}): {order:.2f} "
                 f"(from N = {first} to {cfg['steps'][-1]}).")
    return L


def replace_section3(conv, cfg, path):
    """Rewrite part 3 of an existing FORCE_LAW.md (parts 1-2, the timings, kept as they are)."""
    text = path.read_text()
    head = text[:text.index("## 3. Steps per contact")]
    path.write_text(head + "\n".join(section3(conv, cfg)) + "\n\n")


def write(t, frac, imp, conv, cfg, path):
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    m = report.machine()
    L = ["# The contact law in the time domain: cost and time step", "",
         f"Generated by `python -m bench.force_law{' --quick' if cfg['quick'] else ''}` on {date}; "
         f"machine: {m.get('cpu', '?')}, {os.cpu_count()} cores. Times are medians of "
         f"{cfg['rounds']} interleaved rounds; ratios are medians of per-round ratios to the Hertz "
         "loop of the same round.", "",
         "## 1. Cost of one force call in a user's @njit loop", "",
         "Contact-major (one contact's whole impact, then the next: every branch predictable); the "
         "step-major loop DEM codes run is measured by `python -m bench.dem_loop` (bench/DEM_LOOP.md), "
         "whose figures the docs quote.", "",
         f"{cfg['contacts']} contacts x {cfg['path_steps']} steps of real impact paths (V1* 1.01-100); "
         "share of calls: " + ", ".join(f"{k} {v:.0%}" for k, v in frac.items()) + ".", "",
         "| force | ns per call (median) | x Hertz |", "|---|---|---|"]
    for name, x in t.items():
        L.append(f"| {name} | {x.median * 1e9:.2f} | {x.ratio:.2f} |")
    L += ["", "Target: contact_force <= 3x a plain Hertz force in the same loop.", "",
          "## 2. One time-stepped impact", "",
          f"`ContactLaw.impact(v1_star, {STEPS_1E8})` (velocity Verlet, switch located, JCG, eps_y = 0.005, "
          "nu = 0.33):", "", "| impact | time (median) |", "|---|---|"]
    for name, x in imp.items():
        L.append(f"| {name} | {fmt_time(x.median)} |")
    L += [""] + section3(conv, cfg)
    L.append("")
    path.write_text("\n".join(L) + "\n")


def convergence_rows(conv, steps):
    """The rows of docs/model.md section 10's time-step table: N, worst error located, not located;
    (*) where the worst is at the w_m* = 425 speed itself, with the worst over the other speeds."""
    def cell(locate, j):
        x, below = conv[locate][j], conv["below"][locate][j]
        return fmt_err(x) if x <= below else f"{fmt_err(x)} (*; other speeds {fmt_err(below)})"

    return [f"| {n} | {cell(True, j)} | {cell(False, j)} |" for j, n in enumerate(steps)]


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m bench.force_law", description=__doc__)
    p.add_argument("--quick", action="store_true")
    p.add_argument("--out", default=str(HERE / "FORCE_LAW.md"))
    p.add_argument("--convergence-only", action="store_true",
                   help="only the steps-per-contact table (part 3): print its rows, write nothing")
    p.add_argument("--update-md", action="store_true",
                   help="with --convergence-only: also rewrite part 3 of --out (parts 1-2 kept)")
    p.add_argument("--cost-only", action="store_true", help="only the cost per call (part 1): print it, write nothing")
    p.add_argument("--steps", type=int, nargs="+", metavar="N",
                   help=f"steps per Hertz contact duration for part 3 [default: {' '.join(map(str, STEPS))}]")
    a = p.parse_args(argv)
    warnings.simplefilter("ignore", fastrest.ValidityWarning)
    steps = a.steps or (STEPS[:6] if a.quick else STEPS)
    cfg = dict(quick=a.quick, contacts=64 if a.quick else 256, path_steps=400 if a.quick else 2000,
               rounds=5 if a.quick else 21, steps=steps, n_log=12 if a.quick else 192, n_top=8 if a.quick else 480,
               n_switch=16 if a.quick else 160, refine=8 if a.quick else 32, starts=2 if a.quick else 8)
    if a.cost_only:
        t, frac, _ = cost(dict(cfg, impacts=False), print)
        print("| force | ns per call (median) | x Hertz |\n|---|---|---|")
        print("\n".join(f"| {name} | {x.median * 1e9:.2f} | {x.ratio:.2f} |" for name, x in t.items()))
        return 0
    if a.convergence_only:
        conv = convergence(cfg, print)
        print("| steps per Hertz contact duration N | 1.9 crossing located | not located |")
        print("|---|---|---|")
        print("\n".join(convergence_rows(conv, steps)))
        if a.update_md:
            replace_section3(conv, cfg, Path(a.out))
            print(f"rewrote part 3 of {a.out}")
        return 0
    t, frac, imp = cost(cfg, print)
    conv = convergence(cfg, print)
    write(t, frac, imp, conv, cfg, Path(a.out))
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
