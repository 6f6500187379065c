"""A million spheres hit a rigid wall, time-stepped on the GPU with the JG contact law and its history.

Run from anywhere (it writes no file)::

    python docs/examples/dem_gpu.py [--n 1000000] [--steps-per-contact 200]   # needs an NVIDIA GPU
    python docs/examples/dem_gpu.py --simulate --n 100                       # Numba's CUDA simulator

Needs numba-cuda (``pip install "fastrest[gpu]"``). The DEM-style part runs on the device:

* every particle-wall contact keeps its history row (:data:`fastrest.jit.STATE_SIZE` float64) in a
  device array, ``state[i]``, from the first touch to the rebound;
* a ``numba.cuda.jit`` kernel advances every particle by a chunk of velocity-Verlet steps of one
  global time step (a fraction of the shortest Hertz contact duration,
  :func:`fastrest.jit.hertz_contact_time`), calling :func:`fastrest.jit.contact_force` -- the same
  function a CPU code calls from ``numba.njit`` -- at every step; the host launches chunks until
  every particle has left the wall (a counter on the device).

The particles are steel spheres of radius 0.5-2 mm at impact speeds V1* = V1/V_c from 1.05 to 50 (log-uniform), with
one contact law (normalised: the radius enters through each contact's omega_c and P_c, computed on
the CPU with :func:`fastrest.jit.critical_scales`). Each rebound speed over impact speed is compared with
the energy balance's e of :meth:`fastrest.Curve.e` for the same impact: the worst relative
difference falls with the step (measured with ``--simulate --n 100``: 3.6e-4 at 40 steps per
contact, 8e-6 at 200). Exit status 1 when it is above ``--tol``, 2 without a GPU.
"""
import argparse
import math
import os
import sys
import time


def parse(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=1_000_000, help="number of spheres (default 1e6)")
    p.add_argument("--steps-per-contact", type=int, default=None,
                   help="time steps per shortest Hertz contact (default 200; 40 with --simulate)")
    p.add_argument("--chunk", type=int, default=256, help="time steps per kernel launch (default 256)")
    p.add_argument("--tol", type=float, default=None,
                   help="largest relative difference of e from Curve.e accepted (default 0.1/steps-per-contact)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--simulate", action="store_true",
                   help="run under Numba's CUDA simulator (no GPU; slow: use --n 100)")
    return p.parse_args(argv)


ARGS = parse(sys.argv[1:]) if __name__ == "__main__" else None
if ARGS is not None and ARGS.simulate and os.environ.get("NUMBA_ENABLE_CUDASIM") != "1":
    # the simulator must be chosen before numba.cuda is imported: run this script again with it on
    os.environ["NUMBA_ENABLE_CUDASIM"] = "1"
    os.execv(sys.executable, [sys.executable] + sys.argv)

import numba  # noqa: E402
import numpy as np  # noqa: E402

import fastrest  # noqa: E402
from fastrest import jit as frj  # noqa: E402

try:
    import fastrest.cuda as fc  # noqa: E402
    from numba import cuda  # noqa: E402
except ImportError as err:
    sys.exit(f"{err}")

#: Steel against a rigid wall (E Pa, nu, Sy Pa, rho kg/m^3): eps_y = Sy/E' inside the validated range.
STEEL = fastrest.Material(200e9, 0.30, 1.0e9, 7800)
#: Values of history per contact (a module constant: a local array's size must be one at compile time).
STATE_SIZE = frj.STATE_SIZE


@numba.njit
def setup(E, nu, Sy, rho, radius, v1_star, dt_fraction, omega_c, P_c, mass, speed):
    """Critical scales of every particle-wall contact (CPU); returns the global time step (s)."""
    dt = math.inf
    for i in range(radius.size):
        m = 4.0 / 3.0 * math.pi * radius[i] ** 3 * rho
        s = frj.critical_scales(E, nu, Sy, radius[i], m, math.inf, 0.0, math.inf, math.inf, math.inf)
        omega_c[i], P_c[i], mass[i] = s.omega_c, s.P_c, s.mass
        speed[i] = v1_star[i] * s.V_c
        # Hertz contact duration in seconds: tau_c(V1*) omega_c / V_c
        dt = min(dt, frj.hertz_contact_time(v1_star[i]) * s.omega_c / s.V_c * dt_fraction)
    return dt


@cuda.jit
def advance(law, x, v, a, state, omega_c, P_c, mass, speed, dt, n_steps, e, steps, active):
    """Up to ``n_steps`` velocity-Verlet steps of every particle still on the wall.

    x: interference omega (m, 0 at first touch), v = d omega/dt (m/s, > 0 towards the wall), a its
    rate; state[i]: the contact's history. e[i] is set (rebound over impact speed) when particle i
    leaves the wall; ``active[0]`` counts the particles still on it after this launch.
    """
    i = cuda.grid(1)
    if i >= x.size or steps[i] < 0:
        return
    row = cuda.local.array(STATE_SIZE, numba.float64)  # the history, in registers for the chunk
    for j in range(STATE_SIZE):
        row[j] = state[i, j]
    xi, vi, ai = x[i], v[i], a[i]
    wc, pc, m = omega_c[i], P_c[i], mass[i]
    done = False
    k = 0
    while k < n_steps:
        k += 1
        xi += vi * dt + 0.5 * ai * dt * dt
        f = pc * frj.contact_force(law, row, xi / wc)
        a_new = -f / m
        vi += 0.5 * (ai + a_new) * dt
        ai = a_new
        if (f == 0.0 and vi < 0.0) or f != f:
            done = True
            break
    for j in range(STATE_SIZE):
        state[i, j] = row[j]
    x[i], v[i], a[i] = xi, vi, ai
    if done:
        e[i] = -vi / speed[i]
        steps[i] = -(steps[i] + k)  # negative: finished after that many steps
    else:
        steps[i] += k
        cuda.atomic.add(active, 0, 1)


def run(n, steps_per_contact, chunk=256, seed=1):
    """Simulate ``n`` impacts; returns (e from the time steps, Curve.e, seconds on the device, steps)."""
    rng = np.random.default_rng(seed)
    radius = rng.uniform(0.5e-3, 2e-3, n)
    v1_star = np.exp(rng.uniform(math.log(1.05), math.log(50.0), n))
    omega_c, P_c, mass, speed = (np.empty(n) for _ in range(4))
    dt = setup(STEEL.E, STEEL.nu, STEEL.Sy, STEEL.rho, radius, v1_star, 1.0 / steps_per_contact,
               omega_c, P_c, mass, speed)
    law = fastrest.Impact(STEEL, 1e-3).contact_law("jcg")  # normalised law: the same for every radius
    d_law = fc.to_device(law)
    d = {name: fc.to_device(arr) for name, arr in
         dict(omega_c=omega_c, P_c=P_c, mass=mass, speed=speed, v=speed.copy(), x=np.zeros(n), a=np.zeros(n),
              e=np.full(n, np.nan), steps=np.zeros(n, dtype=np.int64)).items()}
    state = fc.new_state(n)
    active = cuda.to_device(np.zeros(1, dtype=np.int64))
    blocks = (n + fc.THREADS_PER_BLOCK - 1) // fc.THREADS_PER_BLOCK
    cuda.synchronize()
    t0 = time.perf_counter()
    launches = 0
    while True:
        active.copy_to_device(np.zeros(1, dtype=np.int64))
        advance[blocks, fc.THREADS_PER_BLOCK](d_law, d["x"], d["v"], d["a"], state, d["omega_c"], d["P_c"],
                                              d["mass"], d["speed"], dt, chunk, d["e"], d["steps"], active)
        launches += 1
        if active.copy_to_host()[0] == 0 or launches > 10**6:
            break
    cuda.synchronize()
    seconds = time.perf_counter() - t0
    e_dem = d["e"].copy_to_host()
    total = int(-d["steps"].copy_to_host().sum())
    eps_y = fastrest.Impact(STEEL, 1e-3).eps_y
    e_curve = fastrest.curve(eps_y, STEEL.nu, "jcg", v_max=50.0).e(v1_star)
    return e_dem, e_curve, seconds, total


def main(args):
    if not args.simulate and not cuda.is_available():
        print("dem_gpu: no CUDA GPU found (numba.cuda.is_available() is False); run with --simulate --n 100 "
              "to try it under Numba's CUDA simulator", file=sys.stderr)
        return 2
    steps = args.steps_per_contact or (40 if args.simulate else 200)
    tol = args.tol if args.tol is not None else 0.1 / steps
    e_dem, e_curve, seconds, total = run(args.n, steps, args.chunk, args.seed)
    err = np.abs(e_dem / e_curve - 1)
    where = "Numba's CUDA simulator" if fc.SIMULATOR else cuda.get_current_device().name.decode() \
        if isinstance(cuda.get_current_device().name, bytes) else cuda.get_current_device().name
    print(f"{args.n} steel spheres against a rigid wall on {where}, global time step = shortest Hertz "
          f"contact / {steps}")
    print(f"  rebound e vs Curve.e (energy balance): worst relative difference {err.max():.2e}, "
          f"median {np.median(err):.2e} (accepted: {tol:.1e})")
    print(f"  {total} contact-force steps in {seconds:.3f} s ({seconds / total * 1e9:.2f} ns per particle and step)")
    return 0 if err.max() <= tol else 1


if __name__ == "__main__":
    sys.exit(main(ARGS))
