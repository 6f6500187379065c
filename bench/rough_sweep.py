"""A rough-surface sweep here and on a two-worker Dask cluster, in the same run.

``python -m bench.rough_sweep [--surfaces 7] [--summits 20000] [--repeats 3]`` writes
bench/ROUGH_SWEEP.md. Surfaces of explicit Gaussian summits (steel, R_a = 100 um, sigma = 2
omega_c, each its own seed), 20 speeds from 0.01 to 1 m/s, M = 10 g:

* ``local``: ``rough.sweep(specs, V, M)`` in this process (Numba's threads: every core);
* ``dask``: the same on ``LocalCluster(n_workers=2, processes=True, threads_per_worker=1)``: each
  task's kernels on its worker's one thread;
* ``dask, every core per worker``: the same cluster with a factory that sets Numba's thread count
  back to every core inside each task: two workers each running as many threads as the machine
  has cores.

Each configuration runs once untimed (the workers compile or load the kernels), then ``--repeats``
times in turn (the order reversed in every other repeat); the fastest counts. The results of the
three are checked bit-identical.
"""
import argparse
import datetime
import time
from pathlib import Path

import numba
import numpy as np

import fastrest
from fastrest import rough

from .report import machine

HERE = Path(__file__).resolve().parent
STEEL = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
R_A, M = 100e-6, 0.01


def every_core_factory(**spec):
    """A surface, with Numba's threads set to every core in the calling thread (the worker's)."""
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return rough.surface_from_params(**spec)


def specs(n, summits):
    sigma = 2 * fastrest.Impact(STEEL, R_A, mass=1.0).omega_c
    return [dict(material=STEEL, R_a=R_A, gaussian=(summits, sigma, seed)) for seed in range(n)]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--surfaces", type=int, default=7)
    ap.add_argument("--summits", type=int, default=20000)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", default=str(HERE / "ROUGH_SWEEP.md"))
    args = ap.parse_args(argv)
    from dask.distributed import Client, LocalCluster

    s = specs(args.surfaces, args.summits)
    V = np.geomspace(0.01, 1.0, 20)
    t0 = time.perf_counter()
    with LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        runs = {"local": lambda: rough.sweep(s, V, M),
                "dask": lambda: rough.sweep(s, V, M, client=client),
                "dask, every core per worker": lambda: rough.sweep(s, V, M, client=client,
                                                                   factory=every_core_factory)}
        ref = None
        for name, run in runs.items():  # untimed: compile or load the kernels everywhere
            out = run()
            e = np.array([r.e for r in out])
            ref = e if ref is None else ref
            if not np.array_equal(e, ref):
                raise RuntimeError(f"{name}: results differ from the local sweep")
        best = {name: np.inf for name in runs}
        order = list(runs)
        for rep in range(args.repeats):
            for name in (order if rep % 2 == 0 else order[::-1]):
                t = time.perf_counter()
                runs[name]()
                best[name] = min(best[name], time.perf_counter() - t)
                print(name, f"{time.perf_counter() - t:.3f} s", flush=True)
    info = machine()
    lines = [f"# A rough-surface sweep here and on Dask ({datetime.date.today().isoformat()})", "",
             f"`python -m bench.rough_sweep --surfaces {args.surfaces} --summits {args.summits} --repeats "
             f"{args.repeats}` (bench/rough_sweep.py; {time.perf_counter() - t0:.0f} s). Machine: {info['cpu']}, "
             f"{numba.config.NUMBA_NUM_THREADS} cores as Numba counts them. {args.surfaces} surfaces of "
             f"{args.summits} explicit Gaussian summits (steel, R_a = 100 um), 20 speeds 0.01-1 m/s, M = 10 g. "
             "Dask: `LocalCluster(n_workers=2, processes=True, threads_per_worker=1)`. The fastest of "
             f"{args.repeats} alternating repeats after one untimed run each; the three give the same bits.", "",
             "| configuration | sweep (s) | / local |", "|---|---|---|"]
    for name in runs:
        lines.append(f"| {name} | {best[name]:.3f} | {best[name] / best['local']:.2f}x |")
    lines += ["", "`dask` runs each task's Numba kernels on its worker's `threads_per_worker` threads "
              "(`rough.sweep` sets them per task); `dask, every core per worker` sets them back to every "
              "core inside each task, so that two workers each start as many threads as the machine has "
              "cores."]
    Path(args.out).write_text("\n".join(lines) + "\n")
    print("wrote", args.out)


if __name__ == "__main__":
    main()
