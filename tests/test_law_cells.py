"""The contact law's tabulated residual (fastrest.law_cells) against the unloading models' formulas.

The law stores delta = w_max - w_res* from cells beside P*'s (``ForwardData.law_rows``); 0.2
computed it from the formula (eq 35, eqs 33-34, Brake's) when a contact first unloaded. Searched,
for materials at the corners of the validated range and the middle, each unloading model, and
strain hardening: every cell's edges and the points one ulp either side, w = 1, 1.9 and their
neighbours, the law's end and one ulp below, 64 points inside every cell, then a bounded local
maximisation around the 40 worst points of each law. Reference: ``fastrest.unloading.residual``
(the formulas in doubles) with P* of ``fastrest.loading.p_star_unchecked``; JCG's formula is
checked against 40-digit mpmath at a few points. Worst found (2026-11-28): relative error of
delta 3.3e-14 (Etsion, eps_y = 0.01, nu = 0.45, at the cell edge w = 260.0625; JCG 2.6e-14 at
w = 65.003, Brake 2.3e-14, hardening 1.7e-14), the level of the P* cells (~1e-14). The unloading
force P_max s^1.5, s = (w - w_res*)/delta, moves by 1.5 (1 - s)/s of that relative: within 1e-12
relative for s >= 0.05 and within 5e-14 of P_max everywhere on the branch (asserted); towards
separation (s -> 0) the force goes to 0 and its error is absolute. Extrapolated towards JCG's end
(w_m* = 10017.5), where delta -> 0: absolute error of delta 3.3e-12 (at w = 8318).
"""
import math
import warnings

import numba
import numpy as np
import pytest

import fastrest
from fastrest import jit as frj
from fastrest.forward import P_table_forward
from fastrest.law_cells import law_step, law_step_branching
from fastrest.loading import p_star_unchecked
from fastrest.unloading import residual

MATERIALS = [(0.0005, 0.2), (0.0005, 0.45), (0.01, 0.2), (0.01, 0.45), (0.005, 0.33)]
LAWS = [(e, n, m, 0.0) for e, n in MATERIALS for m in ("jcg", "etsion", "brake")]
LAWS += [(e, n, "brake", et) for e, n in ((0.0005, 0.2), (0.01, 0.45)) for et in (0.01, 0.05)]
LAWS += [(0.005, 0.33, "jcg", 0.01)]
#: bounds the search must stay under (about 3x the worst found, see the module doc)
DELTA_RTOL = 1e-13
FORCE_RTOL = 1e-12     # for s = (w - w_res*)/delta >= 0.05
FORCE_ATOL = 5e-14     # in units of P_max, everywhere on the branch


def _law(eps_y, nu, model, et):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fastrest.contact_law(eps_y, nu, model, et_ratio=et)


@numba.njit
def _deltas(data, w, got, want):
    """The law's delta after a virgin step to w, and the formula's."""
    st = np.zeros(4)
    for j in range(w.size):
        st[:] = 0.0
        frj.contact_force(data, st, w[j])
        got[j] = st[3]
        x = w[j]
        p = p_star_unchecked(data.law, x, data.eps_y, data.nu, data.et_ratio)
        want[j] = residual(data.model, x, x - 1.0, p, data.eps_y, data.nu, data.law, data.et_ratio)[1]


def _rel(data, w):
    w = np.ascontiguousarray(w, dtype=np.float64)
    got, want = np.empty(w.size), np.empty(w.size)
    _deltas(data, w, got, want)
    return np.abs(got / want - 1.0), got, want


def _search_points(data):
    rows = data.law_rows
    half = 1.0 / rows[:, 1]
    lo, hi = rows[:, 0] - half, rows[:, 0] + half
    edges = np.unique(np.concatenate([lo, hi]))
    edges = edges[(edges > 1.0) & (edges <= data.w_max)]
    special = np.array([1.0, 1.9, data.w_max])
    pts = np.concatenate([edges, special])
    pts = np.concatenate([pts, np.nextafter(pts, 0.0), np.nextafter(pts, np.inf)])
    u = (np.arange(64) + 0.5) / 64
    inner = (lo[:, None] + (hi - lo)[:, None] * u[None, :]).ravel()
    pts = np.concatenate([pts, inner])
    return np.unique(pts[(pts > 1.0) & (pts <= data.w_max)])


def _worst(data, n_refine=40):
    """Worst relative delta error of one law: the search of the module doc."""
    from scipy.optimize import minimize_scalar
    pts = _search_points(data)
    err, _, _ = _rel(data, pts)
    order = np.argsort(err)[::-1][:n_refine]
    best_w, best = float(pts[order[0]]), float(err[order[0]])
    for k in order:
        a, b = pts[max(k - 1, 0)], pts[min(k + 1, pts.size - 1)]
        if not a < b:
            continue
        r = minimize_scalar(lambda x: -_rel(data, np.array([x]))[0][0], bounds=(a, b), method="bounded",
                            options={"xatol": 1e-15 * b})
        if -r.fun > best:
            best, best_w = -r.fun, float(r.x)
    return best, best_w


@pytest.mark.parametrize("eps_y, nu, model, et", LAWS)
def test_tabulated_residual_matches_the_formula_everywhere(eps_y, nu, model, et):
    law = _law(eps_y, nu, model, et)
    worst, where = _worst(law.data)
    assert worst <= DELTA_RTOL, (worst, where)


def test_reference_residual_is_the_formula_to_rounding():
    mpmath = pytest.importorskip("mpmath")
    mpmath.mp.dps = 40
    for wm in (1.5, 1.9, 2.5, 10.0, 100.0, 425.0):
        want = mpmath.mpf(wm) * (1 - mpmath.mpf("1.02") * (1 - ((mpmath.mpf(wm) + mpmath.mpf("5.9"))
                                                                 / mpmath.mpf("6.9")) ** mpmath.mpf("-0.54")))
        got = residual(0, wm, wm - 1.0, 0.0, 0.005, 0.33, 0, 0.0)[1]
        assert abs(got / float(want) - 1.0) < 1e-15


@pytest.mark.parametrize("model", ["jcg", "etsion", "brake"])
def test_unloading_force_from_the_tabulated_residual(model):
    law = _law(0.0005, 0.2, model, 0.0)
    data = law.data
    worst_w = [_worst(data, n_refine=5)[1], 1.0 + 2**-40, 1.9, np.nextafter(1.9, 2.0), 2.5, 30.0, data.w_max]
    for wm in worst_w:
        st = law.new_state()
        p_max = frj.contact_force(data, st, wm)
        _, _, want = _rel(data, np.array([wm]))
        delta = want[0]
        for s in (1.0, 0.5, 1.0 / 3.0, 0.05, 1e-3, 1e-6, 0.0):
            w = wm - (1.0 - s) * delta
            s_exact = (w - (wm - delta)) / delta
            got = frj.contact_force(data, st.copy(), w)
            exact = p_max * max(s_exact, 0.0) ** 1.5
            assert abs(got - exact) <= FORCE_ATOL * p_max, (wm, s, got, exact)
            if s >= 0.05:
                assert abs(got / exact - 1.0) <= FORCE_RTOL, (wm, s, got, exact)


@pytest.mark.parametrize("model, et", [("jcg", 0.0), ("etsion", 0.0), ("brake", 0.01)])
def test_virgin_loading_is_the_02_law_bit_for_bit(model, et):
    law = _law(0.002, 0.3, model, et)
    data = law.data
    w = np.concatenate([np.linspace(0.0, 1.9, 97), [np.nextafter(1.9, 0.0), 1.9, np.nextafter(1.9, 3.0)],
                        np.geomspace(1.9, data.w_max, 301)[1:], _search_points(data)[::7]])
    for x in w:
        st = law.new_state()
        got = frj.contact_force(data, st, x)
        want = x * math.sqrt(x) if x <= 1.9 else P_table_forward(data, x)
        assert got == want, x


def test_jcg_end_extrapolated_absolute_error():
    """Towards JCG's end (w_m* = 10017.5, only with extrapolate) delta -> 0: its error is absolute."""
    law = fastrest.contact_law(0.0005, 0.2, "jcg", extrapolate=True)
    data = law.data
    pts = _search_points(data)
    pts = pts[pts > 5000.0]
    pts = pts[pts < data.w_max]
    _, got, want = _rel(data, pts)
    err = np.abs(got - want)
    assert err.max() <= 1e-11, err.max()


@numba.njit
def _both(rows, last, w_end, w, a, b, out_a, out_b):
    for t in range(w.shape[1]):
        for i in range(w.shape[0]):
            out_a[i, t] = law_step(rows, 0, last, w_end, a[i], w[i, t])
            out_b[i, t] = law_step_branching(rows, 0, last, w_end, b[i], w[i, t])


@pytest.mark.parametrize("model, et", [("jcg", 0.0), ("etsion", 0.0), ("brake", 0.01)])
def test_branch_free_and_branching_steps_agree_bit_for_bit(model, et):
    """ContactLaw.force and ContactLaw.impact step with the branching kernel, DEM loops with the
    branch-free one: the same forces and rows, bit for bit, including NaN cases and 0.2 rows."""
    law = _law(0.002, 0.3, model, et)
    data = law.data
    rng = np.random.default_rng(7)
    w = np.cumsum(rng.normal(0.0, 3.0, (200, 300)), axis=1)
    w[::17, 150] = np.nan
    w[5::23, 100] = data.w_max * 1.5
    w[7::29, 60] = -np.inf
    a = np.zeros((200, 4))
    a[3] = [10.0, 25.0, 0.0, 0.0]    # a 0.2 row, mid-loading: refused
    a[4] = [-1.0, 0.0, 0.0, 0.0]     # no history
    b = a.copy()
    out_a, out_b = np.empty_like(w), np.empty_like(w)
    _both(data.law_rows, data.law_rows.shape[0] - 1, data.w_max, w, a, b, out_a, out_b)
    np.testing.assert_array_equal(out_a, out_b)
    np.testing.assert_array_equal(a, b)
    assert np.isnan(out_a[3]).all() and np.isnan(out_a[4]).all()
    assert (out_a[~np.isnan(out_a)] >= 0.0).all() and np.isfinite(out_a).any()


def test_forward_data_without_contact_cells():
    """Rough surfaces build their forward tables without the law's cells: the contact law then
    gives NaN where it would read them (w > 1), never a number from missing rows."""
    from fastrest import forward
    d = forward.forward_data(0.005, 0.33, w_max=50.0, contact_cells=False)
    assert np.isnan(d.law_rows).all()
    assert frj.contact_force(d, np.zeros(4), 0.5) == 0.5 * math.sqrt(0.5)
    assert math.isnan(frj.contact_force(d, np.zeros(4), 10.0))
    with pytest.raises(TypeError, match="contact_cells"):
        forward.forward_data(0.005, 0.33, w_max=50.0, contact_cells="no")
