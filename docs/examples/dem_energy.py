"""Energy bookkeeping in a DEM loop: the energy every contact dissipated, summed, is the kinetic energy lost.

Run from anywhere (it writes no file)::

    python docs/examples/dem_energy.py [n_spheres] [steps_per_contact]

A row of spheres of two strain-hardening materials (steel and an aluminium alloy, each with its
tangent modulus Et) moves on a line between two rigid walls, with random radii and velocities:
every sphere collides with its neighbours and the walls, again and again, and each contact (a pair
of neighbours, or a sphere and a wall) keeps its own history row for its whole life. One
``@numba.njit`` function runs everything per contact, as a DEM code's force loop would:

* the critical scales of each contact from the two bodies' E, nu, Sy, radii and masses
  (:func:`fastrest.jit.critical_scales`; a wall is E = R = m = Sy = inf), and the strain hardening
  of the body that yields first, Et/E (:func:`fastrest.jit.yield_et_ratio`), which the contact's
  law was built with;
* at every step the normal force of each contact from :func:`fastrest.jit.contact_force_stacked`
  (loading along Ghaednia et al.'s hardening law, Brake's elastic unloading and reloading), and
  velocity Verlet with one global time step;
* at the end, the energy each contact has dissipated, :func:`fastrest.jit.dissipated_energy_stacked`
  (in units of the contact's U_c), times U_c.

The contact law depends on the pair of materials only (eps_y = Sy/E' and nu of the body that
yields first, and its Et/E), so there are five laws (steel-wall, alu-wall, steel-steel,
steel-alu, alu-alu), stacked; radii and masses enter through each contact's omega_c, P_c and U_c.
The run stops at the first step after ``duration`` where no contact is loaded (every contact
separated: no elastic energy stored), and compares the kinetic energy lost with the sum of the
dissipated energies.
"""
import math
import sys
import time

import numba
import numpy as np

import fastrest
from fastrest import jit as frj
from fastrest.force_law import stack_laws

#: (E Pa, nu, Sy Pa, rho kg/m^3, Et Pa): steel, aluminium alloy (every eps_y in the validated range)
MATERIALS = np.array([[200e9, 0.30, 1.0e9, 7800.0, 1.0e9],
                      [70e9, 0.33, 0.28e9, 2700.0, 1.4e9]])
INF = math.inf


def _bodies(kind_a, kind_b):
    """The two bodies' (E, nu, Sy, Et) of a contact; kind -1 is the rigid wall."""
    a = MATERIALS[kind_a]
    b = MATERIALS[kind_b] if kind_b >= 0 else np.array([INF, 0.0, INF, 0.0, 0.0])
    return a, b


def law_index(kind_a, kind_b):
    """Index of the stacked law of a contact between kinds a and b (-1: a wall): 0, 1 against the
    wall; 2, 3, 4 for steel-steel, steel-alu, alu-alu."""
    if kind_b < 0:
        return kind_a
    lo, hi = min(kind_a, kind_b), max(kind_a, kind_b)
    return 2 + lo + hi


def build_laws(unloading="brake"):
    """The five contact laws (normalised), from the same critical values and Et/E the loop uses."""
    laws = []
    for ka, kb in ((0, -1), (1, -1), (0, 0), (0, 1), (1, 1)):
        a, b = _bodies(ka, kb)
        # eps_y and nu do not depend on radius or mass: any positive ones do
        s = frj.critical_scales(a[0], a[1], a[2], 1e-3, 1.0, b[0], b[1], b[2], 1e-3 if kb >= 0 else INF,
                                1.0 if kb >= 0 else INF)
        h = frj.yield_et_ratio(a[0], a[1], a[2], a[4], b[0], b[1], b[2], b[4])
        laws.append(fastrest.contact_law(s.eps_y, s.nu, unloading, et_ratio=h))
    return stack_laws(laws)


@numba.njit
def _contact(laws, mats, kind, radius, mass, c, n):
    """Critical scales of contact c (0: left wall and sphere 0; c: spheres c-1 and c; n: sphere
    n-1 and the right wall): (law index, omega_c, P_c, U_c, V_c)."""
    i = c - 1 if c > 0 else 0
    j = c if c < n else n - 1
    wall = c == 0 or c == n
    ka = kind[i] if c > 0 else kind[0]
    a = mats[ka]
    if wall:
        s = frj.critical_scales(a[0], a[1], a[2], radius[j if c == 0 else i], mass[j if c == 0 else i],
                                INF, 0.0, INF, INF, INF)
        h = frj.yield_et_ratio(a[0], a[1], a[2], a[4], INF, 0.0, INF, 0.0)
        k = ka
    else:
        b = mats[kind[j]]
        s = frj.critical_scales(a[0], a[1], a[2], radius[i], mass[i], b[0], b[1], b[2], radius[j], mass[j])
        h = frj.yield_et_ratio(a[0], a[1], a[2], a[4], b[0], b[1], b[2], b[4])
        lo, hi = min(ka, kind[j]), max(ka, kind[j])
        k = 2 + lo + hi
    if h != laws.et_ratio[k] or s.eps_y != laws.eps_y[k]:  # the law was built for this pair
        k = -1
    return k, s.omega_c, s.P_c, s.U_c, s.V_c


@numba.njit
def simulate(laws, mats, kind, radius, mass, x, v, length, steps_per_contact, duration):
    """Move the row until ``duration`` (s) has passed and no contact is loaded. Returns
    (kinetic energy lost J, dissipated energy J, steps, time s, number of contacts that yielded)."""
    n = x.size
    nc = n + 1
    law_k = np.empty(nc, np.int64)
    omega_c, P_c, U_c = np.empty(nc), np.empty(nc), np.empty(nc)
    dt = math.inf
    v_rel = 2.0 * np.max(np.abs(v))  # the fastest approach any contact can see
    for c in range(nc):
        law_k[c], omega_c[c], P_c[c], U_c[c], V_c = _contact(laws, mats, kind, radius, mass, c, n)
        if law_k[c] < 0:
            return np.nan, np.nan, 0, 0.0, 0
        dt = min(dt, frj.hertz_contact_time(v_rel / V_c) * omega_c[c] / V_c / steps_per_contact)
    state = np.zeros((nc, frj.STATE_SIZE))
    ke0 = 0.5 * np.sum(mass * v * v)
    f = np.zeros(nc)
    acc = np.zeros(n)
    t = 0.0
    steps = 0
    while True:
        steps += 1
        t += dt
        for i in range(n):
            x[i] += v[i] * dt + 0.5 * acc[i] * dt * dt
        loaded = False
        for c in range(nc):  # overlap of each contact (m), then its force (N)
            if c == 0:
                overlap = radius[0] - x[0]
            elif c == n:
                overlap = x[n - 1] + radius[n - 1] - length
            else:
                overlap = radius[c - 1] + radius[c] - (x[c] - x[c - 1])
            f[c] = P_c[c] * frj.contact_force_stacked(laws, law_k[c], state[c], overlap / omega_c[c])
            loaded = loaded or f[c] != 0.0
            if f[c] != f[c]:
                return np.nan, np.nan, steps, t, 0
        for i in range(n):  # contact i pushes sphere i to +x, contact i + 1 to -x
            a_new = (f[i] - f[i + 1]) / mass[i]
            v[i] += 0.5 * (acc[i] + a_new) * dt
            acc[i] = a_new
        if t >= duration and not loaded:
            break
    lost = ke0 - 0.5 * np.sum(mass * v * v)
    dissipated = 0.0
    yielded = 0
    for c in range(nc):
        dissipated += U_c[c] * frj.dissipated_energy_stacked(laws, law_k[c], state[c])
        yielded += state[c, 0] > 1.0
    return lost, dissipated, steps, t, yielded


def run(n_spheres=30, steps_per_contact=1000, seed=3, collisions=6.0, unloading="brake"):
    """Simulate the row; return (kinetic energy lost J, sum of dissipated energies J, seconds,
    steps, contacts that yielded)."""
    rng = np.random.default_rng(seed)
    kind = rng.integers(0, 2, n_spheres)
    radius = rng.uniform(1e-3, 3e-3, n_spheres)
    mass = 4.0 / 3.0 * math.pi * radius**3 * MATERIALS[kind, 3]
    gap = rng.uniform(0.5e-3, 2e-3, n_spheres + 1)
    x = np.cumsum(gap[:-1] + radius + np.concatenate([[0.0], radius[:-1]]))
    length = x[-1] + radius[-1] + gap[-1]
    v = rng.uniform(-1.0, 1.0, n_spheres)  # m/s
    duration = collisions * np.mean(gap) / np.mean(np.abs(v))  # each sphere meets a few others
    laws = build_laws(unloading)
    simulate(laws, MATERIALS, kind, radius, mass, x.copy(), v.copy(), length, 10, 0.0)  # compile
    t0 = time.perf_counter()
    lost, dissipated, steps, _, yielded = simulate(laws, MATERIALS, kind, radius, mass, x, v, length,
                                                   steps_per_contact, duration)
    return lost, dissipated, time.perf_counter() - t0, steps, yielded


def main(argv):
    n = int(argv[1]) if len(argv) > 1 else 30
    steps = int(argv[2]) if len(argv) > 2 else 1000
    lost, dissipated, seconds, total, yielded = run(n, steps)
    print(f"{n} spheres of 2 hardening materials between two walls, {n + 1} contacts ({yielded} yielded), "
          f"time step = shortest Hertz contact time / {steps}")
    print(f"  kinetic energy lost {lost:.10e} J, sum of dissipated energies {dissipated:.10e} J: "
          f"relative difference {abs(dissipated / lost - 1):.2e}")
    print(f"  {total} steps in {seconds:.3f} s")
    return abs(dissipated / lost - 1)


if __name__ == "__main__":
    main(sys.argv)
