"""Writing bench/RESULTS.md, bench/readme_table.md, and the README's benchmark section."""
import json
import os
import platform
import re
import subprocess
from pathlib import Path

import numpy as np

from .results_md import md_table, median, ns, results_md
from .timing import fmt_err, fmt_ratio, fmt_time

#: The repository's root (README.md, bench/).
REPO = Path(__file__).resolve().parent.parent
#: Markers of the README's benchmark block, which :func:`update_readme` replaces.
START, END = "<!-- bench:start -->", "<!-- bench:end -->"

#: The stored search for the worst errors of curves and the direct solver (``python -m bench.stated_figures``).
STATED = REPO / "bench" / "stated_figures.json"

__all__ = ["REPO", "START", "END", "STATED", "machine", "versions", "apply_search", "headline", "write_all",
           "update_readme", "rerender"]


# --- environment ------------------------------------------------------------------------------------

def machine():
    info = {"cpu": platform.processor() or platform.machine(), "flags": []}
    try:
        text = Path("/proc/cpuinfo").read_text()
        m = re.search(r"^model name\s*:\s*(.+)$", text, re.M)
        if m:
            info["cpu"] = m.group(1).strip()
        m = re.search(r"^flags\s*:\s*(.+)$", text, re.M)
        flags = set(m.group(1).split()) if m else set()
        info["flags"] = sorted(f for f in ("avx2", "fma", "avx512f", "avx512dq", "avx512vl") if f in flags)
        info["cpu_logical_in_cpuinfo"] = len(re.findall(r"^processor\s*:", text, re.M))
        for key in ("cpu family", "model", "cache size"):
            m = re.search(rf"^{key}\s*:\s*(.+)$", text, re.M)
            if m:
                info[key.replace(" ", "_")] = m.group(1).strip()
    except OSError:
        pass
    try:
        info["nproc"] = int(subprocess.run(["nproc"], capture_output=True, text=True).stdout.strip())
    except (OSError, ValueError):
        info["nproc"] = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    try:
        m = re.search(r"^MemTotal:\s*(\d+) kB", Path("/proc/meminfo").read_text(), re.M)
        info["mem_gib"] = int(m.group(1)) / 2**20
    except (OSError, AttributeError):
        info["mem_gib"] = None
    info["os"] = platform.platform()
    return info


def versions():
    import h5py
    import llvmlite
    import matplotlib
    import numba
    import scipy

    import fastrest
    v = {"python": platform.python_version(), "numpy": np.__version__, "numba": numba.__version__,
         "llvmlite": llvmlite.__version__, "scipy": scipy.__version__, "h5py": h5py.__version__,
         "matplotlib": matplotlib.__version__, "fastrest": fastrest.__version__}
    try:
        rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPO, capture_output=True,
                             text=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--", "fastrest", "tables"], cwd=REPO,
                               capture_output=True, text=True).stdout.strip()
        v["git"] = rev + (" (uncommitted changes in fastrest/ or tables/)" if dirty else "") if rev else "unknown"
    except OSError:
        v["git"] = "unknown"
    v["numba_threads"] = numba.config.NUMBA_NUM_THREADS
    v["numba_cache_dir"] = os.environ.get("NUMBA_CACHE_DIR", "(default: __pycache__ next to the sources)")
    return v


# --- tables ------------------------------------------------------------------------------------------


def _stored_table_error():
    """The shipped table's stored measured error (quantity -> dict), {} if unreadable."""
    try:
        import fastrest

        return dict(fastrest.load_table().attrs.get("measured_error") or {})
    except Exception:  # a report from results.json alone still renders
        return {}


def apply_search(R, path=STATED):
    """Fold the stored search (bench/stated_figures.json) into R's sampled errors of the default curve
    and the direct solver: a stated error is the worst found, the sample's and the search's together.
    Curves: e and w_m* over every unloading model, 1 - e^2 of JCG (relative). The direct solver: the
    search's figure to state (its worst ulp count plus a margin for another libm, x 2^-52)."""
    try:
        S = json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return R
    se = R["speed_error"]
    ce = se["curve_errors"][5]
    by = {m["key"]: m for m in se["methods"]}
    if "curve" in S:
        models = S["curve"]["models"]
        for q, sq, names in (("e_jcg", "e", list(models)), ("omega_m", "omega_m", list(models)),
                             ("loss_jcg", "loss", ["jcg"])):
            m = max(names, key=lambda k: models[k][sq]["error"])
            r = models[m][sq]
            if r["error"] > ce[q]["max_rel_error"]:
                v, e, n = r["at"]
                ce[q] = {"max_rel_error": r["error"], "at_v1_star": v, "at_eps_y": e, "at_nu": n,
                         "found_by": f"search ({m} curve, bench/STATED_FIGURES.md)"}
        if "curve_5" in by:
            by["curve_5"]["error"] = max(by["curve_5"]["error"], ce["e_jcg"]["max_rel_error"])
            by["curve_5"]["error_of"] = "vs direct: worst of the sample and the search (every model)"
    if "direct" in S and "direct" in by:
        d = S["direct"]["e"]
        old = se.get("direct_vs_mpmath") or {"max_rel_error": 0.0, "points": 0}
        bound = max(d.get("stated", d["stated_bound"]), old["max_rel_error"] or 0.0)
        se["direct_vs_mpmath"] = {"max_rel_error": bound, "points": old["points"] + d["points"],
                                  "worst_ulp": d["ulp"], "found_by": "search (bench/STATED_FIGURES.md)"}
        by["direct"]["error"] = bound
        by["direct"]["error_of"] = (f"vs 40-digit mpmath, {d['points']} points searched, worst {d['ulp']:.0f} ulp "
                                    "(stated: 4 ulp more, just above a power of two)")
    R["stated_search"] = {"date": S.get("date"), "quick": S.get("quick")}
    return R


def headline(R):
    """The short table for the README (<= 12 rows)."""
    se, mo, fr = R["speed_error"], R["modes"], R["fresh"]
    by = {m["key"]: m for m in se["methods"]}
    batch = mo["batch"]
    n = 10**6 if 10**6 in batch else max(k for k in batch if k <= 10**6)
    b = batch[n]
    j, mm, sc, bt = mo["njit"], mo["multi"], mo["scalar"], mo["build"]
    ce = se["curve_errors"][5]
    te = se["table_errors"]["default"]
    fit = by["fit4344_numba"]
    cv = bt["curve"]["curve(0.005, 0.33) (direct solver, 2^5 cells/octave)"]
    warm = fr["first_use"]["fastrest.e_star(5.0, 0.005, 0.33)"]["warm"]
    warm_c = fr["first_use"]["fastrest.curve(0.005, 0.33).e(5.0)"]["warm"]
    # the bench's random sample, or the worst the table's build found (sample and local search,
    # fastrest.tables.error, stored in the file) if larger: a stated error is the worst found
    me = _stored_table_error()
    te_e = max([te[q]["max_rel_error"] for q in ("e_jcg", "e_etsion")]
               + [me[q]["max_error"] for q in ("e_jcg", "e_etsion", "e_brake") if q in me])
    te_w = max([te["omega_m"]["max_rel_error"]] + [me[q]["max_error"] for q in ("omega_m_star",) if q in me])
    te_loss = max(te["loss_jcg"]["max_rel_error"], me.get("loss_jcg", {}).get("max_error", 0.0))
    rows = [
        [f"`Curve.e(v)`, one material, batch of {n:.0e}", f"{ns(b['Curve.e']['median_s'])}/point",
         fmt_ratio(b["Curve.e"]["ratio_to_ref"]),
         f"{fmt_err(max(ce['e_jcg']['max_rel_error'], ce['omega_m']['max_rel_error']))} (e, w_m*), "
         f"{fmt_err(ce['loss_jcg']['max_rel_error'])} (1 - e^2)"],
        ["`Curve.e(5.0)`, scalar from Python", ns(sc["Curve.e(5.0)"]["median_s"]),
         fmt_ratio(sc["Curve.e(5.0)"]["ratio_to_ref"]), "same"],
        ["`fastrest.jit.e_curve` in your `@njit` loop (throughput / latency)",
         f"{ns(j['e_curve throughput']['median_s'])} / {ns(j['e_curve latency']['median_s'])}",
         f"{fmt_ratio(j['e_curve throughput']['ratio_to_ref'])} / {fmt_ratio(j['e_curve latency']['ratio_to_ref'])}",
         "same"],
        [f"`fastrest.e_star(v, eps_y, nu)`, every point its own material, {mm['_n']:.0e} "
         f"({mo['threads']['max_threads']} threads / 1 thread)",
         f"{ns(mm['fastrest.e_star']['median_s'])} / {ns(mm['fastrest.e_star, 1 Numba thread']['median_s'])} per point",
         f"{fmt_ratio(mm['fastrest.e_star']['ratio_to_ref'])} / "
         f"{fmt_ratio(mm['fastrest.e_star, 1 Numba thread']['ratio_to_ref'])}",
         f"{fmt_err(te_e)} (e), {fmt_err(te_w)} (w_m*), {fmt_err(te_loss)} (1 - e^2, JCG)"],
        ["`fastrest.jit.e_table` in your `@njit` loop (throughput / latency)",
         f"{ns(mm['e_table loop (jit) throughput']['median_s'])} / {ns(mm['e_table chain (jit) latency']['median_s'])}",
         f"{fmt_ratio(mm['e_table loop (jit) throughput']['ratio_to_ref'])} / "
         f"{fmt_ratio(mm['e_table chain (jit) latency']['ratio_to_ref'])}", "same"],
        [f"`fastrest.scene(...)`: `Scene.e(v, k)` / `fastrest.jit.e_material` in your loop, {mm['_n']:.0e} points, "
         "material index per point",
         f"{ns(mm['Scene.e (material index per point)']['median_s'])} / "
         f"{ns(mm['e_scene loop (jit) throughput']['median_s'])} per point",
         f"{fmt_ratio(mm['Scene.e (material index per point)']['ratio_to_ref'])} / "
         f"{fmt_ratio(mm['e_scene loop (jit) throughput']['ratio_to_ref'])}", "as `Curve`"]
        if "Scene.e (material index per point)" in mm else None,
        ["`fastrest.direct.e_exact` (exact solver)", f"{fmt_time(by['direct']['time_median'], 'us')}/point",
         fmt_ratio(by["direct"]["ratio"]),
         f"{fmt_err(by['direct']['error'])} (vs 40-digit mpmath)" if by["direct"]["error"] is not None else "reference"],
        ["JGM closed-form fit (43)-(44), Numba (the speed reference)", f"{ns(fit['time_median'])}/point", "1x",
         f"{fit['error'] * 100:.1f} % (deviation from the model)"],
        ["build the default table (`fastrest build --default`)", f"{median(bt['build_default_s']):.1f} s", "", ""],
        ["build one curve, full range (`fastrest.curve(0.005, 0.33)`)", fmt_time(cv["median_s"], "ms"), "", ""],
        ["first use in a fresh process, warm Numba cache (`e_star` / `curve`)",
         f"{warm['wall_median_s']:.2f} s / {warm_c['wall_median_s']:.2f} s"
         + (f" (Numba's floor: {fr['first_use']['_numba_floor_s']:.2f} s)"
            if fr["first_use"].get("_numba_floor_s") is not None else ""), "", ""],
    ]
    rows = [r for r in rows if r is not None]
    head = ["", "time (median)", "x closed-form fit", "worst relative error"]
    simd = " (AVX-512)" if "avx512f" in R["machine"].get("flags", []) else ""
    # the targets met are in RESULTS.md: the README's caption names the machine only
    caption = f"{R['machine']['nproc']}-core {R['machine']['cpu']}{simd}, {R['date'][:10]}, medians of interleaved rounds."
    return md_table(head, rows) + "\n\n" + caption + "\n"



def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, float) and not np.isfinite(o):
        return None
    return o


def write_all(R, out_dir):
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    (out_dir / "readme_table.md").write_text(R["headline"])
    (out_dir / "RESULTS.md").write_text(results_md(R))
    (out_dir / "results.json").write_text(json.dumps(_jsonable(R), indent=1))


def _int_keys(d):
    return {int(k): v for k, v in d.items()}


def rerender(out_dir=REPO / "bench", log=print):
    """Render RESULTS.md, readme_table.md, results.json and the plot again from the stored
    results.json with the stored search folded in: no timing is rerun."""
    from . import targets
    from .speed_error import plot

    out_dir = Path(out_dir)
    R = json.loads((out_dir / "results.json").read_text())
    se, mo = R["speed_error"], R["modes"]
    se["curve_errors"] = _int_keys(se["curve_errors"])
    mo["batch"] = _int_keys(mo["batch"])
    mo["threads"]["sizes"] = _int_keys(mo["threads"]["sizes"])
    apply_search(R)
    R["targets"] = targets.evaluate(R)
    R["headline"] = headline(R)
    plot(se, out_dir / "speed_vs_error.png")
    write_all(R, out_dir)
    log(f"rendered {out_dir / 'RESULTS.md'}, {out_dir / 'readme_table.md'} and the plot from the stored results")
    return R


def update_readme(readme=REPO / "README.md", out_dir=REPO / "bench", force=False):
    """Replace the text between the bench markers of README.md with readme_table.md and links."""
    readme, out_dir = Path(readme), Path(out_dir)
    table = out_dir / "readme_table.md"
    if not table.exists():
        raise FileNotFoundError(f"{table} does not exist: run `python -m bench` first")
    meta = out_dir / "results.json"
    if meta.exists() and not force:
        R = json.loads(meta.read_text())
        if R.get("quick"):
            raise ValueError(f"{table} comes from a --quick run; run the full `python -m bench` "
                             "(or pass --force)")
    text = readme.read_text()
    if text.count(START) != 1 or text.count(END) != 1 or text.index(START) > text.index(END):
        raise ValueError(f"{readme} must contain {START} ... {END} exactly once")
    rel = Path(os.path.relpath(out_dir, readme.parent)).as_posix()
    block = (f"{START}\n{table.read_text().strip()}\n\nGenerated by `python -m bench`. Method, every "
             f"measurement and the targets: [{rel}/RESULTS.md]({rel}/RESULTS.md); speed against error: "
             f"[{rel}/speed_vs_error.png]({rel}/speed_vs_error.png).\n{END}")
    new = text[:text.index(START)] + block + text[text.index(END) + len(END):]
    readme.write_text(new)
    return new
