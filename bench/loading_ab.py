"""No slowdown of the Jackson-Green paths with the loading-law layer: old code against new, interleaved.

``python -m bench.loading_ab --old /path/to/old/checkout`` times, in alternating subprocesses
(old, new, old, new, ...; each with its own empty Numba cache, warmed before timing), the two
Jackson-Green paths the loading-law refactor touched at run time: building a curve
(``fastrest.curve(0.005, 0.33)``, best of 30) and the exact solver (``direct.e_exact`` on 2000
speeds, best of 5, per point). The old checkout is put first on PYTHONPATH. (Curve, scene and
table evaluation and ``contact_force`` are in ``python -m bench`` and ``python -m bench.force_law``,
as ratios to a reference measured in the same run.) Writes bench/LOADING_AB.md.
"""
from pathlib import Path

from .ab import report_main

WORKER = r'''
import time
import numpy as np
import fastrest
from fastrest import direct
fastrest.curve(0.005, 0.33)
v = np.geomspace(2.3, 1000, 2000)
direct.e_exact(v[:10], 0.005, 0.33)
print(best(lambda: fastrest.curve(0.005, 0.33), 30) * 1e3, best(lambda: direct.e_exact(v, 0.005, 0.33), 5) / v.size * 1e6)
'''


NAMES = ("build `fastrest.curve(0.005, 0.33)` (ms)", "`direct.e_exact`, 2000 speeds (us per point)")


def main(argv=None):
    report_main(argv, "python -m bench.loading_ab", __doc__,
                "Jackson-Green paths before and after the loading-law refactor", WORKER, NAMES,
                Path(__file__).with_name("LOADING_AB.md"), rounds=4)


if __name__ == "__main__":
    main()
