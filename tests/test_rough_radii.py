"""Explicit rough surfaces whose summits have their own radii (``RoughSurface(..., radii=)``).

References, none from the code under test:

* one radius given as ``radii`` (every summit the same) equals ``R_a`` bit for bit;
* :func:`reference_radii`, below: every summit its own :class:`fastrest.Impact` (omega_c, P_c,
  U_c of its radius, JGM eqs 4, 6, 24), its loading energy by quadrature of the loading law
  (:func:`fastrest.energy.f_star_kernel`), its unloading by the single-sphere solver's
  :func:`fastrest.unloading.restitution_kernel`, the flat's position in metres from
  :func:`scipy.optimize.brentq` on sum_i U_c,i F(omega_i/omega_c,i) = M V1^2 / 2: no forward
  table, no radius ratio, no rough kernel;
* a lone summit against the single-sphere solver (``fastrest.Impact``) of its radius.
"""
import math
import pickle

import numpy as np
import pytest
from scipy.optimize import brentq

import fastrest
from fastrest import loading as _loading
from fastrest import rough
from fastrest._validation import OMEGA_M_STAR_MAX
from fastrest.energy import f_star_kernel
from fastrest.unloading import restitution_kernel, unloading_code

STEEL = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
FIELDS = ("e", "loss", "d_min", "force_max", "n_contact", "n_yielded", "dissipated", "w_star_max")


def reference_radii(material, heights, radii, V1, M, unloading="jcg", et_ratio=0.0):
    """Brute-force impact (dict of RoughImpact's scalar fields) of a flat of mass M (kg) at V1 (m/s)
    on summits at ``heights`` (m) of ``radii`` (m), everything in SI units per summit."""
    law = _loading.resolve(None, et_ratio).code
    model = unloading_code(unloading)
    z = np.asarray(heights, float)
    imp = [fastrest.Impact(material, float(R), mass=M) for R in radii]
    eps, nu = float(imp[0].eps_y), float(imp[0].nu)
    w_end = float(fastrest.omega_star_limit(eps, nu))
    energy = 0.5 * M * V1**2

    def stored(d):  # J, the flat's surface at height d (m)
        return sum(ip.U_c * f_star_kernel((zi - d) / ip.omega_c, eps, nu, law, et_ratio)
                   for zi, ip in zip(z, imp) if zi > d) - energy

    top = float(z.max())
    lo = top - min(w_end * ip.omega_c + zi - top for zi, ip in zip(z, imp))  # deepest the model allows
    d = brentq(stored, lo, top, xtol=1e-30, rtol=8.9e-16, maxiter=2000)
    out = dict(force_max=0.0, dissipated=0.0, n_contact=0, n_yielded=0, w_star_max=-math.inf)
    for zi, ip in zip(z, imp):
        if zi <= d:
            continue
        w = (zi - d) / ip.omega_c
        f = f_star_kernel(w, eps, nu, law, et_ratio)
        _, loss, _, _ = restitution_kernel(math.sqrt(f), w, w - 1.0, eps, nu, model, law, et_ratio)
        out["force_max"] += ip.P_c * _loading.p_star(law, w, eps, nu, et_ratio)
        out["dissipated"] += ip.U_c * f * loss
        out["n_contact"] += 1
        out["n_yielded"] += w > 1.0
        out["w_star_max"] = max(out["w_star_max"], w)
    out["loss"] = out["dissipated"] / energy
    out["e"] = math.sqrt(1.0 - out["loss"])
    out["d_min"] = d - float(z.mean())
    return out


def mixed_surface(n, seed):
    """n summits: Gaussian heights (sigma 30 nm), radii log-uniform over 20 um to 500 um."""
    g = np.random.default_rng(seed)
    return g.normal(0.0, 30e-9, n), np.exp(g.uniform(math.log(20e-6), math.log(500e-6), n))


@pytest.mark.parametrize("unloading", ["jcg", "etsion", "brake"])
def test_one_radius_as_radii_is_bit_for_bit_R_a(unloading):
    z = rough.gaussian_summits(300, 50e-9, seed=3)
    V = np.geomspace(1e-4, 0.2, 12)
    a = rough.RoughSurface(STEEL, 1e-4, heights=z).impact(V, 0.05, unloading)
    b = rough.RoughSurface(STEEL, heights=z, radii=np.full(z.size, 1e-4)).impact(V, 0.05, unloading)
    for k in FIELDS:
        assert np.array_equal(a[k], b[k]), k


@pytest.mark.parametrize("unloading,et_ratio", [("jcg", 0.0), ("etsion", 0.0), ("brake", 0.0), ("brake", 0.02)])
def test_mixed_radii_against_per_summit_reference(unloading, et_ratio):
    z, R = mixed_surface(40, seed=7)
    s = rough.RoughSurface(STEEL, heights=z, radii=R, et_ratio=et_ratio)
    M = 2e-3
    # from a few summits elastic to many far into the plastic range
    V = [s.impact_params.V_c * math.sqrt(2e-3 / M) * f for f in (0.3, 3.0, 30.0)] + [0.05, 0.2]
    got = s.impact(np.array(V), M, unloading)
    for k, v in enumerate(V):
        ref = reference_radii(STEEL, z, R, v, M, unloading, et_ratio)
        assert got.n_contact[k] == ref["n_contact"] and got.n_yielded[k] == ref["n_yielded"]
        assert got.e[k] == pytest.approx(ref["e"], rel=0, abs=1e-12), (v, got.e[k], ref["e"])
        for f in ("force_max", "dissipated", "w_star_max"):
            assert got[f][k] == pytest.approx(ref[f], rel=1e-9, abs=1e-300), (f, v)
        assert got.d_min[k] == pytest.approx(ref["d_min"], rel=0, abs=1e-12 * np.ptp(z)), v
    assert got.n_contact[-1] > 20 and got.n_yielded[-1] > 5  # the cases above reach plasticity


@pytest.mark.parametrize("R", [30e-6, 400e-6])
def test_lone_summit_is_the_single_sphere(R):
    """The tallest summit alone in contact (the others far below) rebounds as a sphere of its
    radius with the flat's mass on a rigid flat (fastrest.Impact)."""
    z = np.array([0.0, -1e-3, -2e-3])
    s = rough.RoughSurface(STEEL, heights=z, radii=[R, 1e-5, 1e-3])
    M = 1e-3
    V = fastrest.Impact(STEEL, R, mass=M).V_c * np.array([0.5, 3.0, 20.0])  # elastic to w* ~ 100
    got = s.impact(V, M)
    assert np.all(got.n_contact == 1)
    e = fastrest.Impact(STEEL, R, mass=M).e(V)
    np.testing.assert_allclose(got.e, e, rtol=1e-12, atol=0)


def test_small_low_summit_limits_the_range():
    """A small summit below a big one reaches the model's end first: the surface says so (the
    reference summit is far from its own end), and just below that speed the impact is solved with
    that summit's w* reported as the largest."""
    z, R = [0.0, -2e-9], [1e-3, 1e-6]
    s = rough.RoughSurface(STEEL, heights=z, radii=R)
    M = 1e-3
    small = fastrest.Impact(STEEL, 1e-6, mass=M)
    w_end = OMEGA_M_STAR_MAX  # 425, JGM's range
    d_end = z[1] - w_end * small.omega_c  # flat position where the small summit reaches the end
    big = fastrest.Impact(STEEL, 1e-3, mass=M)
    e_end = big.U_c * f_star_kernel((0.0 - d_end) / big.omega_c, s.eps_y, s.nu, 0, 0.0) \
        + small.U_c * f_star_kernel(w_end, s.eps_y, s.nu, 0, 0.0)
    v_end = math.sqrt(2.0 * e_end / M)
    with pytest.raises(ValueError, match=r"beyond w\* = 425"):
        s.impact(1.01 * v_end, M)
    ok = s.impact(0.99 * v_end, M)
    ref = reference_radii(STEEL, z, R, 0.99 * v_end, M)
    assert ok.w_star_max == pytest.approx(ref["w_star_max"], rel=1e-9)
    assert ok.w_star_max > 300.0 and (0.0 - ok.d_min - np.mean(z)) / big.omega_c < 50.0


def test_attributes_params_pickle_repr():
    z, R = mixed_surface(10, seed=2)
    s = rough.RoughSurface(STEEL, heights=z, radii=R)
    k = int(np.argmax(z))
    assert s.R_a == R[k] and s.omega_c == fastrest.Impact(STEEL, R[k], mass=1.0).omega_c
    np.testing.assert_array_equal(s.radii, R)
    np.testing.assert_array_equal(s.heights, z)
    p = s.params()
    assert "R_a" not in p and np.array_equal(p["radii"], R)
    t = pickle.loads(pickle.dumps(s))
    assert not t.heights.flags.writeable and not t.radii.flags.writeable
    V = np.array([0.01, 0.1])
    for other in (t, rough.RoughSurface(**p)):
        assert np.array_equal(other.impact(V, 1e-3).e, s.impact(V, 1e-3).e)
    assert "radii" in repr(s)
    one = rough.RoughSurface(STEEL, 1e-4, heights=z)
    np.testing.assert_array_equal(one.radii, np.full(z.size, 1e-4))
    assert rough.RoughSurface(STEEL, 1e-4, gw=dict(eta=1e10, sigma=5e-8)).radii is None


def test_sweep_ships_radii():
    z, R = mixed_surface(10, seed=5)
    s = rough.RoughSurface(STEEL, heights=z, radii=R)
    res = rough.sweep([s, dict(material=STEEL, heights=z, radii=R)], [0.01, 0.1], 1e-3)
    assert np.array_equal(res[0].e, res[1].e) and np.array_equal(res[0].e, s.impact([0.01, 0.1], 1e-3).e)


@pytest.mark.parametrize("kwargs,exc,match", [
    (dict(heights=[0.0, 1e-8], radii=[1e-4]), ValueError, "one radius .* per summit: 2 heights, 1 radii"),
    (dict(heights=[0.0, 1e-8], radii=[1e-4, 0.0]), ValueError, r"radii\[1\] = 0.0"),
    (dict(heights=[0.0, 1e-8], radii=[1e-4, float("nan")]), ValueError, r"radii\[1\] = nan"),
    (dict(heights=[0.0, 1e-8], radii=[1e-4, -1e-4]), ValueError, "finite and > 0"),
    (dict(heights=[0.0, 1e-8], radii=["a", "b"]), TypeError, "radii"),
    (dict(R_a=1e-4, heights=[0.0], radii=[1e-4]), ValueError, "not both"),
    (dict(gw=dict(eta=1e10, sigma=5e-8), radii=[1e-4]), ValueError, "needs explicit summits"),
    (dict(heights=[0.0]), TypeError, "give R_a"),
    (dict(heights=[0.0, 1e-8], radii=[1e-4, 1e300]), ValueError, r"radii\[1\]"),
])
def test_bad_radii(kwargs, exc, match):
    with pytest.raises(exc, match=match):
        rough.RoughSurface(STEEL, **kwargs)
