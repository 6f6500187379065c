"""Where compile time goes: each entry point's first call with an empty Numba cache, per function.

``python -m bench.compile [--only NAME ...] [--top 8] [--with-warmup]`` writes bench/COMPILE.md. Each entry point
runs in a fresh process with an empty Numba cache (its own temporary ``NUMBA_CACHE_DIR``), beside
Numba's floor in the same run: a fresh process that imports numba and compiles one trivial cached
``@njit``. Reported per entry point: the wall time of import plus first call, its ratio to the
floor, and, from Numba's compile events (``numba.core.event``, kind ``numba:compile``), the
functions whose compiles took longest: inclusive seconds (a caller's compile holds its callees'),
self seconds (less the compiles nested in it), and how many type signatures were compiled. An
``inline="always"`` callee has no compile event of its own: its cost is in each caller's self time.
"""
import argparse
import datetime
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .report import machine

HERE = Path(__file__).resolve().parent

#: The entry points (issue 39's table): name -> code run after ``import fastrest``.
ENTRY = {
    "Impact(material, R).e([0.5, 2.0])":
        "fastrest.Impact(fastrest.Material(2e11, 0.3, 1e9, rho=7850.0), 0.01).e([0.5, 2.0])",
    "fastrest.curve(0.005, 0.33).e(5.0)": "fastrest.curve(0.005, 0.33).e(5.0)",
    "fastrest.e_star on 1e5 points": "import numpy as np; fastrest.e_star(np.full(100000, 5.0), 0.005, 0.33)",
    "fastrest.contact_law(0.005, 0.33).force(...)": "fastrest.contact_law(0.005, 0.33).force([0.5, 2.0, 1.0])",
    "RoughSurface(heights=20,000 summits).impact(...)":
        "from fastrest import rough; rough.RoughSurface(fastrest.Material(2e11, 0.3, 1e9), 1e-4, "
        "heights=rough.gaussian_summits(20000, 1e-7, 1)).impact([1e-3, 1e-2], 1e-3)",
    "RoughSurface(gw=...).impact(...)":
        "from fastrest import rough; rough.RoughSurface(fastrest.Material(2e11, 0.3, 1e9), 1e-4, "
        "gw=dict(eta=1e10, sigma=6e-9, A_n=1e-6)).impact([1e-4, 2e-4, 3e-4, 4e-4], 1e-3)",
}
#: ``--with-warmup`` adds the command that compiles everything (about a minute).
WARMUP = {"fastrest warmup (everything)": "from fastrest import cli; cli.main(['warmup'])"}

_FLOOR = """
import json, time
t0 = time.perf_counter()
import numba
@numba.njit(cache=True)
def f(x):
    return x + 1.0
f(1.0)
print("RESULT " + json.dumps({"wall_s": time.perf_counter() - t0}))
"""

_PROBE = """
import json, time
t0 = time.perf_counter()
from numba.core import event
with event.install_recorder("numba:compile") as rec:
    import fastrest
    {call}
wall = time.perf_counter() - t0
stack, spans = [], []
for ts, ev in rec.buffer:
    disp = ev.data["dispatcher"]
    name = getattr(disp, "py_func", None)
    name = f"{{name.__module__}}.{{name.__qualname__}}" if name is not None else str(disp)
    if ev.is_start:
        stack.append([name, ts, 0.0])
    else:
        n, t_start, nested = stack.pop()
        span = ts - t_start
        spans.append((n, span, span - nested))
        if stack:
            stack[-1][2] += span
out = {{}}
for n, inc, own in spans:
    d = out.setdefault(n, [0.0, 0.0, 0])
    d[0] += inc
    d[1] += own
    d[2] += 1
print("RESULT " + json.dumps({{"wall_s": wall, "functions": out}}))
"""


def _fresh(code):
    """Run ``code`` in a fresh interpreter with an empty Numba cache; its last printed dict."""
    with tempfile.TemporaryDirectory(prefix="fastrest-compile-") as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        script = Path(cache) / "probe.py"  # a file: Numba caches only functions defined in one
        script.write_text(code)
        t0 = time.perf_counter()
        run = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env)
        wall = time.perf_counter() - t0
    if run.returncode != 0:
        raise RuntimeError(f"probe failed:\n{run.stderr[-2000:]}")
    line = [ln for ln in run.stdout.splitlines() if ln.strip()][-1]
    if not line.startswith("RESULT "):
        raise RuntimeError(f"probe printed no result:\n{run.stdout[-2000:]}")
    data = json.loads(line[len("RESULT "):])
    data["process_s"] = wall
    return data


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="*", help="entry point names (default: all)")
    ap.add_argument("--top", type=int, default=8, help="functions listed per entry point (default 8)")
    ap.add_argument("--with-warmup", action="store_true", help="also `fastrest warmup` (about a minute)")
    ap.add_argument("--out", default=str(HERE / "COMPILE.md"))
    args = ap.parse_args(argv)
    entry = dict(ENTRY, **WARMUP)
    names = args.only or list(ENTRY) + (list(WARMUP) if args.with_warmup else [])
    t0 = time.perf_counter()
    floor = min(_fresh(_FLOOR)["process_s"] for _ in range(2))
    rows = {}
    for name in names:
        rows[name] = _fresh(_PROBE.format(call=entry[name]))
        print(f"{name}: {rows[name]['process_s']:.2f} s ({rows[name]['process_s'] / floor:.1f}x floor)", flush=True)
    floor = min(floor, _fresh(_FLOOR)["process_s"])  # the floor again at the end: the quieter of the two
    info = machine()
    lines = [f"# Compile time with an empty Numba cache ({datetime.date.today().isoformat()})", "",
             f"`python -m bench.compile` (bench/compile.py; {time.perf_counter() - t0:.0f} s). Machine: {info['cpu']}, "
             f"{os.cpu_count()} cores as the OS counts them. Each entry point in a fresh process with an empty "
             f"Numba cache; Numba's floor (a fresh process importing numba and compiling one trivial cached "
             f"`@njit`) {floor:.2f} s in the same run.", "",
             "| first call, empty cache | seconds | x floor | compiled signatures |", "|---|---|---|---|"]
    for name in names:
        r = rows[name]
        count = sum(v[2] for v in r["functions"].values())
        lines.append(f"| `{name}` | {r['process_s']:.2f} | {r['process_s'] / floor:.1f}x | {count} |")
    for name in names:
        r = rows[name]
        lines += ["", f"## `{name}`", "",
                  "| function | inclusive (s) | self (s) | signatures |", "|---|---|---|---|"]
        top = sorted(r["functions"].items(), key=lambda kv: -kv[1][1])[:args.top]
        for fn, (inc, own, n) in top:
            lines.append(f"| `{fn}` | {inc:.2f} | {own:.2f} | {n} |")
    lines += ["", "Self time: a function's compile less the compiles of the jitted functions it calls, which "
              "Numba compiles first, inside it. A function inlined with `inline=\"always\"` has no compile of its "
              "own: it is compiled again inside every caller, and counts in each caller's self time."]
    Path(args.out).write_text("\n".join(lines) + "\n")
    print("wrote", args.out)


if __name__ == "__main__":
    main()
