"""What storing a contact's history in float32 does to the coefficient of restitution.

GPU DEM codes keep per-contact history in their own slots, often float32 (Chrono DEM-Engine's
"wildcards"). ``fastrest.jit.contact_force`` keeps four float64 per contact (w_max, P*(w_max),
w_res*, w_max - w_res*; :data:`fastrest.jit.STATE_SIZE`). This integrates single impacts
(normalised: d^2w/dtau^2 = -(5/4) P*(w), velocity Verlet, ``--steps`` per Hertz contact time, as
:meth:`fastrest.ContactLaw.impact` without its step splitting at w = 1.9) with the state stored
between time steps as

* ``float64``: as it is (the reference);
* ``float32``: each of the four values rounded to float32 after every call (one float slot each);
* ``float32 x2``: each value as a pair of float32, hi = float32(x), lo = float32(x - hi) (two
  slots each, ~48 bits);
* ``w_max only``: one float32 slot, w_max; the other three rebuilt from it before every call
  (P*(w_max) from the loading law, the residual recomputed by ``contact_force``).

and prints the largest |e - e_float64| over speeds V1* from 0.5 to each material's limit, every
unloading model and three materials, next to the time stepping's own error |e_float64 - Curve.e|
for scale; then, for the C header's route (e of the impact speed, ``fastrest_e``), what keeping
the impact speed in one float32 slot does to e (``Curve.e`` at V1* and at float32(V1*)). The interference and velocity stay float64 in every case: only the history's storage
changes. ``python -m bench.history_float32 [--steps N] [--speeds N]``.
"""
import argparse
import math
import time

import numba
import numpy as np

import fastrest
from fastrest import jit as frj

MATERIALS = [(0.005, 0.33), (0.001, 0.3), (0.0095, 0.42)]
MODES = ["float64", "float32", "float32 x2", "w_max only"]


@numba.njit
def _store(state, mode, law, fresh):
    """The state as the DEM code would keep it, read back as float64."""
    if mode == 1:
        for i in range(state.size):
            state[i] = np.float64(np.float32(state[i]))
    elif mode == 2:
        for i in range(state.size):
            hi = np.float32(state[i])
            lo = np.float32(state[i] - np.float64(hi))
            state[i] = np.float64(hi) + np.float64(lo)
    elif mode == 3:
        w_max = np.float64(np.float32(state[0]))
        for i in range(state.size):
            state[i] = 0.0
            fresh[i] = 0.0
        if w_max > 0.0:
            p = frj.contact_force(law, fresh, w_max)  # the loading law at the stored w_max
            state[0] = w_max
            state[1] = p  # w_res and delta: 0, recomputed by contact_force when it unloads


@numba.njit
def impact(law, v1_star, steps, mode):
    """e of one impact with the history stored as ``mode`` between steps."""
    state = np.zeros(frj.STATE_SIZE)
    fresh = np.zeros(frj.STATE_SIZE)
    dt = frj.hertz_contact_time(v1_star) / steps
    w, v, a = 0.0, v1_star, 0.0
    for n in range(1, 1000 * steps):
        w_new = w + v * dt + 0.5 * a * dt * dt
        p = frj.contact_force(law, state, w_new)
        _store(state, mode, law, fresh)
        a_new = -1.25 * p
        v += 0.5 * (a + a_new) * dt
        w, a = w_new, a_new
        if p != p:
            return np.nan
        if p == 0.0 and v < 0.0 and n > 1:
            return -v / v1_star
    return np.nan


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--steps", type=int, default=2000, help="velocity-Verlet steps per Hertz contact time")
    ap.add_argument("--speeds", type=int, default=40, help="speeds per material and model (log-spaced)")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    worst = {m: (0.0, None) for m in MODES[1:]}
    worst_rel = {m: 0.0 for m in MODES[1:]}
    steps_err = 0.0
    for eps, nu in MATERIALS:
        for model in ("jcg", "etsion", "brake"):
            law = fastrest.contact_law(eps, nu, model)
            top = fastrest.limit(eps, nu).v1_star * 0.98
            speeds = np.exp(np.linspace(math.log(0.5), math.log(top), args.speeds))
            e_curve = fastrest.curve(eps, nu, model).e(speeds)
            for v1, ec in zip(speeds, e_curve):
                e64 = impact(law.data, v1, args.steps, 0)
                steps_err = max(steps_err, abs(e64 - ec))
                for code, mode in enumerate(MODES[1:], start=1):
                    d = abs(impact(law.data, v1, args.steps, code) - e64)
                    if not d <= worst[mode][0]:
                        worst[mode] = (d, (eps, nu, model, float(v1)))
                    worst_rel[mode] = max(worst_rel[mode], d / e64)
    n = len(MATERIALS) * 3 * args.speeds
    print(f"{n} impacts ({len(MATERIALS)} materials x 3 unloading models x {args.speeds} speeds, V1* 0.5 to "
          f"0.98 x limit), {args.steps} steps per contact, {time.perf_counter() - t0:.1f} s")
    print(f"time stepping's own error, max |e_float64 - Curve.e|: {steps_err:.2e}")
    print("history stored as   max |e - e_float64|   max relative   at (eps_y, nu, model, V1*)")
    for mode in MODES[1:]:
        d, where = worst[mode]
        print(f"{mode:<19} {d:>20.2e}   {worst_rel[mode]:>12.2e}   {where}")
    # the C header's route: e(V) of the impact speed, the speed kept in one float32 slot
    rng = np.random.default_rng(1)
    worst_v = 0.0
    for eps, nu in MATERIALS:
        top = fastrest.limit(eps, nu).v1_star
        v = np.exp(rng.uniform(math.log(0.5), math.log(top), 200000))
        v32 = v.astype(np.float32).astype(np.float64)
        for model in ("jcg", "etsion", "brake"):
            c = fastrest.curve(eps, nu, model)
            ok = v32 <= c.v_max
            worst_v = max(worst_v, float(np.max(np.abs(c.e(v32[ok]) - c.e(v[ok])))))
    print(f"impact speed V1* kept in float32 (the header's e(V) route): max |e(V1*_float32) - e(V1*)| = {worst_v:.2e} "
          f"({len(MATERIALS)} materials x 3 models x 2e5 random speeds)")


if __name__ == "__main__":
    main()
