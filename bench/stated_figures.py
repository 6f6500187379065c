"""The worst errors behind the accuracy figures the README and the docs state for curves and the
direct solver: a search for the worst, not a sample's maximum.

``python -m bench.stated_figures [--quick] [--part curve direct hardening ...]`` writes
bench/STATED_FIGURES.md and bench/stated_figures.json (read by ``python -m bench`` when it renders
the README's table: a stated error is the worst of its own sample and this search).

1. ``curve``: :func:`fastrest.curve` (JCG, Etsion, Brake) against the direct solver
   (:func:`fastrest.direct.solve`) for e, w_m* and 1 - e^2. Materials: the corners of the validated
   (eps_y, nu) rectangle and their last ulp inside, the centre, points along every edge and random
   ones inside. Speeds per material: every cell boundary of the curve and +/- 1 ulp around it,
   ``per_cell`` points inside every cell (the last one before the w_m* = 425 speed included), both
   sides of the switch at 1.9^1.25, V1* -> 1, the limit speed itself. From the worst points of each
   quantity, golden-section searches in ln V1* (bracket: one cell either side) climb to the top of
   the error's hump between nodes. 1 - e^2: relative for JCG; Etsion's and Brake's change sign just
   above the switch, so theirs is relative to max(|1 - e^2|, 0.1).
2. ``direct``: :func:`fastrest.direct.e_exact` (JCG) against 40-digit mpmath (tests/reference.py).
3. ``hardening``: :func:`fastrest.direct.solve` with strain hardening (Et/E > 0, every unloading
   model) against tests/reference_hardening.py (40-digit mpmath, quadrature and a root find) for
   w_m*, e and 1 - e^2.

The direct solver's error is rounding (a few ulp), not a smooth function to climb: its points are
the domain's corners and edges, both sides of the switch, the limit speeds, the known worst points,
and random points chosen where e lies just above a power of two (where one ulp is the largest
relative error). The error is also given in ulp of the reference; the bound is the larger of the
worst relative error found and that many ulp just above a power of two (``ulp x 2^-52``), which no
point can exceed with the same ulp count, and the figure to state adds LIBM_MARGIN_ULP ulp for
another CPU's libm (for 1 - e^2: twice the bound).
"""
import argparse
import datetime
import json
import math
import sys
import warnings
from pathlib import Path

import numpy as np

import fastrest
from fastrest import direct
from fastrest.energy import V_SWITCH
from fastrest.interpolation import cell_edges

from .timing import fmt_err

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
NAMES = ("jcg", "etsion", "brake")
E0, E1, N0, N1 = 0.0005, 0.01, 0.2, 0.45
GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0
#: Known worst points (these searches' and independent ones'), always evaluated: (V1*, eps_y, nu) per part, with the model.
KNOWN = {
    "curve": [(808.0595551676569, 0.01, 0.45, "etsion"), (2.2812630427249756, 0.0005, 0.2, "jcg"),
              (808.4129525336591, 0.01, 0.45, "jcg"), (2.281713008689937, 0.01, 0.2, "jcg")],
    "direct": [(693.9623955652306, 0.008699936008934026, 0.26629357801684467)],
    "hardening": [(85.615, 0.006054, 0.21673, 1.72e-4)],
}
ULP1 = 2.0 ** -52
#: Ulp a different CPU's libm (another code path of exp/log/pow) may move the direct solver's result.
LIBM_MARGIN_ULP = 4

__all__ = ["run", "main", "KNOWN", "curve_materials"]


def curve_materials(n_edge, n_random, seed):
    """Corners (and their last ulp inside), the centre, ``n_edge`` points on each edge, random inside."""
    rng = np.random.default_rng(seed)
    ends_e = (E0, E1, np.nextafter(E0, 1), np.nextafter(E1, 0))
    ends_n = (N0, N1, np.nextafter(N0, 1), np.nextafter(N1, 0))
    pts = [(float(e), float(n)) for e in ends_e for n in ends_n] + [(0.005, 0.33)]
    t = rng.uniform(0.0, 1.0, (4, n_edge))
    pts += [(E1, N0 + x * (N1 - N0)) for x in t[0]] + [(E0, N0 + x * (N1 - N0)) for x in t[1]]
    pts += [(E0 * (E1 / E0) ** x, N0) for x in t[2]] + [(E0 * (E1 / E0) ** x, N1) for x in t[3]]
    pts += list(zip(rng.uniform(E0, E1, n_random), rng.uniform(N0, N1, n_random)))
    return [(float(a), float(b)) for a, b in pts]


def _metric(got, ref, floor):
    d = np.abs(got - ref)
    r = d / np.maximum(np.abs(ref), floor)
    return np.where(np.isfinite(r), r, np.where(d == 0, 0.0, np.inf))


def golden_max(f, lo, hi, iters):
    """Maximise f (vectorised) on each [lo_i, hi_i] by golden-section steps; the best point seen
    (the ends included) per row: (x, f(x))."""
    a, b = np.array(lo, float), np.array(hi, float)
    fa, fb = f(a), f(b)
    up = fb > fa
    x, best = np.where(up, b, a), np.where(up, fb, fa)
    for _ in range(iters):
        c1, c2 = b - GOLDEN * (b - a), a + GOLDEN * (b - a)
        f1, f2 = f(c1), f(c2)
        for c, fc in ((c1, f1), (c2, f2)):
            u = fc > best
            x, best = np.where(u, c, x), np.where(u, fc, best)
        left = f1 >= f2
        a, b = np.where(left, a, c1), np.where(left, c2, b)
    return x, best


# --- 1. curves -------------------------------------------------------------------------------------

def _curve_speeds(edges, vmax, per_cell):
    lo, hi = edges[:, 0], edges[:, 1]
    t = (np.arange(per_cell) + 0.5) / per_cell
    inner = np.exp(np.log(lo)[:, None] + np.log(hi / lo)[:, None] * t[None, :]).ravel()
    b = np.concatenate([lo, [vmax]])
    s = np.concatenate([b, np.nextafter(b, 0), np.nextafter(b, np.inf), inner,
                        [1.0, 1.0 + 1e-12, 1.0 + 1e-9, 1.5, np.nextafter(V_SWITCH, 0), V_SWITCH * (1 + 1e-12),
                         vmax * (1 - 1e-12), vmax * (1 - 1e-9), vmax * (1 - 1e-6)]])
    return np.unique(s[(s >= 1.0) & (s <= vmax)])


def curve_part(cfg, log):
    out = {m: {q: {"error": 0.0, "at": None} for q in ("e", "omega_m", "loss")} for m in NAMES}
    mats = curve_materials(cfg["n_edge"], cfg["n_random"], 11)
    extra = {}
    for v, e, n, m in KNOWN["curve"]:
        extra.setdefault((e, n), []).append(v)
        if (e, n) not in mats:
            mats.append((e, n))
    n_points = 0
    for eps, nu in mats:
        for m in NAMES:
            c = fastrest.curve(eps, nu, m)
            _, ed = cell_edges(V_SWITCH, c.v_max, 5)
            v = np.unique(np.concatenate([_curve_speeds(ed, c.v_max, cfg["per_cell"]), extra.get((eps, nu), [])]))
            floor = 0.0 if m == "jcg" else 0.1
            width = math.log(2.0) / 32  # one cell in ln V1*

            def values(vv, m=m, c=c):
                s = direct.solve(vv, eps, nu, m)
                return {"e": (c.e(vv), s["e"], 0.0), "omega_m": (c.omega_m(vv), s["omega_m_star"], 0.0),
                        "loss": (c.loss(vv), s["loss"], floor)}

            q = values(v)
            n_points += v.size
            for key, (got, ref, fl) in q.items():
                err = _metric(got, ref, fl)
                start = v[np.argsort(-err, kind="stable")[:cfg["starts"]]]
                lo = np.maximum(np.log(start) - width, 0.0)
                hi = np.minimum(np.log(start) + width, math.log(c.v_max))

                def f(x, key=key):
                    vv = np.clip(np.exp(x), 1.0, c.v_max)
                    g, r, fl2 = values(vv)[key]
                    return _metric(g, r, fl2)

                x, best = golden_max(f, lo, hi, cfg["iters"])
                i, k = int(np.argmax(err)), int(np.argmax(best))
                val, at = (float(err[i]), float(v[i])) if err[i] >= best[k] else \
                    (float(best[k]), float(np.clip(np.exp(x[k]), 1.0, c.v_max)))
                r = out[m][key]
                if val > r["error"]:
                    r["error"], r["at"] = val, [at, eps, nu]
    log(f"  curves: {len(mats)} materials x {len(NAMES)} models, {n_points} sample points, "
        f"searches from the {cfg['starts']} worst of each quantity")
    return {"materials": len(mats), "points": n_points, "starts": cfg["starts"], "per_cell": cfg["per_cell"],
            "models": out}


# --- 2-3. the direct solver against 40-digit mpmath --------------------------------------------------

def _references():
    sys.path.insert(0, str(REPO / "tests"))
    try:
        import reference  # noqa: E402  (the test suite's independent mpmath model)
        import reference_hardening  # noqa: E402
    finally:
        sys.path.remove(str(REPO / "tests"))
    return reference, reference_hardening


def _mantissa(x):
    x = np.abs(np.asarray(x, float))
    return x / 2.0 ** np.floor(np.log2(x))


def _record(acc, key, got, ref, where):
    rel = abs(got - ref) / abs(ref)
    ulp = abs(got - ref) / float(np.spacing(abs(ref)))
    r = acc.setdefault(key, {"relative": 0.0, "at": None, "ulp": 0.0, "ulp_at": None, "points": 0})
    r["points"] += 1
    if rel > r["relative"]:
        r["relative"], r["at"] = rel, list(where)
    if ulp > r["ulp"]:
        r["ulp"], r["ulp_at"] = ulp, list(where)


def _finish(acc):
    """The bound found (worst relative error, or the worst ulp count just above a power of two) and
    the figure to state: that plus LIBM_MARGIN_ULP ulp for e and w_m*, twice it for 1 - e^2 (one ulp
    of e is many of a smaller 1 - e^2), for another CPU's libm."""
    for key, r in acc.items():
        if "relative" in r:
            r["stated_bound"] = max(r["relative"], r["ulp"] * ULP1)
            r["stated"] = 2.0 * r["stated_bound"] if key == "loss" else \
                max(r["relative"], (r["ulp"] + LIBM_MARGIN_ULP) * ULP1)
    return acc


def _candidates(n_pool, n_pick, rng, et=None):
    """Random points whose e (JCG) lies just above a power of two: (v, eps, nu[, et])."""
    eps = E0 * (E1 / E0) ** rng.uniform(0, 1, n_pool)
    nu = rng.uniform(N0, N1, n_pool)
    h = np.zeros(n_pool) if et is None else 10.0 ** rng.uniform(-9, math.log10(0.99), n_pool)
    lim = np.array([fastrest.limit(a, b, et_ratio=c).v1_star for a, b, c in zip(eps, nu, h)])
    lo = np.full(n_pool, 1.0) if et is None else np.full(n_pool, V_SWITCH * (1 + 1e-9))
    v = np.exp(np.log(lo) + rng.uniform(0, 1, n_pool) * np.log(lim / lo))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.ValidityWarning)
        e = direct.solve(v, eps, nu, "jcg", et_ratio=h)["e"]
    k = np.argsort(_mantissa(e), kind="stable")[:n_pick]
    return list(zip(v[k], eps[k], nu[k], h[k]))


def _structured(et_list):
    pts = []
    for h in et_list:
        for eps in (E0, E1, 0.005):
            for nu in (N0, N1, 0.33):
                lim = fastrest.limit(eps, nu, et_ratio=h).v1_star
                for v in (np.nextafter(V_SWITCH, 4), V_SWITCH * (1 + 1e-9), 2.5, 3.0, 30.0, 300.0,
                          lim * (1 - 1e-9), lim):
                    if v <= lim:
                        pts.append((float(v), eps, nu, h))
    return pts


def direct_part(cfg, log):
    ref, _ = _references()
    rng = np.random.default_rng(3)
    pts = [(v, e, n, 0.0) for v, e, n in KNOWN["direct"]] + _structured([0.0])
    pts += [(1.0 + 1e-9, e, n, 0.0) for e in (E0, E1) for n in (N0, N1)]
    pts += _candidates(cfg["pool"], cfg["n_mp"], rng)
    acc = {}
    for v, e, n, _ in pts:
        v, e, n = float(v), float(e), float(n)
        _record(acc, "e", float(fastrest.direct.e_exact(v, e, n)), float(ref.ref_e_star(v, e, n, "jcg")), (v, e, n))
    log(f"  direct: {len(pts)} points against 40-digit mpmath")
    return _finish(acc)


def hardening_part(cfg, log):
    _, hard = _references()
    rng = np.random.default_rng(4)
    pts = list(KNOWN["hardening"]) + _structured([1e-9, 1.72e-4, 1e-3, 0.05, 0.3, 0.5, 0.99])
    pts += _candidates(cfg["pool"], cfg["n_hard"], rng, et=True)
    acc = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.ValidityWarning)
        for v, e, n, h in pts:
            v, e, n, h = float(v), float(e), float(n), float(h)
            for m in NAMES:
                wm, er, loss = hard.hard_e(v, e, n, h, m)
                s = direct.solve(v, e, n, m, et_ratio=h)
                where = (v, e, n, h, m)
                _record(acc, "e", float(s["e"]), er, where)
                _record(acc, "omega_m", float(s["omega_m_star"]), wm, where)
                if m == "jcg" or abs(loss) >= 0.1:
                    _record(acc, "loss", float(s["loss"]), loss, where)
                else:  # a sign-changing 1 - e^2 near its zero: absolute
                    r = acc.setdefault("loss, absolute where |1 - e^2| < 0.1 (Etsion, Brake)",
                                       {"absolute": 0.0, "at": None, "points": 0})
                    r["points"] += 1
                    if abs(float(s["loss"]) - loss) > r["absolute"]:
                        r["absolute"], r["at"] = abs(float(s["loss"]) - loss), list(where)
    log(f"  hardening: {len(pts)} points x {len(NAMES)} models against 40-digit mpmath")
    return _finish(acc)


PARTS = {"curve": curve_part, "direct": direct_part, "hardening": hardening_part}


# --- report ------------------------------------------------------------------------------------------

def write_md(res, path):
    L = ["# The worst errors behind the stated accuracy figures", "",
         f"Generated by `python -m bench.stated_figures{' --quick' if res['quick'] else ''}` on {res['date']}; "
         "method in the script's doc. Each figure is the worst found (sample and local search together); "
         "the README and the docs state these rounded up (the direct solver's: the last column, with a margin "
         "for another CPU's libm).", ""]
    if "curve" in res:
        c = res["curve"]
        L += [f"## Curves against the direct solver ({c['materials']} materials, {c['points']} sample points, "
              f"{c['per_cell']} per cell plus every boundary +/- 1 ulp; golden-section searches from the "
              f"{c['starts']} worst of each quantity)", "",
              "| model | e | w_m* | 1 - e^2 | worst e at (V1*, eps_y, nu) | worst 1 - e^2 at |", "|---|---|---|---|---|---|"]
        for m, r in c["models"].items():
            lm = "relative" if m == "jcg" else "relative to max(abs, 0.1)"
            L.append(f"| {m} | {r['e']['error']:.3g} | {r['omega_m']['error']:.3g} | {r['loss']['error']:.3g} ({lm}) | "
                     f"{tuple(r['e']['at'])} | {tuple(r['loss']['at'])} |")
        L.append("")
    for part, title in (("direct", "The direct solver (JCG) against 40-digit mpmath (tests/reference.py)"),
                        ("hardening", "The direct solver with strain hardening (every model) against 40-digit "
                                      "mpmath (tests/reference_hardening.py)")):
        if part not in res:
            continue
        L += [f"## {title}", "", "| quantity | points | worst relative | at | worst in ulp | at | bound "
              f"(max of relative, ulp x 2^-52) | to state (+{LIBM_MARGIN_ULP} ulp; 1 - e^2: x 2) |",
              "|---|---|---|---|---|---|---|---|"]
        for q, r in res[part].items():
            if "relative" not in r:
                L.append(f"| {q} | {r['points']} | absolute {r['absolute']:.3g} | {tuple(r['at'])} | | | | |")
                continue
            L.append(f"| {q} | {r['points']} | {r['relative']:.3g} | {tuple(r['at'])} | {r['ulp']:.2f} | "
                     f"{tuple(r['ulp_at'])} | {r['stated_bound']:.3g} | {fmt_err(r['stated'])} |")
        L.append("")
    L += ["1 - e^2 with hardening: JCG everywhere; Etsion and Brake where |1 - e^2| >= 0.1 (theirs changes "
          "sign just above the switch, where a relative error has no bound).", ""]
    path.write_text("\n".join(L))


def run(parts, quick, log=print):
    cfg = dict(n_edge=2 if quick else 6, n_random=2 if quick else 10, per_cell=4 if quick else 16,
               starts=4 if quick else 24, iters=20 if quick else 40, pool=2000 if quick else 40000,
               n_mp=8 if quick else 200, n_hard=4 if quick else 60)
    res = {"quick": quick, "config": cfg,
           "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")}
    warnings.simplefilter("ignore", fastrest.ValidityWarning)
    for p in parts:
        res[p] = PARTS[p](cfg, log)
    return res


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m bench.stated_figures", description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="a small search (a minute)")
    p.add_argument("--part", nargs="+", choices=list(PARTS), default=list(PARTS))
    p.add_argument("--out-dir", default=str(HERE))
    p.add_argument("--render", action="store_true",
                   help="search nothing: recompute the figures to state and STATED_FIGURES.md from the stored json")
    a = p.parse_args(argv)
    out = Path(a.out_dir)
    js = out / "stated_figures.json"
    if a.render:
        old = json.loads(js.read_text())
        for part in ("direct", "hardening"):
            if part in old:
                _finish(old[part])
    else:
        res = run(a.part, a.quick)
        old = json.loads(js.read_text()) if js.exists() and set(a.part) != set(PARTS) else {}
        old.update(res)
    tmp = js.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(old, indent=1))
    tmp.replace(js)
    write_md(old, out / "STATED_FIGURES.md")
    print((out / "STATED_FIGURES.md").read_text())
    return 0


if __name__ == "__main__":
    sys.exit(main())
