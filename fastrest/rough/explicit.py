"""Explicit summit heights: the deepest approach of the flat and the sums over every summit.

Summit i stands h_i = (z_i - z_top)/omega_c below the tallest one (h_i <= 0). With the tallest at
w* = x, summit i is at w_i = h_i + x, and the approach solves the energy balance

    G(x) = sum_i F(w_i) = E,    E = (V1/V_c)^2 = M V1^2 / (2 U_c)         (JGM eq 29, per summit)

by Newton's method on G^0.4 = E^0.4 (exact in one step for one Hertzian summit), the slope from
the total force, dG/dx = (5/2) sum_i P*(w_i), safeguarded by bisection on the bracket
G(lo) < E <= G(hi).

Near the onset of yield the dissipated energy is proportional to w_i - 1, which w_i = h_i + x
cannot resolve when x is close to 1. The iteration therefore carries x and delta = x - 1 side by
side (every step moves both by the same amount; each is accurate where it is small): summit i has
w_i - 1 = h_i + delta, and, while the tallest summit is near the onset (abs(delta) < 1/16), the n_1
summits above w* = 1/2 enter G counted from w* = 1,

    G - E = sum_{w_i > 1/2} (F(w_i) - 1) + sum_{0 < w_i <= 1/2} F(w_i) - (E - n_1),

with F - 1 formed from w_i - 1 and E - n_1 from the exact energy (:mod:`.common`). For one summit
this solves (1 + delta)^2.5 - 1 = E - 1 to full relative accuracy in delta, as the single-sphere
solver does; so for a cluster of summits around the onset. (Summits in contact below w* = 1/2
still limit delta to an absolute ~1e-16 (their F carries the rounding of their heights).)

Summits of their own radii (``RoughSurface(..., radii=)``): each summit is normalised by its own
critical values, omega_c r_i, P_c r_i^2, U_c r_i^3 (JGM eqs 4, 6, 24 scale as R, R^2, R^3), r_i =
R_i/R_ref with the reference the tallest summit (r = 1, h = 0). The reference's w* = x still sets
the flat's position: summit i is at w_i = (h_i + x)/r_i with w_i - 1 = (h_i + (delta + (1 - r_i)))/r_i
(:func:`summit_w`), its energy terms weigh r_i^3, its force r_i^2 (so the Newton slope is still
(5/2) times the force sum); the table must reach the largest w_i (:func:`largest_w`), not x. With
every r_i = 1 each of these operations is exact, so equal radii give the bits of ``R_a=``.

Sums run in ``prange`` over fixed blocks of :data:`BLOCK` summits whose partial sums are added in
block order: results do not depend on the number of threads.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import math

import numpy as np
from numba import prange, types
from numba.extending import overload

from .._doc import doc
from .._jit import jit
from .._threads import run_parallel
from .common import (ROUGH_DOC, FAILED, MAX_ITER, NEEDS_TABLE, OK, ONSET_BAND, energy_excess, hertz_terms, jg_terms,
                     summit_values)

__all__ = ["BLOCK", "hertz_estimate", "solve_impacts", "radius_ratios", "largest_w"]

#: Summits per block of the parallel sums (partial sums added in block order: deterministic).
BLOCK = 8192

# the solver's state: the point (x, delta), the bracket ends (x and delta of each), the last step
_X, _D, _LO_X, _LO_D, _HI_X, _HI_D, _DX_PREV = 0, 1, 2, 3, 4, 5, 6


@jit(inline=True)
def _add_blocks(part):
    """Column totals of per-block partial sums, added in block order."""
    tot = np.zeros(part.shape[1])
    for b in range(part.shape[0]):
        for k in range(part.shape[1]):
            tot[k] += part[b, k]
    return tot


@jit(inline=True)
def summit_w(h_i, r_i, x, delta):
    """w* and w* - 1 of one summit (-) with the reference summit at w* = x, delta = x - 1.

    ``h_i``: its height below the tallest over the reference omega_c (<= 0); ``r_i``: its radius
    over the reference radius. omega_c scales with R (JGM eq 4), so w* = (h_i + x)/r_i and w* - 1 =
    (h_i + (delta + (1 - r_i)))/r_i: with r_i = 1 exactly h_i + x and h_i + delta (bit for bit).
    """
    return (h_i + x) / r_i, (h_i + (delta + (1.0 - r_i))) / r_i


def _ratio(r, i):
    """r[i], or 1.0 where ``r`` is None (one radius: the kernels compile the constant, so a uniform
    surface pays no load and no division); jit code only."""
    raise TypeError("_ratio is for Numba code")


@overload(_ratio)
def _ratio_impl(r, i):
    if isinstance(r, types.NoneType):
        return lambda r, i: 1.0
    return lambda r, i: r[i]


def _one_radius(r):
    """True where ``r`` is None (a compile-time constant); jit code only."""
    raise TypeError("_one_radius is for Numba code")


@overload(_one_radius)
def _one_radius_impl(r):
    if isinstance(r, types.NoneType):
        return lambda r: True
    return lambda r: False


@jit(inline=True)
def _block_sums(row, data, summits, x, delta):
    """Column sums of ``row(data, w, d, r_i, onset)`` (4 values) over the summits in contact,
    h_i + x > 0, at w* = w and w* - 1 = d (:func:`summit_w`), in fixed blocks added in block order.

    ``summits`` = (h, r, descending): r None for one radius; with ``descending`` the heights are
    sorted tallest first and a block stops at its first summit out of contact (the rest of it is
    lower)."""
    h, r, descending = summits
    n = h.size
    nblock = (n + BLOCK - 1) // BLOCK
    part = np.zeros((nblock, 4))
    onset = abs(delta) < ONSET_BAND  # loop-invariant: the plain path costs what it always did
    for b in prange(nblock):
        s0 = s1 = s2 = s3 = 0.0  # accumulate in registers: rows of part share cache lines
        for i in range(b * BLOCK, min(n, (b + 1) * BLOCK)):
            if h[i] + x > 0.0:
                r_i = _ratio(r, i)
                w, d = summit_w(h[i], r_i, x, delta)
                r0, r1, r2, r3 = row(data, w, d, r_i, onset)
                s0 += r0
                s1 += r1
                s2 += r2
                s3 += r3
            elif descending:
                break
        part[b, 0], part[b, 1], part[b, 2], part[b, 3] = s0, s1, s2, s3
    return _add_blocks(part)


# A summit of radius r R (r: over the reference radius) has U_c r^3, P_c r^2 and omega_c r (JGM eqs
# 4, 6, 24): its energy terms weigh r^3, its force r^2 in the reference units; d/dx of its F(w*)
# is (5/2) P*(w*) r^2 (w* = (h + x)/r), so the Newton slope stays the weighted force sum.

@jit(inline=True)
def _energy_row(f, p, k, r):
    """(energy term, its magnitude, P*, counted from 1) of a summit of radius ratio r whose own
    terms are (f, p, k), in the reference summit's units."""
    r2 = r * r
    r3 = r2 * r
    return r3 * f, r3 * abs(f), r2 * p, r3 * k


@jit(inline=True)
def _hertz_row(data, w, d, r, onset):
    """:func:`_energy_row` of a Hertzian summit (``data`` unused)."""
    f, p, k = hertz_terms(w, d, onset)
    return _energy_row(f, p, k, r)


@jit(inline=True)
def _jg_row(data, w, d, r, onset):
    """:func:`_hertz_row` under the loading law of ``data``, the forward table."""
    f, p, k = jg_terms(data, w, d, onset)
    return _energy_row(f, p, k, r)


@jit(inline=True)
def _impact_row(data, w, d, r, onset):
    """(P*, L, 1, yielded) of a summit at the deepest approach (exact P*, JGM eqs 9, 14, 38), P*
    and L in the reference summit's units."""
    _, p, _, loss = summit_values(data, w, d)
    return r * r * p, r * r * r * loss, 1.0, (1.0 if d > 0.0 else 0.0)


@jit(parallel=True)
def _hertz_sums(summits, x, delta):
    """[sum of energy terms, sum of their magnitudes, sum P*, summits counted from w* = 1 (their
    U_c)] with every summit Hertzian (F = w^2.5; terms as :func:`.common.hertz_terms`), weighted
    by each summit's critical values over the reference summit's."""
    return _block_sums(_hertz_row, None, summits, x, delta)


@jit(parallel=True)
def _jg_sums(data, summits, x, delta):
    """:func:`_hertz_sums` under the table's loading law (F and the slope P* from the forward table)."""
    return _block_sums(_jg_row, data, summits, x, delta)


@jit(parallel=True)
def _impact_sums(data, summits, x, delta):
    """[sum P*, sum L, in contact, yielded] at the deepest approach (exact P*, JGM eqs 9, 14, 38)."""
    return _block_sums(_impact_row, data, summits, x, delta)


@jit
def x_reaching(h, r, w):
    """The reference summit's w* (-) at which the first summit reaches w* = ``w``: min_i (w r_i - h_i)
    (``w`` itself for one radius, as the tallest summit, h = 0, leads)."""
    if w == np.inf or _one_radius(r):  # one radius: min_i (w - h_i) = w, as max h_i = 0
        return w
    x = np.inf
    for i in range(h.size):
        x = min(x, w * _ratio(r, i) - h[i])
    return x


@jit
def largest_w(h, r, x):
    """The largest w* (-) of any summit with the reference summit at w* = ``x``: max_i (h_i + x)/r_i
    (``x`` itself for one radius).

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest.rough import explicit
    >>> float(explicit.largest_w(np.array([0.0, -1.0]), np.array([1.0, 0.25]), 2.0))
    4.0
    """
    if _one_radius(r):  # max_i (h_i + x) = x, as max h_i = 0
        return x
    w = -np.inf
    for i in range(h.size):
        w = max(w, (h[i] + x) / _ratio(r, i))
    return w


@jit(inline=True)
def _start(x0, d0):
    """Solver state at (x0, delta0 = x0 - 1), bracketed below by x = 0 (nothing in contact)."""
    st = np.empty(7)
    st[_X], st[_D] = x0, d0
    st[_LO_X], st[_LO_D] = 0.0, -1.0
    st[_HI_X], st[_HI_D] = np.inf, np.inf
    st[_DX_PREV] = np.inf
    return st


@jit(inline=True)
def _advance(st, s_terms, s_abs, p_sum, n_1, e_hi, e_lo):
    """One safeguarded Newton step on G^0.4 = E^0.4 from the point in ``st``, whose sums are
    (s_terms, s_abs, p_sum, n_1) (see :func:`_hertz_sums`); True when converged (the solution is
    then the point in ``st``)."""
    x, d = st[_X], st[_D]
    excess = energy_excess(e_hi, e_lo, n_1)  # E - n_1
    g = s_terms - excess  # G - E
    if g >= 0.0:
        st[_HI_X], st[_HI_D] = x, d
    else:
        st[_LO_X], st[_LO_D] = x, d
    if g == 0.0:
        return True
    near = abs(d) < x  # x > 1/2: delta resolves the position better than x
    scale = min(x, abs(d))
    total = e_hi + g  # G
    if total > 0.0 and p_sum > 0.0:
        # the size of G's terms, in units of x: steps below it are rounding noise
        scale += (s_abs + abs(excess)) / (2.5 * p_sum)
        # G^0.4 - E^0.4 without cancellation
        step = -e_hi**0.4 * math.expm1(0.4 * math.log1p(g / e_hi)) * total**0.6 / p_sum
        dx = abs(step)
        # converged: a step at rounding level, or steps no longer shrinking quadratically
        done = dx <= 4e-16 * scale or (dx < 1e-12 * scale and dx >= 0.5 * st[_DX_PREV])
        st[_DX_PREV] = dx
        if near:
            inside = st[_LO_D] < d + step and d + step < st[_HI_D]
        else:
            inside = st[_LO_X] < x + step and x + step < st[_HI_X]
        if done or inside:
            st[_X], st[_D] = x + step, d + step
            return done
    if st[_HI_X] == np.inf:  # no upper bracket yet: double x
        st[_X], st[_D] = x + x, d + x
        return False
    width = st[_HI_D] - st[_LO_D] if near else st[_HI_X] - st[_LO_X]
    st[_X] = 0.5 * (st[_LO_X] + st[_HI_X])
    st[_D] = 0.5 * (st[_LO_D] + st[_HI_D])
    return width <= 4e-16 * scale


@jit(inline=True)
def _approach(sums, data, summits, e_hi, e_lo, x0, d0, w_table, w_model):
    """(status, x, delta) solving G = E with ``sums(data, summits, x, delta)`` (see :func:`_hertz_sums`).

    Trial points that take a summit beyond ``w_table`` return NEEDS_TABLE with x asked for. Once
    the table reaches ``w_model`` (the model's end), trial points beyond it are moved to it, and
    NEEDS_TABLE means the solution itself is beyond the model.
    """
    w_cap = x_reaching(summits[0], summits[1], min(w_table, w_model))
    st = _start(x0, d0)
    for _ in range(MAX_ITER):
        if st[_X] > w_cap:
            if not (w_table >= w_model and st[_LO_X] < w_cap):
                return NEEDS_TABLE, st[_X], st[_D]
            st[_X], st[_D] = w_cap, w_cap - 1.0
        t = sums(data, summits, st[_X], st[_D])
        if _advance(st, t[0], t[1], t[2], t[3], e_hi, e_lo):
            return (OK if st[_X] <= w_cap else NEEDS_TABLE), st[_X], st[_D]
    return FAILED, st[_X], st[_D]


@jit(inline=True)
def _hertz_law_sums(data, summits, x, delta):
    """:func:`_hertz_sums` with the arguments of :func:`_jg_sums` (``data`` unused)."""
    return _hertz_sums(summits, x, delta)


@jit
def _hertz_approach_kernel(summits, e_hi, e_lo, x0, d0):
    """(status, x, delta) of the impact of energy e_hi + e_lo (over U_c) with every summit Hertzian.

    The estimate (no table) that starts every solve under the loading law and sizes its forward table. ``h``: summit
    heights below the tallest over omega_c (<= 0); ``r``: radii over the reference radius (the
    tallest summit's); (x0, d0): start, w* of the tallest and w* - 1.
    """
    return _approach(_hertz_law_sums, None, summits, e_hi, e_lo, x0, d0, np.inf, np.inf)


@jit
def _jg_approach_kernel(data, summits, e_hi, e_lo, x0, d0, w_model):
    """(status, x, delta) of the deepest approach under the table's loading law (JGM eq 29 summed
    over summits).

    Trial points beyond the table (data.w_max) return NEEDS_TABLE with x the w* asked for. Once
    the table reaches ``w_model`` (the model's end), trial points beyond it are moved to it, and
    NEEDS_TABLE means the solution itself is beyond the model. Arguments as
    :func:`_hertz_approach_kernel`.
    """
    return _approach(_jg_sums, data, summits, e_hi, e_lo, x0, d0, data.w_max, w_model)


@jit
def _hertz_approach_array(summits, e_hi, e_lo, out):
    """out[:, k] = :func:`_hertz_approach_kernel` of impact k, started from the tallest summit alone
    (x0 = E^0.4, with x0 - 1 from E - 1 without cancellation)."""
    for k in range(e_hi.size):
        x0 = e_hi[k]**0.4
        d0 = x0 - 1.0
        if x0 >= 0.5 and x0 <= 2.0:
            d0 = math.expm1(0.4 * math.log1p(energy_excess(e_hi[k], e_lo[k], 1.0)))
        out[0, k], out[1, k], out[2, k] = _hertz_approach_kernel(summits, e_hi[k], e_lo[k], x0, d0)


@jit
def _explicit_impacts_array(data, summits, e_hi, e_lo, x0, d0, w_model, out):
    """out[:, k] = (status, w* needed, x, largest w*, sum P*, sum L, in contact, yielded) of impact k.

    x = w* of the reference (tallest) summit at the deepest approach, the position; the largest w*
    of any summit (:func:`largest_w`) is x itself for one radius.
    """
    for k in range(e_hi.size):
        status, x, d = _jg_approach_kernel(data, summits, e_hi[k], e_lo[k], x0[k], d0[k], w_model)
        w_top = largest_w(summits[0], summits[1], x)
        out[0, k], out[1, k], out[2, k], out[3, k] = status, w_top, x, w_top
        if status == OK:
            t = _impact_sums(data, summits, x, d)
            for j in range(4):
                out[4 + j, k] = t[j]


def radius_ratios(r: NDArray[np.float64] | None, n: int) -> NDArray[np.float64]:
    """Radii over the reference radius as an array: ``r``, or n ones for one radius (the GPU's).

    Examples
    --------
    >>> from fastrest.rough import explicit
    >>> explicit.radius_ratios(None, 2)
    array([1., 1.])
    """
    return np.ones(n) if r is None else r


def _summits(h, r, descending):
    """The kernels' (h, r, descending) (see :func:`_block_sums`; r None for one radius)."""
    return (h, r, bool(descending))


def hertz_estimate(h: NDArray[np.float64], e_hi: NDArray[np.float64], e_lo: NDArray[np.float64],
                   r: NDArray[np.float64] | None = None,
                   descending: bool = False) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The deepest approach of every impact with all summits Hertzian (no forward table).

    Parameters
    ----------
    h : ndarray
        Summit heights below the tallest over omega_c (-), <= 0, contiguous; omega_c of the
        reference summit (the tallest).
    e_hi, e_lo : ndarray
        Impact energies over U_c (-) as double plus correction (:func:`.common.energy_parts`).
    r : ndarray, optional
        Summit radii over the reference radius (-), > 0, 1 for the tallest summit; None: one radius.
    descending : bool
        ``h`` is sorted tallest first: the sums stop at the first summit out of contact.

    Returns
    -------
    (ndarray, ndarray)
        x0: w* of the reference (tallest) summit (-); delta0 = x0 - 1 without cancellation (-).

    Raises
    ------
    RuntimeError
        If the solver fails (a bug: the Hertz balance always has a solution).

    Notes
    -----
    Solves sum_i r_i^3 ((h_i + x)/r_i)^2.5 = E (JGM eq 29 with eq 19 per summit, each summit's
    U_c and omega_c scaled by r_i^3 and r_i); the start of every solve under the loading law and
    the size of its table.

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest.rough import explicit
    >>> x0, d0 = explicit.hertz_estimate(np.array([0.0]), np.array([32.0]), np.array([0.0]))
    >>> float(x0[0]), float(d0[0])
    (4.0, 3.0)
    """
    out = np.zeros((3, e_hi.size))
    run_parallel(_hertz_approach_array, None, _summits(h, r, descending), e_hi, e_lo, out)
    if np.any(out[0] != OK):
        raise RuntimeError("rough-surface solver (Hertz estimate) did not converge (please report)")
    return out[1].copy(), out[2].copy()


@doc(ROUGH_DOC)
def solve_impacts(data: Any, h: NDArray[np.float64], e_hi: NDArray[np.float64], e_lo: NDArray[np.float64],
                  x0: NDArray[np.float64], d0: NDArray[np.float64], w_model: float,
                  r: NDArray[np.float64] | None = None, descending: bool = False) -> NDArray[np.float64]:
    """Impacts on explicit summits under the loading law of the forward table ``data``.

    {params_data}
    h : ndarray
        Summit heights below the tallest over omega_c (-), <= 0.
    e_hi, e_lo : ndarray
        Impact energies over U_c (-), double plus correction (:func:`.common.energy_parts`).
    x0, d0 : ndarray
        Start of each solve: w* of the tallest summit and w* - 1 (:func:`hertz_estimate`).
    w_model : float
        w* (-) where the model ends (425, or a/R = 1 extrapolating).
    r, descending
        As :func:`hertz_estimate`.

    Returns
    -------
    ndarray, shape (8, n)
        Per impact: status (OK; NEEDS_TABLE: grow the table to the w* of row 1, or past the model's
        end once the table reaches it; FAILED), w* needed, x (w* of the tallest summit at the
        deepest approach: the position), the largest w* of any summit (x for one radius), sum P*
        and sum L (over the reference P_c and U_c), summits in contact, summits yielded.

    Notes
    -----
    sum_i r_i^3 F(w_i) = E at the deepest approach (JGM eq 29 per summit) and 1 - e_s^2 =
    sum_i r_i^3 L(w_i)/E with L the energy a summit dissipates (eq 38 with the unloading model of
    ``data``).

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest import forward
    >>> from fastrest.rough import explicit
    >>> data = forward.forward_data(0.005, 0.3, w_max=40.0)
    >>> h, e = np.array([0.0, -0.5]), np.array([50.0])
    >>> x0, d0 = explicit.hertz_estimate(h, e, np.zeros(1))
    >>> out = explicit.solve_impacts(data, h, e, np.zeros(1), x0, d0, 425.0)
    >>> bool(out[0, 0] == 0 and out[6, 0] == 2.0 and 0.0 < out[5, 0] / 50.0 < 1.0)
    True
    """
    out = np.zeros((8, e_hi.size))
    run_parallel(_explicit_impacts_array, None, data, _summits(h, r, descending), e_hi, e_lo, x0, d0, w_model, out)
    return out
