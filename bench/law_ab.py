"""The branch-free contact law (0.3) against fastrest 0.2's: the other paths that use its data, old against new.

``python -m bench.law_ab --old /path/to/old/checkout`` times, in alternating subprocesses (old,
new, ...; each with its own empty Numba cache, warmed before timing), what the new
``ForwardData.law_rows`` (built by every ``forward_data``) and the new kernel can touch outside
the DEM loop (bench/DEM_LOOP.md times that one): building a law (``fastrest.contact_law``, all
cells to w* = 425), ``ContactLaw.force`` on a 1e5-step path from Python (and its jit loop alone: the call allocates
and checks arrays, whose cost varies with the process's heap), one time-stepped impact
(``ContactLaw.impact``, 4000 steps per contact: contact-major), a rough surface's impact with 1e6
explicit summits and with a statistical (GW) surface (both read ``ForwardData``), and
``Curve.e`` on 1e6 speeds (untouched: the control). Each figure is the best of several repeats,
the median over rounds. Writes bench/LAW_AB.md.
"""
from pathlib import Path

from .ab import report_main

WORKER = r'''
import time
import numpy as np
import fastrest
from fastrest import rough

steel = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
c = fastrest.curve(0.005, 0.33)
law = fastrest.contact_law(0.005, 0.33)
rng = np.random.default_rng(1)
v = np.exp(rng.uniform(0.0, np.log(800.0), 1_000_000))
path = 30.0 * np.abs(np.sin(np.linspace(0.0, 40.0, 100_000)))
z = rough.gaussian_summits(10**6, 50e-9, seed=1)
ex = rough.RoughSurface(steel, 100e-6, heights=z)
gw = rough.RoughSurface(steel, 100e-6, gw=dict(eta=1e10, sigma=50e-9, A_n=1e-4))
ex.impact(0.1, M=0.01); gw.impact(0.1, M=0.01); law.force(path[:10]); law.impact(10.0, steps_per_contact=100)
c.e(v[:10]); fastrest.contact_law(0.004, 0.3)
from fastrest.force_law import _force_path
out = np.empty(path.size)
_force_path(law.data, np.zeros(4), path[:10], out)

print(best(lambda: fastrest.contact_law(0.005, 0.3), 5) * 1e3,
      best(lambda: law.force(path), 5) / path.size * 1e9,
      best(lambda: _force_path(law.data, np.zeros(4), path, out), 5) / path.size * 1e9,
      best(lambda: law.impact(30.0, steps_per_contact=4000), 5) * 1e6,
      best(lambda: ex.impact(0.1, M=0.01), 3) * 1e3,
      best(lambda: gw.impact(np.geomspace(0.01, 3.0, 50), M=0.01), 15) * 1e3,
      best(lambda: c.e(v), 5) / v.size * 1e9)
'''
NAMES = ("`fastrest.contact_law(...)` build (ms)", "`ContactLaw.force`, 1e5-step path (ns/step)",
         "its jit loop alone (`force_law._force_path`, ns/step)",
         "`ContactLaw.impact(30, 4000 steps)` (us)", "rough, 1e6 explicit summits, one impact (ms)",
         "rough, GW surface, 50 speeds (ms)", "`Curve.e`, 1e6 speeds (ns/point; control)")


def main(argv=None):
    report_main(argv, "python -m bench.law_ab", __doc__, "The branch-free contact law: other paths, old against new",
                WORKER, NAMES, Path(__file__).with_name("LAW_AB.md"))


if __name__ == "__main__":
    main()
