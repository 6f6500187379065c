"""No slowdown of the Jackson-Green paths with the loading-law layer: old code against new, interleaved.

``python -m bench.loading_ab --old /path/to/old/checkout`` times, in alternating subprocesses
(old, new, old, new, ...; each with its own empty Numba cache, warmed before timing), the two
Jackson-Green paths the loading-law refactor touched at run time: building a curve
(``fastrest.curve(0.005, 0.33)``, best of 30) and the exact solver (``direct.e_exact`` on 2000
speeds, best of 5, per point). The old checkout is put first on PYTHONPATH. (Curve, scene and
table evaluation and ``contact_force`` are in ``python -m bench`` and ``python -m bench.force_law``,
as ratios to a reference measured in the same run.) Writes bench/LOADING_AB.md.
"""
import argparse
from pathlib import Path

from .ab import medians, revisions, run_interleaved
from .report import machine

WORKER = r'''
import time
import numpy as np
import fastrest
from fastrest import direct
fastrest.curve(0.005, 0.33)
v = np.geomspace(2.3, 1000, 2000)
direct.e_exact(v[:10], 0.005, 0.33)
def best(f, n):
    t = []
    for _ in range(n):
        s = time.perf_counter(); f(); t.append(time.perf_counter() - s)
    return min(t)
print(best(lambda: fastrest.curve(0.005, 0.33), 30) * 1e3, best(lambda: direct.e_exact(v, 0.005, 0.33), 5) / v.size * 1e6)
'''


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m bench.loading_ab", description=__doc__)
    p.add_argument("--old", required=True, help="checkout of the old fastrest (put first on PYTHONPATH)")
    p.add_argument("--rounds", type=int, default=4)
    a = p.parse_args(argv)
    res = run_interleaved(a.old, a.rounds, WORKER)
    med = medians(res, 2)
    m = machine()
    rev, new = revisions(a.old)
    lines = ["# Jackson-Green paths before and after the loading-law refactor (`python -m bench.loading_ab`)", "",
             f"Machine: {m.get('nproc')}-core {m.get('cpu')}; old = {rev or a.old}, new = {new or 'this checkout'}; "
             f"{a.rounds} interleaved rounds, median of the per-round bests.", "",
             "| path | old | new | new/old |", "| --- | --- | --- | --- |",
             f"| build `fastrest.curve(0.005, 0.33)` (ms) | {med['old'][0]:.3f} | {med['new'][0]:.3f} | {med['new'][0] / med['old'][0]:.3f} |",
             f"| `direct.e_exact`, 2000 speeds (us per point) | {med['old'][1]:.3f} | {med['new'][1]:.3f} | {med['new'][1] / med['old'][1]:.3f} |",
             "", "Rounds (old, new): " + "; ".join(f"{o[0]:.3f}/{n[0]:.3f} ms, {o[1]:.3f}/{n[1]:.3f} us"
                                              for o, n in zip(res["old"], res["new"]))]
    Path(__file__).with_name("LOADING_AB.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
