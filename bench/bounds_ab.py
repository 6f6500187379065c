"""Cost of the row bounds check in the cell polynomials: old code against new, interleaved.

``python -m bench.bounds_ab --old /path/to/old/checkout`` times, in alternating subprocesses (old,
new, old, new, ...; each with its own empty Numba cache, warmed before timing), the paths whose
cell polynomial gained a row check (``fastrest.interpolation.cell_polynomial`` returns NaN for an
index outside the rows): ``Curve.e`` on 1e6 speeds, ``fastrest.jit.e_curve`` in a user ``@njit``
loop, ``Scene.e`` with a material index per point, and ``fastrest.jit.contact_force`` stepping 1e4
contacts through an impact step by step (step-major: every contact each step, as DEM codes loop).
The table path (``e_star``) reads its rows through a pointer, for which the check is no code; it
is not timed here. Each figure is the best of several repeats, the median over rounds. Writes
bench/BOUNDS_AB.md.
"""
from pathlib import Path

from .ab import report_main

WORKER = r'''
import time
import numpy as np
import numba
import fastrest
import fastrest.jit as frj

c = fastrest.curve(0.005, 0.33)
s = fastrest.scene([(0.005, 0.33), (0.002, 0.3), (0.008, 0.4)])
law = fastrest.contact_law(0.005, 0.33)
rng = np.random.default_rng(1)
v = np.exp(rng.uniform(0.0, np.log(800.0), 1_000_000))
k = rng.integers(0, 3, v.size)

@numba.njit(cache=False)
def loop_curve(data, v):
    t = 0.0
    for x in v:
        t += frj.e_curve(data, x)
    return t

@numba.njit(cache=False)
def steps(data, state, w_peak, n_steps):
    t = 0.0
    for j in range(n_steps):            # step-major: every contact each step
        phase = np.sin(np.pi * (j + 0.5) / n_steps)
        for i in range(state.shape[0]):
            t += frj.contact_force(data, state[i], w_peak[i] * phase)
    return t

w_peak = np.exp(rng.uniform(0.0, np.log(300.0), 10_000))
n_steps = 100
cd = c.data
loop_curve(cd, v[:10]); c.e(v[:10]); s.e(v[:10], k[:10])
steps(law.data, np.zeros((10, frj.STATE_SIZE)), w_peak[:10], 4)

def run_steps():
    steps(law.data, np.zeros((w_peak.size, frj.STATE_SIZE)), w_peak, n_steps)

print(best(lambda: c.e(v), 7) / v.size * 1e9, best(lambda: loop_curve(cd, v), 7) / v.size * 1e9,
      best(lambda: s.e(v, k), 7) / v.size * 1e9, best(run_steps, 5) / (w_peak.size * n_steps) * 1e9)
'''
NAMES = ("`Curve.e`, 1e6 speeds (ns/point)", "`jit.e_curve` in a user loop (ns/point)",
         "`Scene.e`, 3 materials (ns/point)", "`jit.contact_force`, 1e4 contacts x 100 steps (ns/contact-step)")


def main(argv=None):
    report_main(argv, "python -m bench.bounds_ab", __doc__, "Row bounds check in the cell polynomials: old against new",
                WORKER, NAMES, Path(__file__).with_name("BOUNDS_AB.md"))


if __name__ == "__main__":
    main()
