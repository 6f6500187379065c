"""Writing bench/RESULTS.md, bench/readme_table.md, and the README's benchmark section."""
import json
import os
import platform
import re
import subprocess
from pathlib import Path

import numpy as np

from .timing import fmt_err, fmt_ratio, fmt_time

REPO = Path(__file__).resolve().parent.parent
START, END = "<!-- bench:start -->", "<!-- bench:end -->"


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

def md_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def load_note(d):
    """A sentence on competing processes during a group of rounds (from any Timing dict of the group)."""
    x = d.get("other_cores") if isinstance(d, dict) else None
    if x is None:
        return ""
    k = d.get("attempts", 1)
    att = f" (the least disturbed of {k} attempts)" if k > 1 else ""
    if x < 0.1:
        return f"Other processes during these rounds: {x:.2f} cores (quiet){att}."
    return (f"**Other processes kept {x:.2f} cores busy during these rounds**{att}: these times are "
            "pessimistic (2-thread figures most).")


def other_col(d):
    x = d.get("other_cores")
    k = d.get("attempts", 1)
    return "-" if x is None else f"{x:.2f}" + (f" ({k} attempts)" if k > 1 else "")


def ns(s):
    return fmt_time(s, "ns")


def t2(d):
    """'median (min)' of a Timing dict, in a fitting unit."""
    return f"{fmt_time(d['median_s'])} ({fmt_time(d['min_s'])})"


def _med(a):
    return float(np.median(a))


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
    te_max = max(te[q]["max_rel_error"] for q in ("omega_m", "e_jcg", "e_etsion"))
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
         f"{fmt_err(te_max)} (w_m*, e), {fmt_err(te['loss_jcg']['max_rel_error'])} (1 - e^2, JCG)"],
        ["`fastrest.jit.e_table` in your `@njit` loop (throughput / latency)",
         f"{ns(mm['e_table loop (jit) throughput']['median_s'])} / {ns(mm['e_table chain (jit) latency']['median_s'])}",
         f"{fmt_ratio(mm['e_table loop (jit) throughput']['ratio_to_ref'])} / "
         f"{fmt_ratio(mm['e_table chain (jit) latency']['ratio_to_ref'])}", "same"],
        [f"`fastrest.scene(...)`: `Scene.e(v, k)` / `fastrest.jit.e_scene` in your loop, {mm['_n']:.0e} points, "
         "material index per point",
         f"{ns(mm['Scene.e (material index per point)']['median_s'])} / "
         f"{ns(mm['e_scene loop (jit) throughput']['median_s'])} per point",
         f"{fmt_ratio(mm['Scene.e (material index per point)']['ratio_to_ref'])} / "
         f"{fmt_ratio(mm['e_scene loop (jit) throughput']['ratio_to_ref'])}", "as `Curve`"]
        if "Scene.e (material index per point)" in mm else None,
        ["`fastrest.direct.e_star` (exact solver)", f"{fmt_time(by['direct']['time_median'], 'us')}/point",
         fmt_ratio(by["direct"]["ratio"]),
         f"{fmt_err(by['direct']['error'])} (vs 40-digit mpmath)" if by["direct"]["error"] is not None else "reference"],
        ["JGM closed-form fit (43)-(44), Numba (the speed reference)", f"{ns(fit['time_median'])}/point", "1x",
         f"{fit['error'] * 100:.1f} % (deviation from the model)"],
        ["build the default table (`fastrest build --default`)", f"{_med(bt['build_default_s']):.1f} s", "", ""],
        ["build one curve, full range (`fastrest.curve(0.005, 0.33)`)", fmt_time(cv["median_s"], "ms"), "", ""],
        ["first use in a fresh process, warm Numba cache (`e_star` / `curve`)",
         f"{warm['wall_median_s']:.2f} s / {warm_c['wall_median_s']:.2f} s"
         + (f" (Numba's floor: {fr['first_use']['_numba_floor_s']:.2f} s)"
            if fr["first_use"].get("_numba_floor_s") is not None else ""), "", ""],
    ]
    rows = [r for r in rows if r is not None]
    met = sum(t["met"] for t in R["targets"])
    head = ["", "time (median)", "x closed-form fit", "worst relative error"]
    caption = (f"{R['machine']['nproc']}-core {R['machine']['cpu']}, {R['date'][:10]}, medians of interleaved rounds; "
               f"the issue's targets: {met} of {len(R['targets'])} met.")
    return md_table(head, rows) + "\n\n" + caption + "\n"


def _spec_table(se):
    rows = []
    for m in se["methods"]:
        extra = ""
        if m["kind"] == "table":
            extra = f"{m['mbytes']:.1f} MiB"
        elif m["kind"] == "curve":
            extra = f"{m['cells_centre_material']} cells (centre material)"
        rows.append([("**" + m["label"] + "**") if m["default"] else m["label"],
                     ns(m["time_median"]), ns(m["time_min"]),
                     fmt_ratio(m["ratio"]), fmt_err(m["error"]) if m["error"] is not None else "-",
                     m["error_of"], extra])
    return md_table(["method", "ns/eval (median)", "min", "x fit (median of per-round ratios)",
                     "worst rel. error", "error measured", "size"], rows)


def results_md(R):
    se, mo, fr, mem = R["speed_error"], R["modes"], R["fresh"], R["memory"]
    ma, ve = R["machine"], R["versions"]
    L = []
    a = L.append
    a("# fastrest benchmark results\n")
    a(f"Generated by `{R['command']}` on {R['date']} in {R['elapsed_s']:.0f} s "
      f"({'QUICK run: small n, few repeats; not for quoting' if R['quick'] else 'full run'}).\n")
    a("## Machine and software\n")
    a(f"* CPU: {ma['cpu']} (family {ma.get('cpu_family', '?')}, model {ma.get('model', '?')}; "
      f"{', '.join(ma['flags']) or 'no AVX flags found'}), `nproc` = {ma['nproc']}, "
      f"memory {ma['mem_gib']:.1f} GiB; {ma['os']}")
    a("* " + ", ".join(f"{k} {ve[k]}" for k in ("python", "numpy", "numba", "llvmlite", "scipy", "h5py",
                                                "matplotlib")))
    a(f"* fastrest {ve['fastrest']} (git {ve['git']}); Numba threads {ve['numba_threads']}; "
      f"Numba cache {ve['numba_cache_dir']}")
    ld = R.get("load") or {}
    if ld.get("other_cores") is not None:
        busy = ld["other_cores"] > 0.1
        a(f"* Other processes used {ld['other_cpu_s']:.0f} CPU-seconds during the run, on average "
          f"{ld['other_cores']:.2f} of the {ma['nproc']} cores" + (
              ": they competed for the cores, so absolute times (and the 2-thread figures most) are "
              "pessimistic" if busy else " (a quiet machine)")
          + f"; load average at the start {ld['start']}, at the end {ld['end']}.")
    po = R.get("policy")
    if po and po["budget"] > 0:
        a(f"* Shared machine: before each group of timed rounds the run waited (up to {po['max_wait']:.0f} s) for "
          f"other processes to leave the cores idle, and repeated a group (up to {po['retries']} times) when they "
          f"used more than {po['threshold']} cores during it, keeping the least disturbed attempt; "
          f"{po['spent_s']:.0f} s of the run went to this (budget {po['budget']:.0f} s).")
    oc = R.get("section_other_cores", {})
    a("* Sections: " + ", ".join(f"{k} {v:.0f} s" + (f" (other processes: {oc[k]:.2f} cores)" if oc.get(k) is not None else "")
                                 for k, v in R.get("section_s", {}).items()))
    a("")
    a("## How the numbers were taken\n")
    a("This machine alternates between a fast and a slow state about 1.85x apart every 0.5-2 s "
      "(measured before the project started). So every kernel is compiled and called once before timing "
      "(warm-up excluded); then the methods of one comparison run in interleaved rounds (order shuffled "
      "each round, each method a block of >= 2 ms), and each time is the **median** over rounds with "
      "the **minimum** beside it. Every time is also given as a ratio to JGM's closed-form fit (43)-(44) "
      "measured in the same rounds (`fastrest.models.jgm_fit_jcg_array` for batches; the fit's scalar "
      "kernel for calls inside `@njit` and from Python): the median over rounds of the per-round ratio, "
      "which cancels most of the machine's state changes. Absolute times can move by ~1.85x between runs; "
      "ratios are the figures to compare. Errors are worst relative errors against the direct solver "
      "(`fastrest.direct`) at random points of the validated domain (0.0005 <= eps_y <= 0.01, "
      "0.2 <= nu <= 0.45, 1 <= V1* <= V1*(w_m* = 425), log-uniform in V1*; fixed seed) plus hard cases "
      "(V1* -> 1, both sides of 1.9^1.25, V1*_max).\n")
    a("## Headline\n")
    a(R["headline"])
    a("## 1. Speed against error\n")
    a("![speed against error](speed_vs_error.png)\n")
    a(f"{se['n_materials']} materials (the 4 corners of the validated (eps_y, nu) rectangle, the centre "
      f"eps_y = 0.005, nu = 0.33, and random ones); timing on {se['n_time']:,} points "
      f"(direct solver: the first {se['n_direct']:,}), errors on {se['n_err']:,} of them plus hard cases; "
      f"{se['rounds']} interleaved rounds. Curves evaluate each material's points with that material's "
      "`Curve`; tables, fits and the direct solver take the points in random order, each with its own "
      "material. Every path is called through its public batch API (validation, output allocation "
      "included)." + (f" {se['dropped_timing_points']} timing points within a coarse table's error of the "
                      "w_m* = 425 limit were dropped for all methods." if se["dropped_timing_points"] else "")
      + "\n")
    a(_spec_table(se))
    a("\n" + load_note(se["methods"][0].get("timing", {})))
    a("")
    a("### Error details: curves (one curve per material, against the direct solver)\n")
    rows = []
    for bits, ce in sorted(se["curve_errors"].items()):
        rows.append([f"2^{bits} cells/octave" + (" (default)" if bits == 5 else ""),
                     fmt_err(ce["e_jcg"]["max_rel_error"]), fmt_err(ce["omega_m"]["max_rel_error"]),
                     fmt_err(ce["loss_jcg"]["max_rel_error"])])
    a(md_table(["Curve", "e (JCG)", "w_m*", "1 - e^2 (JCG)"], rows))
    a("")
    a("### Error details: multi-material tables\n")
    rows = []
    for name, te in se["table_errors"].items():
        refused = max(x["refused"] for x in te.values())
        rows.append([name + (" (shipped)" if name == "default" else "")]
                    + [fmt_err(te[q]["max_rel_error"]) for q in ("omega_m", "e_jcg", "loss_jcg", "e_etsion",
                                                                 "loss_etsion")]
                    + [str(refused)])
    a(md_table(["table (n_eps_y x n_nu, 2^K cells/octave)", "w_m*", "e (JCG)", "1 - e^2 (JCG)",
                "e (Etsion)", "1 - e^2 (Etsion)*", "points refused"], rows))
    a("\n\\* relative to max(|1 - e^2|, 1e-3) (it changes sign). Refused points: hard-case speeds at "
      "V1*_max, which a table refuses when its interpolated w_m* exceeds 425 by more than 1e-9 (relative); "
      "they are excluded from that table's error.\n")
    fe, fw = se["fit_errors"], se["fit_where"]

    def at(w):
        return f"at V1* = {w['at_v1_star']:.4g}, eps_y = {w['at_eps_y']:.3g}, nu = {w['at_nu']:.3g}"
    a(f"The paper's fits against the model (worst relative deviation of e): (42)-(44) {fe['fit4344'] * 100:.2f} % "
      f"for V1* <= 1000 ({at(fw['fit4344'])}; JGM state 4.5 % at most), (45) {fe['fit45'] * 100:.2f} % "
      f"({at(fw['fit45'])}; JGM state 8.4 % at most).\n")

    a("## 2. Modes\n")
    a("### Batch `Curve.e` against n (one material, eps_y = 0.005, nu = 0.33, V1* log-uniform up to "
      "V1*_max)\n")
    rows = []
    for n, b in sorted(mo["batch"].items()):
        rows.append([f"{n:.0e}", t2ns(b["Curve.e"]), fmt_ratio(b["Curve.e"]["ratio_to_ref"]),
                     t2ns(b["curve_loop"]), fmt_ratio(b["curve_loop"]["ratio_to_ref"]),
                     t2ns(b["fit"]), t2ns(b["copy"]), other_col(b["fit"])])
    a(md_table(["n", "`Curve.e(v)` ns/point", "x fit", "jit loop into a preallocated array", "x fit",
                "fit kernel", "memory copy", "other processes (cores)"], rows))
    a("\n`Curve.e(v)` includes the Python call, output allocation and the NaN check; the jit loop is "
      "`out[i] = fastrest.jit.e_curve(data, v[i])` in an `@njit` function.\n")
    th = mo["threads"]
    a(f"### Threads (prange loop calling `fastrest.jit.e_curve`; Numba's maximum here: {th['max_threads']})\n")
    rows = []
    for n, d in sorted(th["sizes"].items()):
        for k, x in d.items():
            rows.append([f"{n:.0e}", k, t2ns(x), fmt_ratio(x["ratio_to_ref"]), other_col(x)])
    a(md_table(["n", "loop", "ns/point (median (min))", "x fit", "other processes (cores)"], rows))
    a("")
    a("### Scalar calls from Python (timeit loops; ns per call)\n")
    rows = [[f"`{k}`", t2ns(x), fmt_ratio(x["ratio_to_ref"])] for k, x in mo["scalar"].items()]
    a(md_table(["call", "ns/call (median (min))", "x fit's scalar call (Numba dispatcher)"], rows))
    a("\n" + load_note(next(iter(mo["scalar"].values()))))
    a("")
    j = mo["njit"]
    a(f"### Inside a user's `@njit` loop ({j['_n']:.0e} calls)\n")
    rows = [[k, t2ns(x), fmt_ratio(x["ratio_to_ref"])] for k, x in j.items() if not k.startswith("_")]
    a(md_table(["", "ns/call (median (min))", "x fit (same kind: throughput or latency)"], rows))
    a("\n" + load_note(j["fit throughput"]))
    a("\nThroughput: `out[i] = e_curve(data, v[i])`; latency: `x = e_curve(data, v[i] - 1e-9 * x)`, each "
      "call waiting for the previous result. The fit's loops are the same with "
      "`jgm_fit_jcg_kernel(v, eps_y)`.\n")
    mm = mo["multi"]
    a(f"### Multi-material points ({mm['_n']:.0e} points in random order, each its own material; default "
      "table)\n")
    rows = [[k, t2ns(x), fmt_ratio(x["ratio_to_ref"])] for k, x in mm.items() if not k.startswith("_")]
    a(md_table(["", "ns/point (median (min))", "x fit (latency rows: x the fit's latency)"], rows))
    a("\n" + load_note(mm["fastrest.e_star"]))
    if mm.get("_parallel_min_points"):
        a(f"\n`fastrest.e_star` runs its loop on all Numba threads ({mo['threads']['max_threads']} here) for "
          f"batches of >= {mm['_parallel_min_points']:,} points; the `@njit` loops and the fit are single-threaded.")
    a("")
    bt = mo["build"]
    fit_s = bt["fit_per_eval_s"]
    a("### Table build and one curve\n")
    g, b = bt["generate_default_s"], bt["build_default_s"]
    a(md_table(["", "median", "min", "runs", "= fit evaluations"], [
        ["default table, `fastrest.tables.generate(None)` (compute only)", f"{_med(g):.2f} s",
         f"{min(g):.2f} s", len(g), f"{_med(g) / fit_s:.2g}"],
        ["default table, `fastrest.tables.build` (compute + error check + HDF5 write)", f"{_med(b):.2f} s",
         f"{min(b):.2f} s", len(b), f"{_med(b) / fit_s:.2g}"],
    ]))
    a(f"\nFile size {bt['file_mbytes']:.1f} MiB. \"= fit evaluations\": the time divided by one evaluation of "
      f"the closed-form fit ({ns(fit_s)}, same run).\n")
    rows = []
    for k, x in bt["curve"].items():
        rows.append([k, t2(x), f"{x['median_s'] / fit_s:.2g}", x["cells"], f"{x['v_max']:.0f}",
                     fmt_err(x["e_jcg"]), fmt_err(x["omega_m"]), fmt_err(x["loss_jcg"])])
    a(md_table(["one curve, eps_y = 0.005, nu = 0.33", "time (median (min))", "= fit evaluations", "cells",
                "V1* max", "error e", "error w_m*", "error 1 - e^2"], rows))
    a("\n\"From the default table\" evaluates the table at the curve's Chebyshev nodes and fits the same "
      "cells; it inherits the table's error. Errors against the direct solver at random V1* of that "
      "material plus hard cases.\n")
    a("### First use in a fresh process\n")
    a("Warm cache: after `fastrest warmup` (run once before these runs; nothing else warms the cache).\n")
    rows = []
    for name, r in fr["first_use"].items():
        if name.startswith("_"):
            continue
        for cache in ("warm", "cold"):
            x = r[cache]
            if not x["runs"]:
                continue
            rows.append([f"`{name}`", "warm cache" if cache == "warm" else "empty NUMBA_CACHE_DIR", x["runs"],
                         f"{x['wall_median_s']:.2f} s ({x['wall_min_s']:.2f} s)", f"{x['import_median_s']:.2f} s",
                         f"{x['call_median_s']:.2f} s", f"{x['wall_median_s'] / fit_s:.2g}"])
    a(md_table(["first call", "Numba cache", "runs", "whole process, median (min)", "import fastrest",
                "first call", "= fit evaluations"], rows))
    a(f"\nA process that only imports numpy takes {fr['first_use']['_python_numpy_startup_s']:.2f} s here.")
    if fr["first_use"].get("_numba_floor_s") is not None:
        ratios = ", ".join(f"`{k}` {r['warm']['ratio_to_floor']:.2f}x" for k, r in fr["first_use"].items()
                           if not k.startswith("_") and r["warm"].get("ratio_to_floor") is not None)
        a(f"Numba's own floor, a process that imports numpy, h5py and numba and calls one cached "
          f"`@njit` function (the first call loads Numba's typing and target registries, and Numba "
          f"imports scipy.linalg for BLAS; at exit Python's final garbage collection walks those "
          f"registries): {fr['first_use']['_numba_floor_s']:.2f} s, run right after each warm "
          f"fastrest run; fastrest's whole process against it (median of the pairs' ratios): {ratios}.")
    a("")
    a("### Peak memory (fresh processes)\n")
    mib = lambda x: "-" if x is None else f"{x:.0f} MiB"  # noqa: E731
    rows = [[k, mib(x.get("process_peak_mib")), mib(x["rss_before_mib"]), mib(x["op_peak_mib"]),
             mib(x["op_above_before_mib"]), mib(x["maxrss_mib"])]
            for k, x in mem.items() if not k.startswith("_")]
    a(md_table(["operation (fresh process)", "process peak (VmHWM)", "RSS before the operation",
                "peak during the operation", "operation's peak above RSS before", "ru_maxrss*"], rows))
    a(f"\nEach process first runs `import fastrest` and one small curve (loading the compiled kernels) and "
      "creates the operation's inputs (for the batches: n random points); then the high-water mark is reset "
      "(`/proc/self/clear_refs`) and the operation runs. \"Operation's peak above RSS before\" is its own "
      "need: output and temporaries (the inputs are already in \"RSS before\"). One float64 array of n "
      f"points is {mem['_batch_n'] * 8 / 2**20:.0f} MiB here. \\* `resource.getrusage(RUSAGE_SELF).ru_maxrss` "
      "of the same process; on Linux it starts, across fork + exec, from the resident size of the process "
      f"that forked it (the benchmark, {mem.get('_parent_rss_mib') or float('nan'):.0f} MiB when these ran, "
      "so values near that are a floor, not the child's); VmHWM (the process's own high-water mark, "
      "/proc/self/status) does not have that problem.\n")
    a("### Observations (computed from the figures above)\n")
    for line in observations(R):
        a(f"* {line}")
    a("")
    a("## 3. Targets\n")
    rows = [[t["name"], t["target"], t["measured"],
             f"{t['fraction_of_target']:.2g}" if t["fraction_of_target"] is not None else "-",
             "**met**" if t["met"] else "**not met**"] for t in R["targets"]]
    a(md_table(["target", "required", "measured", "measured / required", ""], rows))
    met = sum(t["met"] for t in R["targets"])
    a(f"\n{met} of {len(R['targets'])} met.\n")
    return "\n".join(L) + "\n"


def observations(R):
    se, mo = R["speed_error"], R["modes"]
    out = []
    cv = mo["build"]["curve"]
    d5 = cv["curve(0.005, 0.33) (direct solver, 2^5 cells/octave)"]
    tb = cv["curve from the default table (same nodes)"]
    d3 = cv["direct solver, 2^3 cells/octave"]
    out.append(
        f"One curve from the default table takes {fmt_time(tb['median_s'], 'ms')} against "
        f"{fmt_time(d5['median_s'], 'ms')} from the direct solver ({d5['median_s'] / tb['median_s']:.1f}x "
        f"faster), but inherits the table's error (e {fmt_err(tb['e_jcg'])}, 1 - e^2 {fmt_err(tb['loss_jcg'])} "
        f"against {fmt_err(d5['e_jcg'])}, {fmt_err(d5['loss_jcg'])}). At equal accuracy the comparison is with a "
        f"direct-solver curve of 2^3 cells per octave (e {fmt_err(d3['e_jcg'])}, 1 - e^2 {fmt_err(d3['loss_jcg'])}): "
        f"{fmt_time(d3['median_s'], 'ms')}, so the table route is {d3['median_s'] / tb['median_s']:.1f}x faster at "
        "that accuracy; for full accuracy only the direct solver will do.")
    th = mo["threads"]["sizes"]
    n = max(th)
    two = [k for k in th[n] if "2 threads" in k]
    if two:
        one = th[n]["prange, 1 thread"]["median_s"]
        out.append(f"A prange loop over e_curve runs {one / th[n][two[0]]['median_s']:.2f}x as fast on 2 threads "
                   f"as on 1 at n = {n:.0e} (medians; other processes on the machine reduce this).")
    by = {m["key"]: m for m in se["methods"]}
    curves = [m for m in se["methods"] if m["kind"] == "curve"]
    ct = [m["time_median"] for m in curves]
    out.append(f"Curve.e costs {ns(min(ct))} to {ns(max(ct))} per point from 2^{curves[0]['bits']} to "
               f"2^{curves[-1]['bits']} cells per octave ("
               + ", ".join(f"K={m['bits']}: {ns(m['time_median'])}" for m in curves)
               + f"), while its error falls from {fmt_err(curves[0]['error'])} to {fmt_err(curves[-1]['error'])}: "
               "the per-curve rows (64 bytes each) stay in cache at every resolution.")
    tabs = [m for m in se["methods"] if m["kind"] == "table" and m["key"] != "table_default_1t"]
    tt = [m["time_median"] for m in tabs]
    out.append(f"The tables (through the batch API) cost {ns(min(tt))} to {ns(max(tt))} per point for sizes "
               f"{min(m['mbytes'] for m in tabs):.1f} to {max(m['mbytes'] for m in tabs):.1f} MiB and errors "
               f"{fmt_err(max(m['error'] for m in tabs))} to {fmt_err(min(m['error'] for m in tabs))}.")
    fe, fw = se["fit_errors"], se["fit_where"]
    out.append(f"The paper's fits deviate from the model by up to {fe['fit4344'] * 100:.1f} % ((42)-(44), "
               f"paper: 4.5 % at most) and {fe['fit45'] * 100:.1f} % ((45), paper: 8.4 % at most); worst at "
               f"V1* = {fw['fit4344']['at_v1_star']:.0f} (eps_y = {fw['fit4344']['at_eps_y']:.3g}) and "
               f"V1* = {fw['fit45']['at_v1_star']:.0f} (eps_y = {fw['fit45']['at_eps_y']:.3g}).")
    d = by["direct"]
    out.append(f"The direct solver costs {fmt_time(d['time_median'], 'us')} per point, {d['ratio']:.0f}x the fit: "
               "the curves and tables exist to avoid it in loops.")
    return out


def t2ns(d):
    return f"{ns(d['median_s'])} ({ns(d['min_s'])})"


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
