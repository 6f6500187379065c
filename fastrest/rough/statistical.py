"""Statistical (Greenwood-Williamson) surfaces: the deepest approach and the impact's sums.

The approach solves N E[F] = E (the impact energy over U_c; expectations over the summit heights
from :mod:`.expectations`) for the flat's position zs_d = d/sigma by Newton's method on
(N E[F])^0.4 with a bracket search; impacts at different speeds run in parallel.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any
from numpy.typing import ArrayLike, NDArray
import math

import numpy as np
from numba import prange

from .._doc import doc
from .._jit import jit
from .._threads import run_parallel
from .common import ROUGH_DOC, FAILED, MAX_ITER, NEEDS_TABLE, OK
from .expectations import (ZS_UNDERFLOW, gw_hertz_sums_kernel, gw_impact_sums_kernel, gw_jg_sums_kernel, zs_covered_kernel,
                           zs_top_kernel)

__all__ = ["HERTZ_CAP", "check_resolved", "hertz_estimate", "solve_impacts"]

#: The Hertz estimate (the start of every solve under the loading law) stops at this many times the
#: w* where the law ends (a/R = 1): JG summits (and Ghaednia's, whose P* lies between JG's and
#: Hertz's) sink deeper than Hertz ones (bar a few % of force near w* = 1.9), so beyond it so does
#: the impact.
HERTZ_CAP = 4.0


# --- the approach: Newton on (N E[F])^0.4 with a bracket search -----------------------------------

_ZS, _LO, _HI, _STEP, _DX_PREV = 0, 1, 2, 3, 4


@jit(inline=True)
def _start(g, zs0):
    """Solver state from zs0: no bracket yet (a bounded pdf: nothing in contact above zs_hi)."""
    st = np.empty(5)
    st[_LO], st[_HI] = -np.inf, np.inf
    if g.kind == 1:
        st[_HI] = g.zs_hi
    st[_ZS] = zs0 if zs0 < st[_HI] else st[_HI] - 0.5
    st[_STEP], st[_DX_PREV] = 0.5, np.inf
    return st


@jit(inline=True)
def _advance(st, g, e_f, e_p, energy):
    """One step from the point in ``st`` with per-summit expectations (e_f, e_p); True when
    converged (the solution is then the point in ``st``)."""
    zs = st[_ZS]
    n_tot = g.n_total
    gs = n_tot * e_f
    if gs >= energy:
        st[_LO] = zs
    else:
        st[_HI] = zs
    if gs == energy:
        return True
    newton = np.nan
    if gs > 0.0 and e_p > 0.0:
        newton = zs + (gs**0.4 - energy**0.4) * gs**0.6 / (n_tot * g.rho_w * e_p)
    if st[_LO] == -np.inf or st[_HI] == np.inf:
        # no bracket yet: steps doubling away from the start, or Newton's step when it points
        # the same way and goes further (Newton alone creeps up a Gaussian tail, 2.5/zs per step)
        step = st[_STEP]
        zn = zs - step if st[_LO] == -np.inf else zs + step
        if (st[_LO] == -np.inf and newton < zn) or (st[_HI] == np.inf and newton > zn):
            zn = newton
            step *= 0.5
        st[_STEP] = 2.0 * step
        st[_ZS] = zn
        return False
    scale = max(1.0, abs(zs))
    if newton == newton:
        dx = abs(newton - zs)
        if dx <= 4e-16 * scale or (dx < 1e-12 * scale and dx >= 0.5 * st[_DX_PREV]):
            st[_ZS] = newton
            return True
        st[_DX_PREV] = dx
    if newton > st[_LO] and newton < st[_HI]:
        st[_ZS] = newton
        return False
    st[_ZS] = 0.5 * (st[_LO] + st[_HI])
    return st[_HI] - st[_LO] <= 4e-16 * scale


@jit(inline=True)
def _coverage(g, w_cap):
    """zs_d below which the integration would pass w* = w_cap (with a rounding margin)."""
    zs_cov = zs_covered_kernel(g, w_cap)
    return zs_cov + 1e-12 * (1.0 + abs(zs_cov))


@jit(inline=True)
def _approach(sums, data, g, energy, zs0, w_cap, clamp):
    """(status, zs_d, w* at the top) solving N E[F] = energy with ``sums(data, g, zs_d, w_cap)`` ->
    (E[F], E[P*]). Trial points whose heights reach past ``w_cap`` return NEEDS_TABLE, or with
    ``clamp`` (w_cap is the model's end) are moved to it: NEEDS_TABLE then means the solution is
    beyond it."""
    zs_cov = _coverage(g, w_cap)
    st = _start(g, zs0)
    for _ in range(MAX_ITER):
        if st[_ZS] < zs_cov:
            if not (clamp and st[_HI] > zs_cov):
                break
            st[_ZS] = zs_cov
        e_f, e_p = sums(data, g, st[_ZS], w_cap)
        if _advance(st, g, e_f, e_p, energy):
            break
    else:
        return FAILED, st[_ZS], np.nan
    zs = st[_ZS]
    return (OK if zs >= zs_cov else NEEDS_TABLE), zs, (zs_top_kernel(g, zs) - zs) * g.rho_w


@jit(inline=True)
def _hertz_sums(data, g, zs_d, w_cap):
    """:func:`gw_hertz_sums_kernel` with the arguments of :func:`gw_jg_sums_kernel` (``data``, ``w_cap`` unused)."""
    return gw_hertz_sums_kernel(g, zs_d)


@jit
def _gw_hertz_kernel(g, energy, zs0, w_cap):
    """(status, zs_d, w* at the top) of the impact of energy ``energy`` (over U_c) with every
    summit Hertzian: the estimate that starts every solve and sizes its table. Trial points
    whose heights reach past ``w_cap`` are moved to it; NEEDS_TABLE: the solution is beyond it."""
    return _approach(_hertz_sums, None, g, energy, zs0, w_cap, True)


@jit
def _gw_approach_kernel(data, g, energy, zs0, w_model):
    """(status, zs_d, w* at the top) of the deepest approach under the loading law of ``data``.

    A trial point whose heights reach past the table (data.w_max) returns NEEDS_TABLE with the w*
    it needs. Once the table reaches ``w_model`` (the model's end) trial points are moved to it,
    and NEEDS_TABLE means the solution itself is beyond the model.
    """
    return _approach(gw_jg_sums_kernel, data, g, energy, zs0, min(data.w_max, w_model), data.w_max >= w_model)


@jit
def _hertz_one(g, energies, zs0, w_cap, out, k):
    out[0, k], out[1, k], out[2, k] = _gw_hertz_kernel(g, energies[k], zs0, w_cap)


@jit(parallel=True)
def _gw_hertz_array(g, energies, zs0, w_cap, out):
    """out[:, k] = :func:`_gw_hertz_kernel` of impact k, all started at zs0 (in parallel)."""
    for k in prange(energies.size):
        _hertz_one(g, energies, zs0, w_cap, out, k)


@jit
def _gw_hertz_serial(g, energies, zs0, w_cap, out):
    for k in range(energies.size):
        _hertz_one(g, energies, zs0, w_cap, out, k)


@jit
def _impact_one(data, g, energies, zs0, w_model, out, k):
    status, zs, need = _gw_approach_kernel(data, g, energies[k], zs0[k], w_model)
    out[0, k], out[1, k], out[2, k] = status, need, zs
    if status == OK:
        e_p, e_l, p_c, p_y, w_top = gw_impact_sums_kernel(data, g, zs, min(data.w_max, w_model))
        out[3, k], out[4, k], out[5, k], out[6, k], out[7, k] = w_top, e_p, e_l, p_c, p_y


@jit(parallel=True)
def _gw_impacts_array(data, g, energies, zs0, w_model, out):
    """out[:, k] = (status, w* needed, zs_d, w* at the top, E P*, E L, P(contact), P(yield)) of
    impact k, per summit (times N for the surface), in parallel (impacts are independent)."""
    for k in prange(energies.size):
        _impact_one(data, g, energies, zs0, w_model, out, k)


@jit
def _gw_impacts_serial(data, g, energies, zs0, w_model, out):
    for k in range(energies.size):
        _impact_one(data, g, energies, zs0, w_model, out, k)


def _run(n, parallel, serial, *args):
    """n impacts: in parallel from 4 on (fewer: no parallel start-up, no waiting for threads)."""
    if n >= 4:
        return run_parallel(parallel, serial, *args)
    return serial(*args)


def check_resolved(g: Any, energy: NDArray[np.float64], where: Callable[[int], str]) -> None:
    """Refuse impacts too light for the statistical model to resolve (Gaussian heights).

    Parameters
    ----------
    g : GWData
        The surface's height statistics.
    energy : ndarray
        Impact energies over U_c, (V1/V_c)^2 (-).
    where : callable
        ``where(k)``: text naming impact k, for the message.

    Raises
    ------
    ValueError
        If an impact is so light that the flat would stop more than ZS_UNDERFLOW sigma above the
        mean summit plane, where the Gaussian density exp(-zs^2/2) underflows.

    Notes
    -----
    The bound is N E[F] with the Hertz law at zs_d = ZS_UNDERFLOW, whatever the loading law (it
    tests the resolution of the height density, not the law). A pdf with bounded support has no
    such limit.

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest.rough import heights, statistical
    >>> g, _ = heights.gw_data(heights.GreenwoodWilliamson(eta=1e10, sigma=1e-8, A_n=1e-4), 1e-8)
    >>> statistical.check_resolved(g, np.array([1.0]), str)  # fine: returns None
    """
    if g.kind != 0:
        return
    low = g.n_total * gw_hertz_sums_kernel(g, ZS_UNDERFLOW)[0]
    if np.any(energy < low):
        k = int(np.flatnonzero(energy < low)[0])
        raise ValueError(
            f"the impact at {where(k)} is too light for the statistical model: the flat would stop more "
            f"than {ZS_UNDERFLOW:g} sigma above the mean summit plane, where the Gaussian height density "
            f"exp(-zs^2/2) is below 1e-281 (N = {g.n_total:.4g} summits); (V1/V_c)^2 = {float(energy[k])!r} "
            f"must be >= {low:.4g}")


def hertz_estimate(g: Any, energy: NDArray[np.float64], w_cap: float) -> NDArray[np.float64]:
    """The deepest approach of every impact with all summits Hertzian (no forward table).

    Parameters
    ----------
    g : GWData
        The surface's height statistics.
    energy : ndarray
        Impact energies over one summit's U_c, (V1/V_c)^2 (-), > 0.
    w_cap : float
        Largest w* (-) the integration may reach; a solution beyond it is reported, not computed.

    Returns
    -------
    ndarray, shape (3, n)
        Per impact: status (OK; NEEDS_TABLE: the solution reaches past w_cap; FAILED), zs_d (the
        flat's position over sigma, -) and w* at the top of the integration (-).

    Notes
    -----
    Solves N E[F] = E (JGM eq 29 summed over the height distribution) with F = w^2.5; the start of
    every solve under the loading law and the size of its table.

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest.rough import heights, statistical
    >>> g, _ = heights.gw_data(heights.GreenwoodWilliamson(eta=1e10, sigma=1e-8, A_n=1e-4), 1e-8)
    >>> out = statistical.hertz_estimate(g, np.array([1.0, 100.0]), 1e3)
    >>> out[0].tolist(), bool(out[1, 0] > out[1, 1])
    ([0.0, 0.0], True)
    """
    out = np.zeros((3, energy.size))
    zs0 = 0.0 if g.kind == 0 else 0.5 * (g.zs_lo + g.zs_hi)
    _run(energy.size, _gw_hertz_array, _gw_hertz_serial, g, energy, zs0, w_cap, out)
    return out


@doc(ROUGH_DOC)
def solve_impacts(data: Any, g: Any, energy: NDArray[np.float64], zs0: NDArray[np.float64], w_model: float) -> NDArray[np.float64]:
    """Impacts on a statistical surface under the loading law of the forward table ``data``.

    {params_data}
    g : GWData
        The surface's height statistics.
    energy : ndarray
        Impact energies over U_c, (V1/V_c)^2 (-), > 0.
    zs0 : ndarray
        Start of each solve (flat position over sigma, -): the Hertz estimate.
    w_model : float
        w* (-) where the model ends (425, or a/R = 1 extrapolating).

    Returns
    -------
    ndarray, shape (8, n)
        Per impact: status (OK; NEEDS_TABLE: grow the table to the w* of row 1, or past the model's
        end once the table reaches it; FAILED), w* needed, zs_d, w* at the top of the integration,
        E[P*], E[L], P(contact), P(w* > 1) (per summit: times N for the surface).

    Notes
    -----
    N E[F] = E at the deepest approach (JGM eq 29 over the heights); 1 - e_s^2 = N E[L]/E with L
    the energy a summit dissipates (eq 38 with the unloading model of ``data``).

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest import forward
    >>> from fastrest.rough import heights, statistical
    >>> g, _ = heights.gw_data(heights.GreenwoodWilliamson(eta=1e10, sigma=1e-8, A_n=1e-4), 1e-8)
    >>> data = forward.forward_data(0.005, 0.3, w_max=40.0)
    >>> out = statistical.solve_impacts(data, g, np.array([100.0]), np.array([0.0]), 425.0)
    >>> bool(out[0, 0] == 0 and 0.0 < out[5, 0] / 100.0 < 1.0)
    True
    """
    out = np.zeros((8, energy.size))
    _run(energy.size, _gw_impacts_array, _gw_impacts_serial, data, g, energy, zs0, w_model, out)
    return out


def capacity_note(data: Any, g: Any, w_end: float, sigma: float, omega_c: float, R_a: float, U_c: float,
                  n_summits: float, v: float, M: float) -> str:
    """What a statistical surface can absorb before its tallest summits pass the law's end, for
    the message of an impact that drives them past it (text that follows that message).

    Parameters
    ----------
    data : fastrest.forward.ForwardData
        The summit's forward table, up to at least ``w_end``.
    g : GWData
        The surface's height statistics.
    w_end : float
        w* (-) where the law (or what the impact may use of it) ends.
    sigma, omega_c, R_a : float
        Standard deviation of the summit heights, one summit's critical interference and the
        summit radius (m).
    U_c : float
        One summit's critical energy (J).
    n_summits : float
        N = eta A_n (-).
    v, M : float
        The impact's speed (m/s) and mass (kg).

    Returns
    -------
    str
        The energy the surface absorbs with the flat at the lowest position whose integrated
        heights stay within ``w_end`` (:func:`~fastrest.rough.expectations.zs_covered_kernel`),
        the largest V1 at this M (and M at this V1) below it, and what to change in the inputs.
    """
    zs = zs_covered_kernel(g, w_end)
    e_f, _ = gw_jg_sums_kernel(data, g, zs, w_end)
    cap_j = float(n_summits) * float(e_f) * U_c
    rho = sigma / omega_c
    reach = float(zs_top_kernel(g, 0.0))  # integrated heights above the flat at the mean height (/ sigma)
    how = ("the Gaussian up to where its tail is negligible" if g.kind == 0 else "the pdf up to its support's top")
    text = (f". The summit heights spread with sigma = {sigma:.4g} m = {rho:.4g} omega_c (omega_c = {omega_c:.4g} m, "
            f"one summit's critical interference); the model integrates {how}, {reach:.3g} sigma above the flat "
            f"when the flat is at the mean summit height. The surface absorbs at most {cap_j:.4g} J before its "
            f"tallest integrated summits reach the law's end, w* = {w_end:.6g} (an interference of "
            f"{w_end * omega_c:.4g} m); this impact brings (1/2) M V1^2 = {0.5 * M * v * v:.4g} J")
    if cap_j > 0.0:
        text += (f": V1 must be below {math.sqrt(2.0 * cap_j / M):.4g} m/s at this M (M below "
                 f"{2.0 * cap_j / v**2:.4g} kg at this V1)")
    rho_max = w_end / reach
    if zs > 0.0 and reach > 0.0:  # even the flat at the mean height is past the law: the surface is the problem
        text += (f". The flat can reach the mean summit height only with sigma/omega_c <= {rho_max:.4g}: sigma <= "
                 f"{rho_max * omega_c:.4g} m at R_a = {R_a:.4g} m, or R_a >= {R_a * rho / rho_max:.4g} m at this "
                 "sigma (omega_c grows in proportion to R_a)")
    else:
        text += ". For harder impacts use a smaller sigma or a larger R_a (omega_c grows in proportion to R_a)"
    return text + ("; or explicit heights (heights=...)" if g.kind else
                   "; or explicit heights (heights=...), or a pdf of bounded support "
                   "(GreenwoodWilliamson(pdf=..., support=...)), which the model does not extend past its support")
