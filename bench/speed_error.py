"""Part 1: speed against error of every way to get e, on the same random points of the validated domain.

Time: per evaluation, batch calls through each path's public API on the timing set (the curves
evaluate each material's points with that material's Curve; tables, fits and the direct solver take
the points in a random order, every point with its own material). Error: worst relative error of e
(JCG unloading unless stated) against the direct solver on the error set (a subset of the timing
points plus hard cases); for the paper's fits that is their deviation from the model, and for the
direct solver its deviation from an independent 40-digit mpmath implementation (tests/reference.py).
"""
import sys
import warnings
from pathlib import Path

import numba
import numpy as np

import fastrest
from fastrest import models, tables
from fastrest.curve import Curve
from fastrest.curve_data import BITS_PER_OCTAVE, build_curve_data
from fastrest.tables import Table
from fastrest.tables.kernel import table_array

from . import kernels
from .points import error_subset, point_set, reference, worst
from .timing import interleaved, with_threads

REPO = Path(__file__).resolve().parent.parent
QTY = {"omega_m": 0, "e_jcg": 1, "loss_jcg": 2, "e_etsion": 3, "loss_etsion": 4}
#: The Etsion loss changes sign at low speed: its error is relative to max(|1 - e^2|, 1e-3), as in
#: Table.measure_error.
FLOOR = {"loss_etsion": 1e-3}


def grid_label(g):
    g = tables.normalise_grid(g)
    k = f"K={g['bits_per_octave']}" + (f"/{g['fine_bits_per_octave']}" if g["fine_bits_per_octave"] != g["bits_per_octave"] else "")
    n = "/".join(str(n) for _, n in g["eps_y_blocks"]) + ("/" if g["eps_y_blocks"] else "") + str(g["n_eps_y"])
    return f"{n}x{g['n_nu']}, {k}"


def curve_errors(curves, ps, ref):
    """Worst relative error of Curve.omega_m / e / loss (JCG) over the error set."""
    got = {q: np.empty(ps.size) for q in ("omega_m", "e_jcg", "loss_jcg")}
    for k, c in enumerate(curves):
        s = slice(ps.start[k], ps.start[k + 1])
        v = ps.v[s]
        got["omega_m"][s] = c.omega_m(v)
        got["e_jcg"][s] = c.e(v)
        got["loss_jcg"][s] = c.loss(v)
    out = {}
    for q, a in got.items():
        err, i = worst(a, ref[q])
        out[q] = {"max_rel_error": err, "at_v1_star": float(ps.v[i]), "at_eps_y": float(ps.eps_y[i]),
                  "at_nu": float(ps.nu[i])}
    return out


def table_errors(tab, ps, ref):
    """Worst relative error of every table quantity; points the table refuses (NaN) are counted."""
    out = {}
    for q, iq in QTY.items():
        got = np.empty(ps.size)
        table_array(tab.data, iq, ps.v, ps.eps_y, ps.nu, got)
        refused = ~np.isfinite(got)
        err, i = worst(got, ref[q], mask=~refused, floor=FLOOR.get(q, 0.0))
        out[q] = {"max_rel_error": err, "at_v1_star": float(ps.v[i]), "at_eps_y": float(ps.eps_y[i]),
                  "at_nu": float(ps.nu[i]), "refused": int(refused.sum()),
                  "refused_max_v_over_vmax": float(np.max(ps.v[refused] / np.repeat(ps.vmax_m, np.diff(ps.start))[refused]))
                  if refused.any() else None}
    return out


def direct_vs_mpmath(ps, n, seed=7):
    """Worst relative error of the direct solver's e (JCG) against tests/reference.py (mpmath)."""
    if n <= 0:
        return None
    try:
        sys.path.insert(0, str(REPO / "tests"))
        import reference as mpref  # noqa: E402  (the test-suite's independent mpmath model)
    except Exception:  # mpmath missing: no independent check
        return None
    finally:
        if sys.path and sys.path[0] == str(REPO / "tests"):
            sys.path.pop(0)
    rng = np.random.default_rng(seed)
    idx = np.concatenate([[0, 5, 9], rng.choice(ps.size, size=max(0, n - 3), replace=False)])[:n]
    worst_err = 0.0
    for i in idx:
        v, e, nu = float(ps.v[i]), float(ps.eps_y[i]), float(ps.nu[i])
        exact = mpref.ref_e_star(v, e, nu, "jcg")
        got = fastrest.direct.e_exact(v, e, nu)
        worst_err = max(worst_err, abs(got - exact) / abs(exact))
    return {"max_rel_error": worst_err, "points": int(idx.size)}


def run(cfg, log=print):
    K = cfg["n_materials"]
    ps = point_set(K, cfg["n_time"] // K)
    pe = error_subset(ps, cfg["per_err"])
    log(f"  reference: direct solver at {pe.size} points ...")
    ref = reference(pe)

    # --- curves at several cells per octave, tables at several resolutions --------------------
    curves = {}
    for bits in cfg["curve_bits"]:
        curves[bits] = [Curve(e, n, "jcg", build_curve_data(e, n, "jcg", bits_per_octave=bits))
                        for e, n in zip(ps.eps_m, ps.nu_m)]
    c_err = {bits: curve_errors(cs, pe, ref) for bits, cs in curves.items()}

    default_tab = fastrest.load_table()
    tabs = {}
    for g in cfg["table_grids"]:
        log(f"  generating table {grid_label(tables.normalise_grid(g))} ...")
        tabs[grid_label(tables.normalise_grid(g))] = Table(tables.generate(g, progress=False))
    t_err = {"default": table_errors(default_tab, pe, ref)}
    t_err.update({name: table_errors(t, pe, ref) for name, t in tabs.items()})

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.ValidityWarning)
        fit_range = pe.v <= models.JGM_FIT_V_MAX
        fit43_err, i43 = worst(models.jgm_fit_jcg(pe.v, pe.eps_y), ref["e_jcg"], mask=fit_range)
        fit45_err, i45 = worst(models.jgm_fit_etsion(pe.v, pe.eps_y), ref["e_etsion"])
    fit_where = {k: {"at_v1_star": float(pe.v[i]), "at_eps_y": float(pe.eps_y[i]), "at_nu": float(pe.nu[i])}
                 for k, i in (("fit4344", i43), ("fit45", i45))}
    log(f"  direct solver vs mpmath at {cfg['n_mp']} points ...")
    d_err = direct_vs_mpmath(pe, cfg["n_mp"])

    # --- timing set: points every table answers for (drops V1* within a coarse table's error of
    # the w_m* = 425 limit, a handful at most) ---------------------------------------------------
    v, e, n = ps.shuffled()
    keep = np.ones(v.size, bool)
    for t in [default_tab, *tabs.values()]:
        o = np.empty(v.size)
        table_array(t.data, 1, v, e, n, o)
        keep &= np.isfinite(o)
    dropped = int((~keep).sum())
    v, e, n = (np.ascontiguousarray(a[keep]) for a in (v, e, n))
    N = v.size
    out = np.empty(N)
    dst = np.empty(N)
    nd = cfg["n_direct"]
    vd, ed, nud = v[:nd].copy(), e[:nd].copy(), n[:nd].copy()
    chunks = [ps.chunk(k) for k in range(K)]
    n_curve = sum(c.size for c in chunks)

    def curve_case(cs):
        def f():
            for c, x in zip(cs, chunks):
                c.e(x)
        return f, n_curve

    def table_case(t):
        return (lambda: t.e(v, e, n)), N

    cases = {
        "copy": ((lambda: np.copyto(dst, v)), N),
        "fit4344_numba": ((lambda: models.jgm_fit_jcg_array(v, e, out)), N),
        "fit4344_numpy": ((lambda: models.jgm_fit_jcg(v, e)), N),
        "fit45_numba": ((lambda: kernels.fit45_loop(v, e, out)), N),
        "fit45_numpy": ((lambda: models.jgm_fit_etsion(v, e)), N),
        "direct": ((lambda: fastrest.direct.e_exact(vd, ed, nud)), nd),
        "table_default": ((lambda: fastrest.e_star(v, e, n)), N),
        "table_default_1t": (with_threads(1, lambda: fastrest.e_star(v, e, n)), N),
    }
    for bits, cs in curves.items():
        cases[f"curve_{bits}"] = curve_case(cs)
    for name, t in tabs.items():
        cases[f"table_{name}"] = table_case(t)
    log(f"  timing {len(cases)} methods, {cfg['rounds_plot']} interleaved rounds ...")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.ValidityWarning)
        tm = interleaved(cases, cfg["rounds_plot"], ref="fit4344_numba", seed=1)

    methods = []

    def add(key, label, kind, error, error_of, default=False, **extra):
        t = tm[key]
        methods.append(dict(key=key, label=label, kind=kind, time_median=t.median, time_min=t.min,
                            ratio=t.ratio, ratio_of_minima=t.ratio_of_minima, error=error,
                            error_of=error_of, default=default, n_evals=t.n_evals,
                            timing={"other_cores": t.other_cores}, **extra))

    add("direct", "direct solver (fastrest.direct.e_exact)", "direct",
        d_err["max_rel_error"] if d_err else None,
        f"vs 40-digit mpmath, {d_err['points']} points" if d_err else "reference (mpmath unavailable)")
    for bits in cfg["curve_bits"]:
        cells = curves[bits][0].data.e_rows.shape[0]
        add(f"curve_{bits}", f"Curve.e, 2^{bits} cells/octave" + (" (default)" if bits == BITS_PER_OCTAVE else ""),
            "curve", c_err[bits]["e_jcg"]["max_rel_error"], "vs direct", default=bits == BITS_PER_OCTAVE,
            bits=bits, cells_centre_material=cells)
    g0 = tables.normalise_grid(None)
    add("table_default", f"fastrest.e_star, default table ({grid_label(g0)})", "table",
        t_err["default"]["e_jcg"]["max_rel_error"], "vs direct", default=True,
        mbytes=default_tab.data.coef.nbytes / 2**20)
    add("table_default_1t", "fastrest.e_star, default table, 1 Numba thread", "table",
        t_err["default"]["e_jcg"]["max_rel_error"], "vs direct", mbytes=default_tab.data.coef.nbytes / 2**20)
    for name, t in tabs.items():
        add(f"table_{name}", f"Table.e, {name}", "table", t_err[name]["e_jcg"]["max_rel_error"],
            "vs direct", mbytes=t.data.coef.nbytes / 2**20)
    add("fit4344_numba", "fit (42)-(44), Numba kernel (speed reference)", "fit", fit43_err,
        "deviation from the model (JCG), V1* <= 1000")
    add("fit4344_numpy", "fit (42)-(44), NumPy (models.jgm_fit_jcg)", "fit", fit43_err,
        "deviation from the model (JCG), V1* <= 1000")
    add("fit45_numba", "fit (45), Numba loop (models.jgm_fit_etsion_kernel)", "fit", fit45_err, "deviation from the model (Etsion)")
    add("fit45_numpy", "fit (45), NumPy (models.jgm_fit_etsion)", "fit", fit45_err,
        "deviation from the model (Etsion)")
    add("copy", "memory copy (np.copyto, the floor)", "floor", None, "-")
    return {
        "n_materials": K, "n_time": N, "n_err": pe.size, "n_direct": nd, "dropped_timing_points": dropped,
        "rounds": cfg["rounds_plot"], "methods": methods,
        "parallel_min_points": getattr(tables, "PARALLEL_MIN_POINTS", None),
        "threads": numba.config.NUMBA_NUM_THREADS, "curve_errors": c_err, "table_errors": t_err,
        "direct_vs_mpmath": d_err, "fit_errors": {"fit4344": fit43_err, "fit45": fit45_err}, "fit_where": fit_where,
        "materials": [[float(a), float(b), float(c)] for a, b, c in zip(ps.eps_m, ps.nu_m, ps.vmax_m)],
    }


def plot_label(m):
    if m["kind"] == "curve":
        return f"Curve.e, K={m['bits']}" + (" (default)" if m["default"] else "")
    if m["key"] == "table_default":
        return m["label"]
    if m["key"] == "table_default_1t":
        return "same, 1 thread"
    if m["kind"] == "table":
        return "Table " + m["label"].split(", ", 1)[1]
    return m["label"]


def plot(res, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = {"direct": ("D", "tab:red"), "curve": ("o", "tab:blue"), "table": ("s", "tab:green"),
              "fit": ("^", "tab:orange")}
    fig, ax = plt.subplots(figsize=(9.5, 6.2))
    floor_y = 1e-17  # an error of exactly 0 is drawn here
    by = {m["key"]: m for m in res["methods"]}
    short = {"fit4344_numba": ("fit (42)-(44), Numba", (-8, -13), "right"),
             "fit4344_numpy": ("fit (42)-(44), NumPy", (8, -13), "left"),
             "fit45_numba": ("fit (45), Numba", (-8, 7), "right"),
             "fit45_numpy": ("fit (45), NumPy", (8, 7), "left"),
             "direct": ("direct solver", (-8, 7), "right"),
             "table_default_1t": ("same, 1 thread", (8, 3), "left"),
             "table_default": (None, (-10, 6), "right")}
    for m in res["methods"]:
        if m["kind"] == "floor":
            continue
        x = m["time_median"] * 1e9
        y = m["error"] if m["error"] else floor_y
        mk, col = styles[m["kind"]]
        ax.plot([m["time_min"] * 1e9, x], [y, y], "-", color=col, lw=1, alpha=0.6)
        ax.plot(x, y, mk, color=col, ms=11 if m["default"] else 7,
                markeredgecolor="k" if m["default"] else col, markeredgewidth=1.5 if m["default"] else 0.5)
        label, off, ha = short.get(m["key"], (None, (8, 4), "left"))
        label = label or plot_label(m)
        ax.annotate(label, (x, y), textcoords="offset points", xytext=off, fontsize=7.5, ha=ha,
                    fontweight="bold" if m["default"] else "normal")
    for key, text in (("copy", "memory copy\n(the floor)"), ("fit4344_numba", "closed-form\nfit's cost")):
        x = by[key]["time_median"] * 1e9
        ax.axvline(x, ls=":" if key == "copy" else "--", color="0.35", lw=1)
        ax.text(x * 1.08, 3e-18, text, fontsize=7.5, color="0.3", va="bottom")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per evaluation (ns), median over interleaved rounds (line: to the minimum)")
    ax.set_ylabel("worst relative error of e vs the direct solver")
    ax.set_title(f"fastrest: speed against error ({res['n_time']:,} random points of the validated domain "
                 f"for timing, {res['n_err']:,} for errors)", fontsize=9.5)
    ax.grid(True, which="major", alpha=0.3)
    xs = [m["time_median"] * 1e9 for m in res["methods"]] + [m["time_min"] * 1e9 for m in res["methods"]]
    ax.set_xlim(min(xs) / 2, max(xs) * 12)
    ax.set_ylim(1e-18, 5)
    thr = (f" Tables: fastrest.e_star / Table.e_star use {res['threads']} Numba threads for batches of "
           f">= {res['parallel_min_points']:,} points (\"same, 1 thread\": the default table limited to one thread)."
           if res.get("parallel_min_points") else "")
    import textwrap
    caption = textwrap.fill("Larger markers: the default configurations. K: 2^K cells per octave of V1*. Direct "
                            "solver: its error against a 40-digit mpmath implementation. Fits: their deviation "
                            "from the model (JCG: (42)-(44); Etsion: (45))." + thr, 175)
    fig.text(0.01, 0.008, caption, fontsize=7.5, color="0.3")
    fig.tight_layout(rect=(0, 0.015 + 0.022 * (caption.count("\n") + 1), 1, 1))
    fig.savefig(path, dpi=130)
    plt.close(fig)
