"""Part 3: the performance targets, met or not, with the measured figures."""
import math

from .timing import fmt_err, fmt_ratio, fmt_time

CURVE_DEFAULT = "curve(0.005, 0.33) (direct solver, 2^5 cells/octave)"


def _row(name, target, value, limit, measured, met=None, note=""):
    if met is None:
        met = value is not None and math.isfinite(value) and value <= limit
    return {"name": name, "target": target, "value": value, "limit": limit, "measured": measured,
            "fraction_of_target": (value / limit) if value is not None and limit else None,
            "met": bool(met), "note": note}


def evaluate(R):
    se, mo, fr = R["speed_error"], R["modes"], R["fresh"]
    rows = []

    # 1. batch over 1e6 points vs the fit
    batch = mo["batch"]
    n = 10**6 if 10**6 in batch else max(k for k in batch if k <= 10**6)
    b = batch[n]
    r = b["Curve.e"]["ratio_to_ref"]
    rows.append(_row(
        f"Curve.e batch, {n:.0e} points", "<= 1/3 of the closed-form fit's time", r, 1 / 3,
        f"{fmt_time(b['Curve.e']['median_s'], 'ns')}/point vs fit {fmt_time(b['fit']['median_s'], 'ns')}/point: "
        f"{r:.3f}x the fit (ratio of minima {b['Curve.e']['ratio_of_minima']:.3f}x)",
        note="" if n == 10**6 else "quick run: largest n measured"))

    # 2. multi-material speed
    m = mo["multi"]
    t = m["fastrest.e_star"]["median_s"]
    one = m["fastrest.e_star, 1 Numba thread"]
    pm = m.get("_parallel_min_points")
    rows.append(_row(
        f"multi-material fastrest.e_star, {m['_n']:.0e} points", "<= 100 ns/point", t * 1e9, 100.0,
        f"{fmt_time(t, 'ns')}/point (min {fmt_time(m['fastrest.e_star']['min_s'], 'ns')}), "
        f"{fmt_ratio(m['fastrest.e_star']['ratio_to_ref'])} the fit"
        + (f", using {mo['threads']['max_threads']} threads (batches >= {pm:,} points)" if pm else "")
        + f"; on 1 thread {fmt_time(one['median_s'], 'ns')}/point ({fmt_ratio(one['ratio_to_ref'])}); "
        f"jit e_table loop {fmt_time(m['e_table loop (jit) throughput']['median_s'], 'ns')}/point"))

    # 3. scalar from Python
    s = mo["scalar"]["Curve.e(5.0)"]
    rows.append(_row("scalar Curve.e(5.0) from Python", "<= 300 ns", s["median_s"] * 1e9, 300.0,
                     f"{fmt_time(s['median_s'], 'ns')} (min {fmt_time(s['min_s'], 'ns')}), "
                     f"{fmt_ratio(s['ratio_to_ref'])} the fit's scalar call"))

    # 4. inside njit
    j = mo["njit"]
    for key, label in (("e_curve throughput", "throughput, independent calls"),
                       ("e_curve latency", "latency, dependent chain")):
        x = j[key]
        rows.append(_row(f"e_curve inside @njit ({label})", "<= 15 ns per call", x["median_s"] * 1e9, 15.0,
                         f"{fmt_time(x['median_s'], 'ns')} (min {fmt_time(x['min_s'], 'ns')}), "
                         f"{fmt_ratio(x['ratio_to_ref'])} the fit's {label.split(',')[0]}"))

    # 5. table build
    bt = mo["build"]
    import numpy as np
    tb = float(np.median(bt["build_default_s"]))
    tg = float(np.median(bt["generate_default_s"]))
    rows.append(_row("default table build", "<= 60 s", tb, 60.0,
                     f"{tb:.2f} s for fastrest.tables.build (generation alone {tg:.2f} s)"))
    mb = bt["file_mbytes"]
    rows.append(_row("default table file", "a few MB at most (read here as <= 5 MiB)", mb, 5.0,
                     f"{mb:.2f} MiB (HDF5, contiguous, uncompressed)"))

    # 6. one curve
    c = bt["curve"][CURVE_DEFAULT]
    rows.append(_row("one curve after compilation", "<= 50 ms", c["median_s"] * 1e3, 50.0,
                     f"{fmt_time(c['median_s'], 'ms')} (min {fmt_time(c['min_s'], 'ms')}), full range "
                     f"V1* <= {c['v_max']:.0f}, {c['cells']} cells"))

    # 7. first use with a warm cache
    for name, r in fr["first_use"].items():
        if name.startswith("_"):
            continue
        w = r["warm"]
        rows.append(_row(f"first use, warm cache: {name}", "<= 1 s", w["wall_median_s"], 1.0,
                         f"{w['wall_median_s']:.2f} s whole process (import + call inside it "
                         f"{w['inside_median_s']:.2f} s; empty cache {r['cold']['wall_median_s']:.2f} s)"
                         if r["cold"]["runs"] else f"{w['wall_median_s']:.2f} s"))
        if fr["first_use"].get("_numba_floor_s") is not None and w.get("ratio_to_floor") is not None:
            rows[-1]["measured"] += (f"; Numba's own floor {fr['first_use']['_numba_floor_s']:.2f} s, "
                                     f"fastrest {w['ratio_to_floor']:.2f}x it")

    # 8. Curve accuracy
    ce = se["curve_errors"][5] if 5 in se["curve_errors"] else se["curve_errors"]["5"]
    for q, lim in (("e_jcg", 1e-12), ("omega_m", 1e-12), ("loss_jcg", 1e-10)):
        x = ce[q]
        rows.append(_row(f"Curve accuracy, {q}", f"<= {lim:.0e}", x["max_rel_error"], lim,
                         f"{fmt_err(x['max_rel_error'])} worst relative (at V1* = {x['at_v1_star']:.6g}, "
                         f"eps_y = {x['at_eps_y']:.4g}, nu = {x['at_nu']:.3g})"))

    # 9. multi-material accuracy
    te = se["table_errors"]["default"]
    for q in ("omega_m", "e_jcg", "loss_jcg", "e_etsion", "loss_etsion"):
        x = te[q]
        extra = " (relative to max(|1 - e^2|, 1e-3))" if q == "loss_etsion" else ""
        ref = f"; {x['refused']} hard-case points refused" if x["refused"] else ""
        rows.append(_row(f"multi-material accuracy, {q}", "<= 1e-09", x["max_rel_error"], 1e-9,
                         f"{fmt_err(x['max_rel_error'])} worst relative{extra} (at V1* = "
                         f"{x['at_v1_star']:.6g}, eps_y = {x['at_eps_y']:.4g}, nu = {x['at_nu']:.3g}){ref}"))
    return rows
