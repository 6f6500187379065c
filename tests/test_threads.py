"""Parallel kernels from several Python threads under Numba's workqueue layer.

workqueue is not thread-safe: two threads inside parallel kernels at once abort the process. Each
case runs in a subprocess with NUMBA_THREADING_LAYER=workqueue and a time limit; it must exit 0
with the same numbers as a single-threaded run.
"""
import os
import subprocess
import sys
import textwrap

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

_SCRIPT = textwrap.dedent("""
    import sys, threading, warnings
    import numba, numpy as np
    import fastrest
    from fastrest import rough
    warnings.simplefilter("ignore")
    rng = np.random.default_rng(1)
    n = 40000  # above PARALLEL_MIN_POINTS: the parallel table kernel
    v = rng.uniform(1.0, 50.0, n); e = rng.uniform(0.001, 0.009, n); nu = rng.uniform(0.25, 0.4, n)
    steel = fastrest.Material(2e11, 0.3, 1e9)
    explicit = rough.RoughSurface(steel, 1e-4, heights=rough.gaussian_summits(30000, 1e-6, seed=2))
    ip = fastrest.Impact(steel, 1e-4, mass=1.0)
    gw = rough.RoughSurface(steel, 1e-4, gw=dict(eta=1e10, sigma=0.5 * ip.omega_c, A_n=1e-6))
    speeds = np.array([1e-4, 2e-4, 5e-4, 1e-3])
    ref_table = fastrest.e_star(v, e, nu)
    ref_ex = explicit.impact(speeds, 1e-3).e
    ref_gw = gw.impact(speeds, 1e-3).e
    assert numba.threading_layer() == "workqueue", numba.threading_layer()
    errors = []

    def work(k):
        try:
            for _ in range(3):
                if not np.array_equal(fastrest.e_star(v, e, nu), ref_table):
                    errors.append("table")
                if not np.array_equal(explicit.impact(speeds, 1e-3).e, ref_ex):
                    errors.append("explicit")
                if not np.array_equal(gw.impact(speeds, 1e-3).e, ref_gw):
                    errors.append("gw")
        except Exception as exc:  # pragma: no cover - reported below
            errors.append(repr(exc))

    if sys.argv[1] == "threads":
        ts = [threading.Thread(target=work, args=(k,)) for k in range(4)]
        [t.start() for t in ts]
        [t.join() for t in ts]
    else:  # Dask's threaded scheduler
        import dask
        tasks = [dask.delayed(work)(k) for k in range(4)]
        dask.compute(*tasks, scheduler="threads", num_workers=4)
    print("errors", errors)
    sys.exit(1 if errors else 0)
""")


@pytest.mark.parametrize("how", ["threads", "dask"])
def test_parallel_kernels_from_threads_under_workqueue(how):
    env = dict(os.environ, NUMBA_THREADING_LAYER="workqueue", NUMBA_NUM_THREADS="2")
    r = subprocess.run([sys.executable, "-c", _SCRIPT, how], cwd=ROOT, env=env, capture_output=True,
                       text=True, timeout=600)
    assert r.returncode == 0, (r.returncode, r.stdout[-2000:], r.stderr[-2000:])
    assert "errors []" in r.stdout


def test_run_parallel_uses_serial_kernel_when_busy(monkeypatch):
    """The fallback itself: with the lock held by another thread, the serial kernel runs."""
    import threading

    from fastrest import _threads

    monkeypatch.setattr(_threads, "layer_is_thread_safe", lambda: False)  # as under workqueue

    got = []
    held, release = threading.Event(), threading.Event()

    def holder():
        with _threads._LOCK:
            held.set()
            release.wait(10)

    t = threading.Thread(target=holder)
    t.start()
    held.wait(10)
    try:
        _threads.run_parallel(lambda: got.append("parallel"), lambda: got.append("serial"))
    finally:
        release.set()
        t.join()
    assert got == ["serial"]
