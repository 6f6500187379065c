"""Random points of the validated domain (fixed seed) and exact reference values.

Materials: the four corners of the validated (eps_y, nu) rectangle, the centre material
(eps_y = 0.005, nu = 0.33), and random ones uniform in the rectangle. Speeds: per material,
log-uniform in [1, V1*_max(eps_y, nu)] (V1*_max: w_m* = 425), plus hard cases (V1* -> 1, both sides of
the Hertz/JG switch 1.9^1.25, V1*_max itself) in the error set.
"""
from dataclasses import dataclass

import numpy as np

from fastrest._validation import EPS_Y_VALIDATED, NU_VALIDATED
import fastrest
from fastrest.direct import impact_array
from fastrest.energy import V_SWITCH
from fastrest.unloading import ETSION, JCG

SEED = 20100217  # fixed: Nonlinear Dyn. 60:217
CENTRE = (0.005, 0.33)

__all__ = ["SEED", "CENTRE", "hard_speeds", "PointSet", "materials", "point_set", "reference", "rel_error", "worst",
           "error_subset"]


def hard_speeds(vmax):
    return np.array([1.0, 1 + 1e-12, 1 + 1e-9, V_SWITCH * (1 - 1e-12), V_SWITCH * (1 + 1e-12),
                     V_SWITCH * (1 + 1e-6), 3.0, 60.0, vmax * (1 - 1e-9), vmax])


@dataclass
class PointSet:
    """Points grouped by material: material k owns v[start[k]:start[k + 1]]."""

    eps_m: np.ndarray      # (K,) materials
    nu_m: np.ndarray
    vmax_m: np.ndarray
    v: np.ndarray          # all points, grouped by material
    eps_y: np.ndarray
    nu: np.ndarray
    start: np.ndarray      # (K + 1,)

    @property
    def size(self):
        return self.v.size

    def chunk(self, k):
        return self.v[self.start[k]:self.start[k + 1]]

    def shuffled(self, seed=SEED):
        """(v, eps_y, nu) in a random order: every point its own material, as in a DEM step."""
        p = np.random.default_rng(seed).permutation(self.size)
        return self.v[p], self.eps_y[p], self.nu[p]


def materials(n_materials, seed=SEED):
    lo_e, hi_e = EPS_Y_VALIDATED
    lo_n, hi_n = NU_VALIDATED
    fixed = [CENTRE, (lo_e, lo_n), (lo_e, hi_n), (hi_e, lo_n), (hi_e, hi_n)]
    rng = np.random.default_rng(seed)
    k = max(0, n_materials - len(fixed))
    eps = np.concatenate([[f[0] for f in fixed], rng.uniform(lo_e, hi_e, k)])[:n_materials]
    nu = np.concatenate([[f[1] for f in fixed], rng.uniform(lo_n, hi_n, k)])[:n_materials]
    vmax = np.array([fastrest.limit(a, b).v1_star for a, b in zip(eps, nu)])
    return eps, nu, vmax


def point_set(n_materials, per_material, seed=SEED, hard=False):
    """Random speeds, ``per_material`` per material (plus the hard cases if ``hard``)."""
    eps_m, nu_m, vmax_m = materials(n_materials, seed)
    rng = np.random.default_rng(seed + 1)
    vs = []
    for vmax in vmax_m:
        v = np.exp(rng.uniform(0.0, 1.0, per_material) * np.log(vmax))
        vs.append(np.concatenate([hard_speeds(vmax), v]) if hard else v)
    sizes = np.array([x.size for x in vs])
    start = np.concatenate([[0], np.cumsum(sizes)])
    return PointSet(eps_m, nu_m, vmax_m, np.concatenate(vs), np.repeat(eps_m, sizes),
                    np.repeat(nu_m, sizes), start)


def reference(ps):
    """The direct solver at every point: dict of omega_m, e_jcg, loss_jcg, e_etsion, loss_etsion."""
    out = {}
    for m, tag in ((JCG, "jcg"), (ETSION, "etsion")):
        sol = np.empty((5, ps.size))
        impact_array(ps.v, ps.eps_y, ps.nu, np.zeros_like(ps.v), m, False, 0, sol)
        if m == JCG:
            out["omega_m"] = sol[0]
        out["e_" + tag] = sol[1]
        out["loss_" + tag] = sol[2]
    for k, a in out.items():
        if not np.isfinite(a).all():
            raise RuntimeError(f"direct solver gave non-finite {k} on the benchmark points")
    return out


def rel_error(got, ref, floor=0.0):
    """|got - ref| / max(|ref|, floor); the absolute error where that denominator is 0."""
    got = np.asarray(got, dtype=float)
    den = np.maximum(np.abs(ref), floor)
    err = np.abs(got - ref)
    ok = den > 0
    rel = np.where(ok, err / np.where(ok, den, 1.0), err)
    rel[~np.isfinite(got)] = np.inf
    return rel


def worst(got, ref, mask=None, floor=0.0):
    """(worst relative error, index of the worst point) over ``mask``."""
    rel = rel_error(got, ref, floor)
    if mask is not None:
        rel = np.where(mask, rel, -1.0)
    k = int(np.argmax(rel))
    return float(rel[k]), k


def error_subset(ps, per_material):
    """The first ``per_material`` points of every material of ``ps``, plus the hard cases."""
    vs = [np.concatenate([hard_speeds(vmax), ps.chunk(k)[:per_material]])
          for k, vmax in enumerate(ps.vmax_m)]
    sizes = np.array([x.size for x in vs])
    start = np.concatenate([[0], np.cumsum(sizes)])
    return PointSet(ps.eps_m, ps.nu_m, ps.vmax_m, np.concatenate(vs), np.repeat(ps.eps_m, sizes),
                    np.repeat(ps.nu_m, sizes), start)
