"""Part 2: the ways fastrest is used, each timed against the closed-form fit in the same run."""
import tempfile
import timeit
import warnings
from pathlib import Path

import numba
import numpy as np

import fastrest
from fastrest import models, tables
from fastrest.curve import Curve
from fastrest.curve_data import BITS_PER_OCTAVE, build_curve_data
from fastrest.tables.kernel import table_array

from . import kernels
from .points import CENTRE, SEED, point_set, reference, worst
from .timing import interleaved, repeated, with_threads

EPS, NU = CENTRE

__all__ = ["batch_sizes", "threads", "scalar", "in_njit", "multi_material", "curve_from_table", "build_times", "run"]


def _speeds(n, vmax, seed=SEED):
    return np.exp(np.random.default_rng(seed + n % 1000003).uniform(0.0, 1.0, n) * np.log(vmax))


def batch_sizes(cfg, c, log):
    """Curve.e over n points (ns per point) against the fit kernel on the same points."""
    out = {}
    eps1 = np.array([EPS])
    for n in cfg["batch_sizes"]:
        v = _speeds(n, c.v_max)
        o = np.empty(n)
        dst = np.empty(n)
        cases = {
            "Curve.e": ((lambda: c.e(v)), n),
            "curve_loop": ((lambda: kernels.curve_loop(c.data, v, o)), n),
            "fit": ((lambda: models.jgm_fit_jcg_array(v, eps1, o)), n),
            "copy": ((lambda: np.copyto(dst, v)), n),
        }
        rounds = cfg["rounds"] if n <= 10**6 else max(5, cfg["rounds"] // 2)
        log(f"  batch n = {n:.0e} ...")
        tm = interleaved(cases, rounds, ref="fit", seed=n % 97)
        out[int(n)] = {k: t.as_dict() for k, t in tm.items()}
    return out


def threads(cfg, c, log):
    """A prange loop calling fastrest.jit.e_curve with 1 and 2 threads."""
    out = {}
    n_max = numba.config.NUMBA_NUM_THREADS
    eps1 = np.array([EPS])
    try:
        for n in cfg["thread_sizes"]:
            v = _speeds(n, c.v_max)
            o = np.empty(n)

            def par(k):
                def f():
                    numba.set_num_threads(k)
                    kernels.curve_prange(c.data, v, o)
                return f

            cases = {"fit": ((lambda: models.jgm_fit_jcg_array(v, eps1, o)), n),
                     "serial loop": ((lambda: kernels.curve_loop(c.data, v, o)), n)}
            for k in sorted({1, min(2, n_max)}):
                cases[f"prange, {k} thread" + ("s" if k > 1 else "")] = (par(k), n)
            log(f"  threads n = {n:.0e} ...")
            tm = interleaved(cases, cfg["rounds"], ref="fit", seed=3)
            out[int(n)] = {k: t.as_dict() for k, t in tm.items()}
    finally:
        numba.set_num_threads(n_max)
    return {"max_threads": n_max, "sizes": out}


def scalar(cfg, c, log):
    """Scalar calls from Python (timeit loops, interleaved rounds)."""
    import fastrest.direct  # noqa: F401
    g = {"c": c, "fastrest": fastrest, "models": models, "fit": models.jgm_fit_jcg_kernel}
    stmts = {
        "Curve.e(5.0)": "c.e(5.0)",
        "Curve.loss(5.0)": "c.loss(5.0)",
        "Curve.omega_m(5.0)": "c.omega_m(5.0)",
        "Curve.e(500.0)": "c.e(500.0)",
        "fastrest.e_star(5.0, 0.005, 0.33)": "fastrest.e_star(5.0, 0.005, 0.33)",
        "fastrest.direct.e_exact(5.0, 0.005, 0.33)": "fastrest.direct.e_exact(5.0, 0.005, 0.33)",
        "fit jgm_fit_jcg_kernel(5.0, 0.005) (Numba dispatcher)": "fit(5.0, 0.005)",
        "fit models.jgm_fit_jcg(5.0, 0.005) (NumPy)": "models.jgm_fit_jcg(5.0, 0.005)",
    }
    ref = "fit jgm_fit_jcg_kernel(5.0, 0.005) (Numba dispatcher)"
    cases = {}
    for name, stmt in stmts.items():
        t = timeit.Timer(stmt, globals=g)
        t.timeit(10)  # warm-up
        number = max(10, int(cfg["scalar_block"] / max(t.timeit(100) / 100, 1e-9)))
        cases[name] = ((lambda t=t, number=number: t.timeit(number)), number)
    log("  scalar calls ...")
    tm = interleaved(cases, cfg["rounds"], ref=ref, min_block=0.0, seed=5)
    return {k: t.as_dict() for k, t in tm.items()}


def in_njit(cfg, c, log):
    """Calls from inside a user's @njit loop: throughput (independent) and latency (dependent chain)."""
    n = cfg["njit_n"]
    v = _speeds(n, c.v_max, SEED + 11)
    o = np.empty(n)
    cases = {
        "e_curve throughput": ((lambda: kernels.curve_loop(c.data, v, o)), n),
        "e_curve latency": ((lambda: kernels.curve_chain(c.data, v)), n),
        "fit throughput": ((lambda: kernels.fit_loop(v, EPS, o)), n),
        "fit latency": ((lambda: kernels.fit_chain(v, EPS)), n),
    }
    if not np.isfinite(kernels.curve_chain(c.data, v)):
        raise RuntimeError("latency chain left the curve's domain")
    log("  inside @njit ...")
    tm = interleaved(cases, cfg["rounds"], ref="fit throughput", seed=7)
    res = {k: t.as_dict() for k, t in tm.items()}
    for k in ("e_curve latency", "fit latency"):
        res[k]["ratio_to_ref"] = float(np.median(tm[k].per_eval / tm["fit latency"].per_eval))
        res[k]["ratio_of_minima"] = tm[k].min / tm["fit latency"].min
    res["_n"] = n
    return res


def multi_material(cfg, log):
    """Points with their own materials: fastrest.e_star and the jit e_table loop."""
    K = cfg["n_materials"]
    ps = point_set(K, cfg["mm_n"] // K, seed=SEED + 3)
    v, e, nu = ps.shuffled(SEED + 4)
    # the same points as a scene: material index per point
    perm = np.random.default_rng(SEED + 4).permutation(ps.size)
    kidx = np.repeat(np.arange(K), np.diff(ps.start))[perm]
    scn = fastrest.scene(list(zip(ps.eps_m, ps.nu_m)))
    tab = fastrest.load_table()
    o = np.empty(v.size)
    table_array(tab.data, 1, v, e, nu, o)
    keep = np.isfinite(o)
    v, e, nu, kidx = (np.ascontiguousarray(a[keep]) for a in (v, e, nu, kidx))
    n = v.size
    o = np.empty(n)
    cases = {
        "fastrest.e_star": ((lambda: fastrest.e_star(v, e, nu)), n),
        "fastrest.e_star, 1 Numba thread": (with_threads(1, lambda: fastrest.e_star(v, e, nu)), n),
        "e_table loop (jit) throughput": ((lambda: kernels.table_loop(tab.data, v, e, nu, o)), n),
        "e_table chain (jit) latency": ((lambda: kernels.table_chain(tab.data, v, e, nu)), n),
        "Scene.e (material index per point)": ((lambda: scn.e(v, kidx)), n),
        "e_scene loop (jit) throughput": ((lambda: kernels.scene_loop(scn.data, kidx, v, o)), n),
        "fit kernel (per-point eps_y)": ((lambda: models.jgm_fit_jcg_array(v, e, o)), n),
        "fit latency (jit chain)": ((lambda: kernels.fit_chain_mm(v, e)), n),
    }
    if not np.isfinite(kernels.table_chain(tab.data, v, e, nu)):
        raise RuntimeError("latency chain left the table's domain")
    log(f"  multi-material n = {n:.0e} ...")
    tm = interleaved(cases, cfg["rounds"], ref="fit kernel (per-point eps_y)", seed=9)
    res = {k: t.as_dict() for k, t in tm.items()}
    for k in ("e_table chain (jit) latency", "fit latency (jit chain)"):
        res[k]["ratio_to_ref"] = float(np.median(tm[k].per_eval / tm["fit latency (jit chain)"].per_eval))
    res["_n"] = n
    res["_dropped"] = int((~keep).sum())
    res["_parallel_min_points"] = getattr(tables, "PARALLEL_MIN_POINTS", None)
    return res


def curve_from_table(tab, eps_y, nu, bits=BITS_PER_OCTAVE):
    """The Curve of one material built from a multi-material table instead of the direct solver:
    the table evaluated at the curve's Chebyshev nodes, then the same per-cell fit."""
    def from_table(v):
        e_ = np.full(v.size, eps_y)
        n_ = np.full(v.size, nu)
        out = np.empty((3, v.size))
        for q in (0, 1, 2):
            table_array(tab.data, q, v, e_, n_, out[q])
        if not np.isfinite(out).all():
            raise RuntimeError("table refused a curve node")
        return out

    return Curve(eps_y, nu, "jcg", build_curve_data(eps_y, nu, "jcg", bits_per_octave=bits,
                                                     jg_values=from_table))


def build_times(cfg, log):
    """Default table generation/build, and one curve: from the direct solver vs from the table."""
    res = {}
    log("  default table: generate(None) ...")
    res["generate_default_s"] = repeated(lambda: tables.generate(None, progress=False),
                                         cfg["build_repeats"]).tolist()
    with tempfile.TemporaryDirectory() as d:
        log("  default table: build (generate + error measurement + HDF5 write) ...")
        res["build_default_s"] = repeated(lambda: tables.build(Path(d) / "t.h5", None, progress=False),
                                          1).tolist()
        res["file_mbytes"] = (Path(d) / "t.h5").stat().st_size / 2**20
    tab = fastrest.load_table()
    ps = point_set(1, cfg["curve_err_n"], seed=SEED + 5, hard=True)  # material 0 = CENTRE
    ref = reference(ps)
    variants = {
        "curve(0.005, 0.33) (direct solver, 2^5 cells/octave)": lambda: fastrest.curve(EPS, NU),
        "curve from the default table (same nodes)": lambda: curve_from_table(tab, EPS, NU),
        "curve(0.005, 0.33, v_max=200)": lambda: fastrest.curve(EPS, NU, v_max=200.0),
        "direct solver, 2^3 cells/octave": lambda: Curve(EPS, NU, "jcg", build_curve_data(EPS, NU, "jcg", bits_per_octave=3)),
    }
    errs = {}
    for name, f in variants.items():
        cv = f()
        m = ps.v <= cv.v_max
        errs[name] = {q: worst(getattr(cv, meth)(ps.v[m]), ref[q][m])[0]
                      for q, meth in (("e_jcg", "e"), ("omega_m", "omega_m"), ("loss_jcg", "loss"))}
        errs[name]["cells"] = int(cv.data.e_rows.shape[0])
        errs[name]["v_max"] = float(cv.v_max)
    log("  one curve ...")
    cases = {k: (f, 1) for k, f in variants.items()}
    v = _speeds(10**5, fastrest.limit(EPS, NU).v1_star)
    o = np.empty(v.size)
    cases["fit kernel, 1e5 points"] = ((lambda: models.jgm_fit_jcg_array(v, np.array([EPS]), o)), v.size)
    tm = interleaved(cases, cfg["curve_repeats"], min_block=0.0, seed=11)
    res["curve"] = {k: {**tm[k].as_dict(), **errs[k]} for k in variants}
    res["fit_per_eval_s"] = tm["fit kernel, 1e5 points"].median
    return res


def run(cfg, log=print):
    c = fastrest.curve(EPS, NU)
    c.e(5.0), c.e(np.array([5.0]))
    out = {}
    out["batch"] = batch_sizes(cfg, c, log)
    out["threads"] = threads(cfg, c, log)
    out["scalar"] = scalar(cfg, c, log)
    out["njit"] = in_njit(cfg, c, log)
    out["multi"] = multi_material(cfg, log)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.ValidityWarning)
        out["build"] = build_times(cfg, log)
    return out
