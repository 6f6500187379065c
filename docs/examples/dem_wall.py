"""Many spheres of a few materials hit a rigid wall in a time-stepped (DEM-style) loop.

Run from anywhere (it writes no file)::

    python docs/examples/dem_wall.py [n_particles] [steps_per_contact]

Each particle has its own material (steel, aluminium, titanium alloy), radius and impact speed.
Everything per contact happens inside one ``@numba.njit(parallel=True)`` function, the way a DEM
code's force loop runs:

* the critical scales (omega_c, P_c, V_c) of each particle-wall contact from the particle's E, nu,
  Sy, radius and mass by :func:`fastrest.jit.critical_scales` (a rigid wall: E, R, m, Sy = inf);
* at every step the normal force from :func:`fastrest.jit.contact_force_stacked` with one history
  row per contact, and velocity Verlet with one global time step (a fraction of the shortest Hertz
  contact duration, :func:`fastrest.jit.hertz_contact_time`), as DEM codes do.

The contact law of a material against the rigid wall depends only on eps_y = Sy/E' and nu, so
there is one law per material (built in Python). The laws of all materials are stacked into one
data indexed by material (:func:`fastrest.force_law.stack_laws`), so that one ``prange`` loop runs
over every particle whatever its material: ``contact_force_stacked(laws, kind[i], state, w)``. (A
tuple or list of the laws' ``law.data`` cannot be indexed by a run-time material inside a jitted
loop.) The rebound speed of every particle is compared with the energy-balance e of
:meth:`fastrest.Curve.e` for the same impact.
"""
import math
import sys
import time

import numba
import numpy as np

import fastrest
from fastrest import jit as frj
from fastrest.force_law import stack_laws

#: (E Pa, nu, Sy Pa, rho kg/m^3): every eps_y = Sy/E' inside the paper's validated range
MATERIALS = [fastrest.Material(200e9, 0.30, 1.0e9, 7800),     # steel
             fastrest.Material(70e9, 0.33, 0.28e9, 2700),     # aluminium alloy
             fastrest.Material(114e9, 0.34, 0.88e9, 4430)]    # titanium alloy


@numba.njit
def setup(kind, E, nu, Sy, rho, radius, speed, dt_fraction, omega_c, P_c, mass):
    """Critical scales of every particle-wall contact; returns the global time step (s)."""
    dt = math.inf
    for i in range(kind.size):
        k = kind[i]
        m = 4.0 / 3.0 * math.pi * radius[i] ** 3 * rho[k]
        s = frj.critical_scales(E[k], nu[k], Sy[k], radius[i], m, math.inf, 0.0, math.inf, math.inf, math.inf)
        omega_c[i], P_c[i], mass[i] = s.omega_c, s.P_c, s.mass
        # Hertz contact duration in seconds: tau_c(V1*) omega_c / V_c
        dt = min(dt, frj.hertz_contact_time(speed[i] / s.V_c) * s.omega_c / s.V_c * dt_fraction)
    return dt


@numba.njit(parallel=True)
def simulate(laws, kind, omega_c, P_c, mass, speed, dt, out):
    """Drop every particle on the wall at its speed, particle i of material ``kind[i]`` of the
    stacked ``laws``; out[i] = (rebound speed, e, steps)."""
    for i in numba.prange(kind.size):
        state = np.zeros(frj.STATE_SIZE)
        x = 0.0                # interference omega (m): the sphere touches the wall at x = 0
        v = speed[i]           # d omega / dt (m/s), towards the wall
        a = 0.0
        steps = 0
        while True:
            steps += 1
            x += v * dt + 0.5 * a * dt * dt
            f = P_c[i] * frj.contact_force_stacked(laws, kind[i], state, x / omega_c[i])
            a_new = -f / mass[i]
            v += 0.5 * (a + a_new) * dt
            a = a_new
            if (f == 0.0 and v < 0.0) or f != f or steps > 10**8:
                break
        out[i, 0] = -v
        out[i, 1] = -v / speed[i]
        out[i, 2] = steps


def run(n_particles=300, steps_per_contact=4000, seed=1, unloading="jcg"):
    """Simulate ``n_particles`` impacts; return (e_dem, e_curve, seconds)."""
    rng = np.random.default_rng(seed)
    kind = rng.integers(0, len(MATERIALS), n_particles)
    radius = rng.uniform(0.5e-3, 5e-3, n_particles)
    E = np.array([m.E for m in MATERIALS])
    nu = np.array([m.nu for m in MATERIALS])
    Sy = np.array([m.Sy for m in MATERIALS])
    rho = np.array([m.rho for m in MATERIALS])
    impacts = [fastrest.Impact(MATERIALS[k], r) for k, r in zip(kind, radius)]
    # speeds from just above yield to well into the plastic range (V1* = 1.05 .. 100)
    v1_star = np.exp(rng.uniform(math.log(1.05), math.log(100.0), n_particles))
    speed = np.array([v * imp.V_c for v, imp in zip(v1_star, impacts)])
    # one law per material (normalised: the radius enters through omega_c and P_c), stacked
    laws = stack_laws([fastrest.Impact(m, 1e-3).contact_law(unloading) for m in MATERIALS])
    out = np.empty((n_particles, 3))
    omega_c, P_c, mass = np.empty(n_particles), np.empty(n_particles), np.empty(n_particles)
    dt = setup(kind, E, nu, Sy, rho, radius, speed, 1.0 / steps_per_contact, omega_c, P_c, mass)
    simulate(laws, kind[:1], omega_c, P_c, mass, speed, dt, out)  # compile
    t0 = time.perf_counter()
    simulate(laws, kind, omega_c, P_c, mass, speed, dt, out)
    seconds = time.perf_counter() - t0
    curves = [fastrest.curve(fastrest.Impact(m, 1e-3).eps_y, m.nu, unloading, v_max=100.0) for m in MATERIALS]
    e_curve = np.array([curves[k].e(float(s / imp.V_c)) for k, s, imp in zip(kind, speed, impacts)])
    return out[:, 1], e_curve, seconds, int(out[:, 2].sum())


def main(argv):
    n = int(argv[1]) if len(argv) > 1 else 300
    steps = int(argv[2]) if len(argv) > 2 else 4000
    e_dem, e_curve, seconds, total = run(n, steps)
    err = np.abs(e_dem / e_curve - 1)
    print(f"{n} particles, 3 materials, global time step = shortest Hertz contact time / {steps}")
    print(f"  e from the time-stepped contact law vs Curve.e (energy balance): worst relative "
          f"difference {err.max():.2e}, median {np.median(err):.2e}")
    print(f"  {total} force evaluations in {seconds:.3f} s ({seconds / total * 1e9:.1f} ns per step "
          f"and particle, {numba.get_num_threads()} threads)")
    return err.max()


if __name__ == "__main__":
    main(sys.argv)
