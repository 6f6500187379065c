"""What the explicit and the statistical solvers share: one summit's terms, the impact energy.

A summit at normalised interference w* = w (omega/omega_c, JGM eq 4) contributes to the energy
balance its loading energy F(w) (JGM eqs 19, 25; :mod:`fastrest.forward`) and to the Newton slope
its force P*(w) (eqs 9, 14). Near the onset of yield (w -> 1) the dissipated energy L(w) is
proportional to w - 1, so the solvers pass w - 1 computed without cancellation (``d``) beside w:
while the tallest summit is near the onset, summits enter the energy balance as F - 1
(:func:`hertz_terms`), and
:func:`summit_values` is :func:`fastrest.forward.forward_values_excess` (w - 1 given).

The impact energy over U_c, E = M V1^2 / (2 U_c) = (V1/V_c)^2, is carried as an unevaluated sum
``e_hi + e_lo`` (:func:`_energy_low_array`), so that E - n (n summits counted from their onset) keeps
its relative accuracy when E is close to n.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import math

import numpy as np

from .. import forward as fw
from .._doc import paragraphs
from .._jit import jit
from .._validation import as_float_array, kernel_array
from .._validation import OMEGA_STAR_SWITCH as W_SWITCH  # every loading law's Hertz switch (fastrest.loading)

__all__ = ["OK", "NEEDS_TABLE", "FAILED", "MAX_ITER", "ONSET_BAND", "hertz_fp", "hertz_terms", "jg_terms",
           "summit_values", "energy_excess", "energy_parts"]

#: The first parameter of the solvers of both surface models, written once (fastrest._doc).
ROUGH_DOC = paragraphs(params_data="""
    Parameters
    ----------
    data : fastrest.forward.ForwardData
        Forward table of one summit (loading energy, force, unloading; its loading law, JG or
        Ghaednia et al. with hardening, is every summit's).
    """)

#: Solver status codes: converged; a trial point lies beyond the forward table (grow it, or, at the
#: model's end, the impact is outside the model); no convergence in MAX_ITER steps (a bug).
OK, NEEDS_TABLE, FAILED = 0, 1, 2
#: Iterations allowed per solve (Newton takes 3-6; bisection at most ~110 on a double's range).
MAX_ITER = 200
#: The energy balance is formed relative to the onset of yield while the tallest summit is within
#: this of w* = 1 (``|w* - 1| < 1/16``): further away, plain F (as the table holds it) costs at most a
#: factor 16 of rounding in w* - 1 (~1e-15 relative), and the sums stay as cheap as without it.
ONSET_BAND = 0.0625


@jit(inline=True)
def hertz_fp(w):
    """Loading energy and force of a Hertzian summit.

    Parameters
    ----------
    w : float
        Interference w* = omega/omega_c (-), >= 0.

    Returns
    -------
    (float, float)
        F = w^2.5 (over U_c) and P* = w^1.5 (over P_c) (-), JGM eqs (19), (14).

    Examples
    --------
    >>> from fastrest.rough import common
    >>> common.hertz_fp(4.0)
    (32.0, 8.0)
    """
    p = w * math.sqrt(w)
    return w * p, p


@jit(inline=True)
def hertz_terms(w, d, onset):
    """A Hertzian summit's terms of the energy balance and its slope.

    Parameters
    ----------
    w : float
        Interference w* (-), > 0.
    d : float
        w* - 1 (-), computed without cancellation by the caller.
    onset : bool
        The tallest summit is within :data:`ONSET_BAND` of w* = 1.

    Returns
    -------
    (float, float, float)
        The energy term, P* = w^1.5 (-), and 1 if the term is counted from w* = 1, else 0. The
        term is F = w^2.5 (JGM eq 19), except with ``onset`` for summits above w* = 1/2: these
        enter the balance counted from w* = 1, F - 1 formed from d without cancellation.

    Notes
    -----
    With a = sqrt(w): w^2.5 - 1 = (a - 1)(a^4 + a^3 + a^2 + a + 1) and a - 1 = d/(a + 1).

    Examples
    --------
    >>> from fastrest.rough import common
    >>> f1, p, k = common.hertz_terms(1.0 + 1e-12, 1e-12, True)
    >>> round(f1 / 2.5e-12, 9), k
    (1.0, 1.0)
    """
    a = math.sqrt(w)
    p = w * a
    if onset and d > -0.5:
        return d / (a + 1.0) * (w * (w + a + 1.0) + a + 1.0), p, 1.0
    return w * p, p, 0.0


@jit(inline=True)
def jg_terms(data, w, d, onset):
    """:func:`hertz_terms` under the forward table's loading law (JG, or Ghaednia et al. with
    strain hardening).

    Parameters
    ----------
    data : fastrest.forward.ForwardData
        Forward table of one summit.
    w, d, onset
        As :func:`hertz_terms`.

    Returns
    -------
    (float, float, float)
        As :func:`hertz_terms`; above w* = 1.9, F (JGM eqs 19, 25) and the Newton slope P* (eq 9,
        or the hardening law's)
        from the table (F - 1 >= 1.9^2.5 - 1 loses nothing there). NaN past ``data.w_max``.

    Examples
    --------
    >>> from fastrest import forward
    >>> from fastrest.rough import common
    >>> data = forward.forward_data(0.005, 0.3, w_max=10.0)
    >>> f, p, k = common.jg_terms(data, 5.0, 4.0, False)
    >>> bool(f > 5.0**2.5 * 0.9 and k == 0.0)
    True
    """
    if w > W_SWITCH:
        f, p = fw.FP_table_forward(data, w)
        if onset:
            return f - 1.0, p, 1.0
        return f, p, 0.0
    return hertz_terms(w, d, onset)


#: One summit's (F, P*, R, L) from (data, w, w - 1): :func:`fastrest.forward.forward_values_excess`.
summit_values = fw.forward_values_excess


@jit(inline=True)
def energy_excess(e_hi, e_lo, n):
    """The impact energy in excess of n.

    Parameters
    ----------
    e_hi, e_lo : float
        The energy E = e_hi + e_lo (-) (:func:`energy_parts`).
    n : float
        A count of summits (-).

    Returns
    -------
    float
        E - n (-), with relative accuracy: e_hi - n is exact when E is within a factor 2 of n
        (Sterbenz's lemma).

    Examples
    --------
    >>> from fastrest.rough import common
    >>> common.energy_excess(1.0, 1e-20, 1.0)
    1e-20
    """
    return (e_hi - n) + e_lo


@jit(inline=True)
def _split(a):
    """Dekker's split of a into two 26-bit halves (a = hi + lo exactly)."""
    c = 134217729.0 * a  # 2^27 + 1
    hi = c - (c - a)
    return hi, a - hi


@jit(inline=True)
def _two_prod(a, b):
    """(p, err) with p = fl(a b) and a b = p + err exactly (Dekker; no fused multiply-add needed)."""
    p = a * b
    ah, al = _split(a)
    bh, bl = _split(b)
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


@jit
def _energy_low_array(v, m, two_uc, e_hi, out):
    """out[i] = M V1^2 / (2 U_c) - e_hi[i], the part of the exact impact energy its double misses.

    ``v``: speeds V1 (m/s); ``m``: mass M (kg); ``two_uc``: 2 U_c (J); ``e_hi``: the rounded
    energies fl(fl(M fl(V1^2)) / (2 U_c)) (the caller's). The numerator M V1^2 is formed exactly
    from two Dekker products; e_hi 2 U_c likewise, so their difference (equal to within rounding)
    is exact. Where a product would overflow (V1^2 > 1e300) the correction is 0.
    """
    for i in range(v.size):
        a, a_lo = _two_prod(v[i], v[i])
        b, b_lo = _two_prod(m, a)
        t, t_lo = _two_prod(e_hi[i], two_uc)
        lo = (((b - t) - t_lo) + (b_lo + m * a_lo)) / two_uc
        out[i] = lo if math.isfinite(lo) else 0.0


def check_speeds(V1):
    """``V1`` as a flat float64 kernel array, every value finite and > 0 (m/s).

    Parameters
    ----------
    V1 : float or array_like
        Impact speeds (m/s).

    Returns
    -------
    (ndarray, tuple)
        The flat speeds and ``V1``'s shape.

    Raises
    ------
    TypeError
        Non-numeric V1.
    ValueError
        A V1 that is not finite and > 0, naming it.

    Examples
    --------
    >>> check_speeds([0.1, 1.0])[0]
    array([0.1, 1. ])
    """
    v = as_float_array(V1, "V1")
    flat = kernel_array(v)
    bad = ~(np.isfinite(flat) & (flat > 0))
    if np.any(bad):
        got = float(flat[bad][0])
        raise ValueError(f"V1 must be finite and > 0 (m/s); got {got!r}"
                         + (" (at V1 = 0 no summit is ever touched and e_s is undefined)" if got == 0 else ""))
    return flat, v.shape


def energy_parts(v: NDArray[np.float64], m: float, u_c: float) -> Any:
    """Impact energies over one summit's critical energy, as double plus correction.

    Parameters
    ----------
    v : ndarray
        Impact speeds V1 (m/s), 1-d contiguous.
    m : float
        Mass of the flat M (kg).
    u_c : float
        Critical energy of one summit U_c (J), JGM eq (24).

    Returns
    -------
    (ndarray, ndarray)
        e_hi = fl(M V1^2 / (2 U_c)) = (V1/V_c)^2 (-, JGM eq 28) and e_lo, with e_hi + e_lo the
        exact energy of the given doubles to ~1e-32 relative (0 where e_hi is not finite).

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest.rough import common
    >>> e_hi, e_lo = common.energy_parts(np.array([2.0 * (1.0 + 2.0**-52)]), 0.5, 1.0)
    >>> float(e_hi[0] - 1.0 + e_lo[0]) == 2.0**-51 + 2.0**-104
    True
    """
    with np.errstate(over="ignore", under="ignore"):
        e_hi = m * v**2 / (2.0 * u_c)
    e_lo = np.zeros_like(e_hi)
    ok = np.isfinite(e_hi)
    if np.all(ok):
        _energy_low_array(v, float(m), 2.0 * u_c, e_hi, e_lo)
    return e_hi, e_lo
