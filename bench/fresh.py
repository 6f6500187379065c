"""Fresh processes: first-use latency (warm and empty Numba cache) and peak memory (ru_maxrss)."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from .timing import wait_for_quiet

REPO = Path(__file__).resolve().parent.parent

#: First calls in a fresh process after ``fastrest warmup`` (run once at the start, nothing else
#: warms the cache): every entry point warmup compiles.
FIRST_USE = {
    "fastrest.e_star(5.0, 0.005, 0.33)": "fastrest.e_star(5.0, 0.005, 0.33)",
    "fastrest.curve(0.005, 0.33).e(5.0)": "fastrest.curve(0.005, 0.33).e(5.0)",
    "fastrest.direct.e_exact(5.0, 0.005, 0.33)": "fastrest.direct.e_exact(5.0, 0.005, 0.33)",
    "fastrest.e_star, 1e5 points (parallel kernel)":
        "import numpy as np; fastrest.e_star(np.full(100000, 5.0), 0.005, 0.33)",
    "fastrest.scene([...], v_max=20).e(5.0, 1)": "fastrest.scene([(0.005, 0.33), (0.003, 0.3)], v_max=20.0).e(5.0, 1)",
    "rough, explicit summits": "from fastrest import rough; rough.RoughSurface(fastrest.Material(2e11, 0.3, 1e9), "
                               "1e-4, heights=rough.gaussian_summits(100, 1e-7, 1)).impact(1e-3, 1e-3)",
    "rough, statistical (4 speeds)": "from fastrest import rough; rough.RoughSurface(fastrest.Material(2e11, 0.3, 1e9), "
                                     "1e-4, gw=dict(eta=1e10, sigma=6e-9, A_n=1e-6)).impact([1e-4, 2e-4, 3e-4, 4e-4], 1e-3)",
    "fastrest.contact_law(0.005, 0.33).force(...)": "fastrest.contact_law(0.005, 0.33).force([0.5, 2.0, 1.0])",
}

_LATENCY = """
import time
t0 = time.perf_counter()
import fastrest
t1 = time.perf_counter()
{call}
t2 = time.perf_counter()
import json
print(json.dumps({{"import_s": t1 - t0, "call_s": t2 - t1}}))
"""

_MEMORY = """
import json, resource, sys, tempfile, warnings
import numpy as np
import fastrest

def status(key):
    try:
        for line in open("/proc/self/status"):
            if line.startswith(key + ":"):
                return int(line.split()[1])
    except OSError:
        return None

fastrest.curve(0.005, 0.33, v_max=10.0).e(5.0)
{setup}
rss0 = status("VmRSS")
hwm0 = status("VmHWM")
hwm_reset = False
try:  # reset the high-water mark (Linux >= 4.0), so VmHWM is the operation's own peak
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")
    hwm_reset = status("VmHWM") is not None and status("VmHWM") <= rss0 + 1024
except OSError:
    pass
{code}
print(json.dumps({{"rss_before_kib": rss0, "hwm_kib": status("VmHWM") if hwm_reset else None,
                  "hwm_before_kib": hwm0, "hwm_end_kib": status("VmHWM"),
                  "maxrss_kib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss}}))
"""

MEMORY = {  # name: (set-up before the high-water mark is reset, the operation measured)
    "baseline (nothing)": ("pass", "pass"),
    "default table build (fastrest.tables.build, compute + check + write)": (
        "pass",
        "with tempfile.TemporaryDirectory() as d: fastrest.tables.build(d + '/t.h5', None, progress=False)"),
    "one curve, full range (fastrest.curve(0.005, 0.33))": ("pass", "c = fastrest.curve(0.005, 0.33)"),
    "Curve.e batch, {n:.0e} points": (
        "c = fastrest.curve(0.005, 0.33); v = np.random.default_rng(0).uniform(1.0, c.v_max, {n})",
        "e = c.e(v)"),
    "fastrest.e_star batch, {n:.0e} points, per-point materials": (
        "rng = np.random.default_rng(0); n = {n}; eps = rng.uniform(0.0005, 0.01, n); "
        "nu = rng.uniform(0.2, 0.45, n); v = rng.uniform(1.0, 800.0, n); fastrest.e_star(v[:10], eps[:10], nu[:10])",
        "e = fastrest.e_star(v, eps, nu)"),
}


def _env(cache_dir=None):
    env = dict(os.environ)
    env["PYTHONPATH"] = str(REPO) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["MPLBACKEND"] = "Agg"
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = cache_dir
    return env


def warm_cache():
    """``fastrest warmup`` into the Numba cache the fresh processes use (the documented way)."""
    subprocess.run([sys.executable, "-m", "fastrest", "warmup"], cwd=REPO, env=_env(), check=True,
                   capture_output=True, timeout=3600)


def _run(code, env, timeout=600):
    wait_for_quiet()
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-c", code], cwd=REPO, env=env, capture_output=True, text=True,
                       timeout=timeout)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        raise RuntimeError(f"subprocess failed ({p.returncode}):\n{p.stderr[-2000:]}")
    return wall, json.loads(p.stdout.strip().splitlines()[-1])


# The floor any Numba library pays: the same imports, one cached @njit call (which initialises
# Numba's typing and target registries; Numba imports scipy.linalg for BLAS then), and the
# interpreter's exit, whose final garbage collection walks those registries.
_FLOOR_MODULE = """
import numba

@numba.njit(cache=True)
def f(x):
    return x + 1.0
"""
_FLOOR = """
import time
t0 = time.perf_counter()
import numpy, h5py, numba
import fastrest_bench_floor
fastrest_bench_floor.f(1.0)
t1 = time.perf_counter()
import json
print(json.dumps({"import_s": t1 - t0, "call_s": 0.0}))
"""


def first_use(cfg, log=print):
    """Wall time of a fresh process and, inside it, import + first call; warm and empty cache.

    Each warm run is paired with a run of the Numba floor (``_FLOOR``) right after it; the
    median of the per-pair ratios says what fastrest adds to it."""
    res = {}
    floor_dir = tempfile.mkdtemp(prefix="fastrest-bench-floor-")
    Path(floor_dir, "fastrest_bench_floor.py").write_text(_FLOOR_MODULE)
    floor_env = _env(str(Path(floor_dir, "cache")))
    floor_env["PYTHONPATH"] = floor_dir + os.pathsep + floor_env["PYTHONPATH"]
    _run(_FLOOR, floor_env)  # warm its cache
    floors = []
    warm_cache()  # each entry's first call below comes after it alone
    for name, call in FIRST_USE.items():
        code = _LATENCY.format(call=call)
        rows = {"warm": [], "cold": []}
        for _ in range(cfg["fresh_warm"]):
            wall, inner = _run(code, _env())
            floor_wall, _ = _run(_FLOOR, floor_env)
            floors.append(floor_wall)
            rows["warm"].append({"wall_s": wall, "floor_wall_s": floor_wall, **inner})
        for _ in range(cfg["fresh_cold"]):
            d = tempfile.mkdtemp(prefix="fastrest-bench-numba-")
            try:
                wall, inner = _run(code, _env(d))
            finally:
                shutil.rmtree(d, ignore_errors=True)
            rows["cold"].append({"wall_s": wall, **inner})
        log(f"  first use: {name}")
        res[name] = {
            k: {"runs": len(r),
                "wall_median_s": float(np.median([x["wall_s"] for x in r])) if r else None,
                "wall_min_s": float(np.min([x["wall_s"] for x in r])) if r else None,
                "import_median_s": float(np.median([x["import_s"] for x in r])) if r else None,
                "call_median_s": float(np.median([x["call_s"] for x in r])) if r else None,
                "inside_median_s": float(np.median([x["import_s"] + x["call_s"] for x in r])) if r else None,
                "ratio_to_floor": float(np.median([x["wall_s"] / x["floor_wall_s"] for x in r]))
                if r and "floor_wall_s" in r[0] else None}
            for k, r in rows.items()}
    # interpreter + numpy start-up alone, for scale
    wall = [_run("import json, numpy; print(json.dumps({}))", _env())[0] for _ in range(max(1, cfg["fresh_warm"]))]
    res["_python_numpy_startup_s"] = float(np.median(wall))
    res["_numba_floor_s"] = float(np.median(floors))
    shutil.rmtree(floor_dir, ignore_errors=True)
    return res


def own_rss_mib():
    try:
        for line in open("/proc/self/status"):
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    except OSError:
        return None


def peak_memory(cfg, log=print):
    warm_cache()  # peaks as users see them, without compiling (`python -m bench` uses a fresh cache)
    res = {"_parent_rss_mib": own_rss_mib()}
    n = cfg["memory_batch_n"]
    for name, (setup, code) in MEMORY.items():
        name = name.format(n=n)
        _, r = _run(_MEMORY.format(setup=setup.format(n=n), code=code.format(n=n)), _env())
        log(f"  peak memory: {name}")
        res[name] = {"maxrss_mib": r["maxrss_kib"] / 1024, "rss_before_mib": r["rss_before_kib"] / 1024,
                     "process_peak_mib": max(r["hwm_before_kib"] or 0, r["hwm_end_kib"] or 0) / 1024,
                     "op_peak_mib": r["hwm_kib"] / 1024 if r["hwm_kib"] is not None else None,
                     "op_above_before_mib": (r["hwm_kib"] - r["rss_before_kib"]) / 1024
                     if r["hwm_kib"] is not None else None}
    res["_batch_n"] = n
    return res
