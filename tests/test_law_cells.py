"""The contact law's tabulated residual (fastrest.law_cells) against the unloading models' formulas.

The law stores delta = w_max - w_res* from cells beside P*'s (``ForwardData.law_rows``); 0.2
computed it from the formula (eq 35, eqs 33-34, Brake's) when a contact first unloaded. Searched,
for the materials at the corners of the validated range (eps_y 0.0005, 0.01 x nu 0.2, 0.45) and
the middle (0.005, 0.33), each unloading model, Brake's at Et/E = 0.01 and 0.05 and JCG's at 0.01:
every cell's edges and the points one ulp either side, w = 1, 1.9 and their neighbours, the law's
end (w* = 425) and one ulp below, 64 points inside every cell, then a bounded local maximisation
around the 40 worst points of each law; and 512 points in every cell with a golden-section
maximisation inside every cell (4096 points in the slow test), which find the same worst.
Reference: ``fastrest.unloading.residual`` (the formulas in doubles) with P* of
``fastrest.loading.p_star_unchecked``, itself checked against 40-digit mpmath (JCG's eq 35, and
Etsion's/Brake's P*/sqrt(A*) with JG's eqs 8-9) to 1e-15.

Worst relative error of delta found (2026-11-28), all inside a cell (at edges <= 1.3e-15):
Etsion 3.30e-14 (eps_y = 0.01, nu = 0.45, w = 260.0625, cell 256 .. 264; 1.8e-14 .. 3.3e-14 over
the materials), JCG 2.58e-14 (w = 65.003, cell 64 .. 66; the same for every material and at Et/E
= 0.01: eq 35 does not depend on them), Brake 1.50e-14 .. 2.32e-14 (0.01, 0.45, w = 260.09),
Brake hardened 1.38e-14 .. 1.68e-14 at Et/E = 0.01, 0.99e-14 .. 1.23e-14 at 0.05. It is the
degree-5 fit's own error (a smooth equioscillation across the cell; the reference agrees with
mpmath to 4e-16 there), the level of the P* cells. Asserted: 1e-13.

The unloading force P_max s^1.5, s = (w - w_res*)/delta, inherits it as 1.5 (1 - s)/s times
delta's relative error; measured at each law's worst w_max and at 1 + 2^-40, 1.9 and 1.9 + ulp,
2.5, 30, 65, 260.0625 and the end, for s = 1, 0.5, 1/3, 0.05, 0.01, 1e-3, 1e-6 and 0 (the
residual): relative 4.9e-14 at s = 0.5, 9.4e-13 at s = 0.05, 4.9e-11 at s = 1e-3, 4.9e-8 at
s = 1e-6 (so 1e-12 relative holds for s >= 0.05 only, with no margin there); absolute at most
1.9e-14 of P_max (at s ~ 1/3). Asserted: relative <= 1.5 (1 - s)/s * 1e-13 + 1e-15 for s > 0,
absolute <= 5e-14 P_max everywhere. Extrapolated towards JCG's end (w_m* = 10017.5), where delta
-> 0: absolute error of delta 3.3e-12 (at w = 8320.5), 4e-13 at the end itself (the formula's
0, the law's +4e-13: a contact loaded to the end still has a history, delta > 0).

Virgin loading: bit for bit 0.2's (Hertz w sqrt(w) to 1.9, ``P_table_forward`` above).
"""
import functools
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
LAWS += [(e, n, "brake", et) for e, n in MATERIALS for et in (0.01, 0.05)]
LAWS += [(e, n, "jcg", 0.01) for e, n in MATERIALS]
#: bounds the search must stay under (about 3x the worst found, see the module doc)
DELTA_RTOL = 1e-13
FORCE_ATOL = 5e-14     # in units of P_max, everywhere on the branch
#: unloading-branch points: s = (w - w_res*)/delta
S_VALUES = (1.0, 0.5, 1.0 / 3.0, 0.05, 1e-2, 1e-3, 1e-6, 0.0)


def force_rtol(s):
    """Relative bound of the unloading force at s > 0: delta's bound, carried by 1.5 (1 - s)/s."""
    return 1.5 * (1.0 - s) / s * DELTA_RTOL + 1e-15


@functools.lru_cache(maxsize=None)
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


def _cells(data):
    """(lo, hi) of every row's cell, clipped to 1 .. the law's end (empty cells dropped)."""
    rows = data.law_rows
    half = 1.0 / rows[:, 1]
    lo = np.maximum(rows[:, 0] - half, 1.0)
    hi = np.minimum(rows[:, 0] + half, data.w_max)
    keep = hi > lo
    return lo[keep], hi[keep]


def _search_points(data, per_cell=64):
    lo, hi = _cells(data)
    special = np.array([1.0, 1.9, data.w_max])
    pts = np.unique(np.concatenate([lo, hi, special]))
    pts = np.concatenate([pts, np.nextafter(pts, 0.0), np.nextafter(pts, np.inf)])
    u = (np.arange(per_cell) + 0.5) / per_cell
    inner = (lo[:, None] + (hi - lo)[:, None] * u[None, :]).ravel()
    pts = np.concatenate([pts, inner])
    return np.unique(pts[(pts > 1.0) & (pts <= data.w_max)])


@functools.lru_cache(maxsize=None)
def _worst_of(eps_y, nu, model, et):
    return _worst(_law(eps_y, nu, model, et).data)


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


def _worst_every_cell(data, per_cell=512, steps=60):
    """The slow search: ``per_cell`` points in every cell, then a golden-section maximisation
    around each cell's worst point (all cells at once)."""
    lo, hi = _cells(data)
    u = (np.arange(per_cell) + 0.5) / per_cell
    pts = lo[:, None] + (hi - lo)[:, None] * u[None, :]
    err = _rel(data, pts.ravel())[0].reshape(pts.shape)
    k = np.argmax(err, axis=1)
    a = lo + (hi - lo) * np.maximum(k - 0.5, 0.0) / per_cell
    b = lo + (hi - lo) * np.minimum(k + 1.5, per_cell) / per_cell
    g = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(steps):
        c1, c2 = b - g * (b - a), a + g * (b - a)
        left = _rel(data, c1)[0] > _rel(data, c2)[0]
        a, b = np.where(left, a, c1), np.where(left, c2, b)
    mid = 0.5 * (a + b)
    found = np.concatenate([err[np.arange(k.size), k], _rel(data, mid)[0]])
    where = np.concatenate([pts[np.arange(k.size), k], mid])
    return float(found.max()), float(where[np.argmax(found)])


@pytest.mark.parametrize("eps_y, nu, model, et", LAWS)
def test_tabulated_residual_matches_the_formula_everywhere(eps_y, nu, model, et):
    worst, where = _worst_of(eps_y, nu, model, et)
    assert worst <= DELTA_RTOL, (worst, where)


@pytest.mark.parametrize("eps_y, nu, model, et", LAWS)
def test_residual_at_and_below_one_is_w(eps_y, nu, model, et):
    """Up to w = 1 the law stores delta = w (w_res* = 0): the formulas' value there, exactly."""
    data = _law(eps_y, nu, model, et).data
    w = np.array([1e-300, 1e-8, 0.5, np.nextafter(1.0, 0.0), 1.0])
    _, got, want = _rel(data, w)
    np.testing.assert_array_equal(got, w)
    np.testing.assert_array_equal(want, w)


@pytest.mark.parametrize("eps_y, nu, model, et", LAWS)
def test_tabulated_residual_every_cell_maximised(eps_y, nu, model, et):
    worst, where = _worst_every_cell(_law(eps_y, nu, model, et).data)
    assert worst <= DELTA_RTOL, (worst, where)


@pytest.mark.slow
@pytest.mark.parametrize("eps_y, nu, model, et", LAWS)
def test_tabulated_residual_every_cell_maximised_dense(eps_y, nu, model, et):
    worst, where = _worst_every_cell(_law(eps_y, nu, model, et).data, per_cell=4096, steps=80)
    assert worst <= DELTA_RTOL, (worst, where)


def test_reference_residual_is_the_formula_to_rounding():
    mpmath = pytest.importorskip("mpmath")
    mpf = mpmath.mpf
    old_dps, mpmath.mp.dps = mpmath.mp.dps, 40
    try:
        for wm in (1.5, 1.9, 2.5, 10.0, 65.0034, 100.0, 425.0):
            want = mpf(wm) * (1 - mpf("1.02") * (1 - ((mpf(wm) + mpf("5.9")) / mpf("6.9")) ** mpf("-0.54")))
            got = residual(0, wm, wm - 1.0, 0.0, 0.005, 0.33, 0, 0.0)[1]
            assert abs(got / float(want) - 1.0) < 1e-15, wm
        # Etsion (eq 33, A* of eq 8) and Brake (A* = w): delta = P*/sqrt(A*), P* of JG's eq 9
        for eps_y, nu in ((0.0005, 0.2), (0.01, 0.45), (0.005, 0.33)):
            e, n = mpf(eps_y), mpf(nu)
            C = mpf("1.295") * mpmath.exp(mpf("0.736") * n)
            B = mpf("0.14") * mpmath.exp(23 * e)
            for wm in (2.5, 30.0, 259.87, 260.0625, 424.9):
                w = mpf(wm)
                area = w * (w / mpf("1.9")) ** B
                a_over_r = mpmath.pi * C * e / 2 * mpmath.sqrt(area)
                h = mpf("2.84") - mpf("0.92") * (1 - mpmath.cos(mpmath.pi * a_over_r))
                p = (mpmath.exp(-w ** (mpf(5) / 12) / 4) * w ** mpf("1.5")
                     + 4 * h / C * (1 - mpmath.exp(-w ** (mpf(5) / 9) / 25)) * w)
                for model, a in ((1, area), (2, w)):
                    law = _law(eps_y, nu, ("jcg", "etsion", "brake")[model], 0.0)
                    assert law.data.model == model
                    p64 = p_star_unchecked(law.data.law, wm, eps_y, nu, 0.0)
                    got = residual(model, wm, wm - 1.0, p64, eps_y, nu, law.data.law, 0.0)[1]
                    assert abs(got / float(p / mpmath.sqrt(a)) - 1.0) < 1e-15, (eps_y, nu, model, wm)
    finally:
        mpmath.mp.dps = old_dps


@pytest.mark.parametrize("eps_y, nu, model, et", LAWS)
def test_unloading_force_from_the_tabulated_residual(eps_y, nu, model, et):
    law = _law(eps_y, nu, model, et)
    data = law.data
    maxima = [_worst_of(eps_y, nu, model, et)[1], 1.0 + 2**-40, 1.9, np.nextafter(1.9, 2.0), 2.5, 30.0, 65.0034,
              260.0625, np.nextafter(data.w_max, 0.0), data.w_max]
    for wm in maxima:
        st = law.new_state()
        p_max = frj.contact_force(data, st, wm)
        _, _, want = _rel(data, np.array([wm]))
        delta = want[0]
        for s in S_VALUES:
            w = wm - (1.0 - s) * delta
            s_exact = (delta - (wm - w)) / delta       # as the kernel forms it, with the formula's delta
            got = frj.contact_force(data, st.copy(), w)
            exact = p_max * max(s_exact, 0.0) ** 1.5
            assert abs(got - exact) <= FORCE_ATOL * p_max, (wm, s, got, exact)
            if s > 0.0:
                assert abs(got / exact - 1.0) <= force_rtol(s_exact), (wm, s, got, exact)


@pytest.mark.parametrize("eps_y, nu", MATERIALS)
@pytest.mark.parametrize("model, et", [("jcg", 0.0), ("etsion", 0.0), ("brake", 0.01), ("brake", 0.05)])
def test_virgin_loading_is_the_02_law_bit_for_bit(eps_y, nu, model, et):
    law = _law(eps_y, nu, model, et)
    data = law.data
    w = np.concatenate([np.linspace(0.0, 1.9, 97), [np.nextafter(1.0, 0.0), 1.0, np.nextafter(1.0, 2.0),
                                                    np.nextafter(1.9, 0.0), 1.9, np.nextafter(1.9, 3.0),
                                                    np.nextafter(data.w_max, 0.0), data.w_max],
                        np.geomspace(1.9, data.w_max, 301)[1:], _search_points(data, per_cell=4)])
    for x in w:
        st = law.new_state()
        got = frj.contact_force(data, st, x)
        want = x * math.sqrt(x) if x <= 1.9 else P_table_forward(data, x)
        assert got == want, x
        assert st[1] == got


def test_jcg_end_extrapolated_absolute_error():
    """Towards JCG's end (w_m* = 10017.5, only with extrapolate) delta -> 0: its error is absolute;
    the law's delta stays > 0 up to the end itself, so a contact loaded there keeps its history."""
    law = fastrest.contact_law(0.0005, 0.2, "jcg", extrapolate=True)
    data = law.data
    assert data.w_max == pytest.approx(10017.523577897808, rel=1e-15)
    pts = _search_points(data)
    pts = pts[pts > 425.0]
    with np.errstate(divide="ignore", invalid="ignore"):
        _, got, want = _rel(data, pts)
    err = np.abs(got - want)
    assert err.max() <= 1e-11, (err.max(), pts[np.argmax(err)])
    near = np.linspace(data.w_max - 10.0, data.w_max, 20001)
    near = np.concatenate([near, np.nextafter(data.w_max, 0.0) - np.arange(64.0) * 2e-12])
    with np.errstate(divide="ignore", invalid="ignore"):
        _, got, want = _rel(data, near)
    assert (got > 0.0).all() and np.abs(got - want).max() <= 1e-11
    st = law.new_state()
    frj.contact_force(data, st, data.w_max)
    assert frj.contact_force(data, st, data.w_max - 0.5) == 0.0 and st[3] > 0.0


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


@pytest.mark.parametrize("bits", [4, 6])
def test_law_cells_do_not_follow_the_tables_cell_width(bits):
    """The law's cells are always 2^5 per octave (its index is fixed): a forward table of another
    width still carries them, not its own cells read at the wrong index."""
    from fastrest import forward
    base = forward.forward_data(0.005, 0.33, "etsion", w_max=50.0)
    other = forward.forward_data(0.005, 0.33, "etsion", w_max=50.0, bits_per_octave=bits)
    np.testing.assert_array_equal(other.law_rows, base.law_rows)
    assert frj.contact_force(other, np.zeros(4), 10.0) == frj.contact_force(base, np.zeros(4), 10.0)
