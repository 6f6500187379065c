"""The forward map of one asperity: maximum interference w* -> loading energy, force, returned energy.

The rest of fastrest answers "what is e for this impact speed" (the inverse map V1* -> w_m*).
Multi-asperity codes need the opposite direction: every asperity of a rough surface has its own
interference w_i* = omega_i / omega_c, fixed by the position of the flat, and one wants

    F(w)        loading energy up to w, over U_c (JGM eqs 19, 25: F = 1 - (W_ep)*; equal to the
                V1*^2 of a single sphere whose maximum interference is w);
                F = w^2.5 for w <= 1.9 (Hertz), F = 1.9^2.5 + (5/2) int_1.9^w P*_JG dz above
                (P* of the loading law: JG's, or Ghaednia et al.'s with hardening, ``et_ratio``)
    P*(w)       contact force over P_c (JG law, eqs 9, 14; exact formula, no table;
                :func:`P_table_forward` and :func:`FP_table_forward` read it from a table
                (~1e-14 relative), for Newton slopes)
    R(w)        energy returned by elastic unloading from w, over U_c (JGM eq 38 normalised):
                R = P*(w) (w - w_res*(w)),  w_res* from JCG eq (35) or Etsion eq (33)
    L(w)        energy dissipated, F - R, computed without cancellation (0 exactly for w <= 1,
                and for w <= 1.9 with Etsion unloading)

These are exactly the expressions of :func:`fastrest.unloading.restitution_kernel` (for a single
sphere, e^2 = R(w_m)/F(w_m) and 1 - e^2 = L(w_m)/F(w_m)).

F has no closed form above w = 1.9. :func:`forward_data` tabulates it for one material up to the
largest w* a scene needs, on the bit-indexed degree-5 cells of :mod:`fastrest.interpolation` (2^5
cells per octave of w, the first starting exactly at w = 1.9 where P* jumps). The node values come
from one cumulative march of :func:`fastrest.energy.jg_integral` (Gauss-Legendre in ln w) with
compensated summation; the interpolant agrees with :func:`fastrest.energy.f_star_kernel` to ~1e-15
relative (at most ~1e-14; tests/test_rough.py asserts <= 1e-12).

Use from your own Numba code::

    import numba
    from fastrest import forward

    data = forward.forward_data(eps_y=0.005, nu=0.3, w_max=50.0)   # ForwardData namedtuple

    @numba.njit
    def energy_of(data, w):            # w: array of asperity interferences (w* = omega/omega_c)
        s = 0.0
        for i in range(w.size):
            if w[i] > 0.0:
                s += forward.F_forward(data, w[i])
        return s

All ``*_forward`` functions return NaN for w < 0, NaN, or w > data.w_max (no exceptions in jitted
loops); w = 0 gives 0.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import math
from collections import namedtuple

import numpy as np

from ._deprecation import alias, keyword_only, module_getattr
from ._doc import doc, paragraphs
from ._jit import jit
from ._validation import (check_bool, check_count, check_eps_y, check_nu, real_scalar,
                          warn_if_outside_validated)
from .loading.jackson_green import W_SWITCH, area_exponent
from .critical import c_of_nu
from .energy import F_SWITCH, law_integral
from .loading import p_star_above, resolve as resolve_loading
from .law_cells import LAW_BITS_PER_OCTAVE, LAW_ROW, law_rows
from .limits import interference_limit, raise_interference_out_of_range, w_upper_model
from .interpolation import (MANTISSA_BITS, cell_edges, cell_index, cell_polynomial,
                            chebyshev_nodes, fit_cells, row_polynomial, share_edges)
from .unloading import BRAKE, ETSION, JCG, N_MODELS, restitution, unloading_code, warn_if_unfitted

__all__ = ["ForwardData", "forward_data", "F_forward", "P_forward",
           "P_table_forward", "FP_table_forward", "returned_forward", "loss_forward",
           "forward_values", "forward_values_excess", "JCG", "ETSION", "BRAKE"]

# The parameters of the ``*_forward`` kernels and their examples' first lines, written once
# (fastrest._doc).
_DOC = paragraphs(
    params="""
        Parameters
        ----------
        data : ForwardData
            The material's forward map, :func:`forward_data`.
        w : float
            Normalised interference omega/omega_c (-), 0 <= w <= ``data.w_max``.
        """,
    examples="""
        Examples
        --------
        >>> from fastrest import forward
        >>> d = forward.forward_data(0.005, 0.33, w_max=50.0)
        """,
)

#: Cells per octave of w (2^K). K = 5: max relative error ~5e-15 on F (K = 4: ~5e-13), measured
#: against energy.f_star_kernel over 0.0005 <= eps_y <= 0.01 (tests/test_rough.py asserts <= 1e-12).
BITS_PER_OCTAVE = 5

ForwardData = namedtuple("ForwardData", ["model", "eps_y", "nu", "C", "B", "w_max", "shift", "base",
                                         "f_rows", "p_rows", "law", "et_ratio", "law_rows"])
ForwardData.__doc__ = """Numba-friendly forward map of one material (see :func:`forward_data`).

Build it with :func:`forward_data` (or :func:`fastrest.contact_law`, as ``law.data``), not by
hand; pass it into jitted code and to the ``*_forward`` kernels.

Parameters
----------
model : int
    Unloading model code: 0 = JCG (eq 35), 1 = Etsion (eqs 33-34), 2 = Brake
    (:data:`JCG`, :data:`ETSION`, :data:`BRAKE`).
eps_y, nu : float
    The material (-).
C : float
    C(nu) (-), JGM eq (5).
B : float
    Area exponent 0.14 exp(23 eps_y) (-), eq (10).
w_max : float
    Largest interference w* = omega/omega_c served (-); the kernels give NaN above it.
shift, base : int
    Cell-index parameters of the bit-indexed cells (:mod:`fastrest.interpolation`).
f_rows : ndarray
    (ncell, 8) float64 rows [center, 1/half_width, c0..c5] of F on (1.9, w_top], where
    w_top >= w_max is the end of the bit-cell holding w_max.
p_rows : ndarray
    The same for P* (used by :func:`P_table_forward`, :func:`FP_table_forward` and
    :func:`fastrest.jit.contact_force`).
law : int
    Loading law code (:mod:`fastrest.loading`): 0 = Jackson-Green, 1 = Ghaednia et al. (2019).
et_ratio : float
    Tangent modulus over Young's modulus Et/E (-); 0 for Jackson-Green.
law_rows : ndarray
    (n, 16) float64 rows of P* and of the unloading model's delta = w_m* - w_res* from w = 1 to
    the top cell, one index for both (:mod:`fastrest.law_cells`; read by
    :func:`fastrest.jit.contact_force`).

Examples
--------
>>> from fastrest import forward
>>> d = forward.forward_data(0.005, 0.33, w_max=50.0)
>>> d.model, d.w_max, d.f_rows.shape
(0, 50.0, (151, 8))
"""




@jit(inline=True)
def _p_jg(data, w):
    """P* above the switch (JG eq 9, or the hardening law) for this material, exact formula."""
    return p_star_above(data.law, w, data.eps_y, data.nu, data.C, data.B, data.et_ratio)


# --- scalar kernels (call these from @njit code) -----------------------------------------------

@jit(inline=True)
@doc(_DOC)
def F_forward(data, w):
    """Loading energy to interference w over U_c, F(w) = 1 - (W_ep)*(w) (-).

    The V1*^2 of a single sphere whose maximum interference is w (JGM eq 29).

    {params}

    Returns
    -------
    float
        F (-); w^2.5 for w <= 1.9. NaN for w < 0, NaN or w > ``data.w_max`` (a jit kernel: it never
        raises).

    Notes
    -----
    JGM eqs (19), (25) normalised by U_c. Above w = 1.9 read from the degree-5 cells of
    ``data.f_rows`` (~1e-15 relative to :func:`fastrest.loading_energy`). Inlined into the calling
    jitted loop.

    {examples}
    >>> round(forward.F_forward(d, 6.549856322605), 9)  # the V1* = 10 check value, squared
    100.0
    >>> forward.F_forward(d, 60.0)  # past w_max
    nan
    """
    if w > W_SWITCH:
        if w <= data.w_max:
            return cell_polynomial(data.f_rows, cell_index(w, data.shift, data.base), w)
        return np.nan
    if w >= 0.0 and w <= data.w_max:
        return w * (w * math.sqrt(w))  # = w * P*, as forward_values
    return np.nan


@jit(inline=True)
@doc(_DOC)
def P_forward(data, w):
    """Contact force at interference w over P_c, P*(w) (-), by the exact formula (no table).

    {params}

    Returns
    -------
    float
        P* (-); NaN for w < 0, NaN or w > ``data.w_max`` (a jit kernel: it never raises).

    Notes
    -----
    The Jackson-Green law: Hertz w^1.5 up to w = 1.9 (JGM eq 14), eq (9) above (as
    :func:`fastrest.P_star`); Ghaednia et al.'s (2019) above for a hardening ``data``
    (``data.law``, ``data.et_ratio``).

    {examples}
    >>> round(forward.P_forward(d, 10.0), 6)
    25.647583
    """
    if w > W_SWITCH:
        if w <= data.w_max:
            return _p_jg(data, w)
        return np.nan
    if w >= 0.0 and w <= data.w_max:
        return w * math.sqrt(w)
    return np.nan


@jit(inline=True)
@doc(_DOC)
def P_table_forward(data, w):
    """P*(w) from the table (within ~1e-14 of :func:`P_forward`, ~7x cheaper above w = 1.9) (-).

    For Newton slopes and other places where the last digits do not matter; reported forces use
    the exact :func:`P_forward`.

    {params}

    Returns
    -------
    float
        P* (-), NaN where :func:`P_forward` gives NaN (a jit kernel: it never raises).

    Notes
    -----
    JGM eqs (9), (14), above w = 1.9 from the degree-5 cells of ``data.p_rows`` fitted to eq (9).

    {examples}
    >>> abs(forward.P_table_forward(d, 10.0) / forward.P_forward(d, 10.0) - 1) < 1e-13
    True
    """
    if w > W_SWITCH:
        if w <= data.w_max:
            return cell_polynomial(data.p_rows, cell_index(w, data.shift, data.base), w)
        return np.nan
    return P_forward(data, w)  # Hertz (NaN below 0 or past w_max)


@jit(inline=True)
@doc(_DOC)
def FP_table_forward(data, w):
    """(F(w), P*(w)) with P* from its table: one cell lookup for both.

    The pair a Newton iteration on the energy balance needs (energy and its slope, the force);
    about 3x cheaper than :func:`F_forward` plus :func:`P_forward` above w = 1.9.

    {params}

    Returns
    -------
    F : float
        Loading energy over U_c (-), as :func:`F_forward`.
    P : float
        Force over P_c (-), as :func:`P_table_forward`. Both NaN for w < 0, NaN or
        w > ``data.w_max`` (a jit kernel: it never raises).

    Notes
    -----
    JGM eqs (19), (25) and (9), (14); dF/dw = (5/2) P* (eq 25).

    {examples}
    >>> f, p = forward.FP_table_forward(d, 10.0)
    >>> round(f, 6), round(p, 6)
    (272.276805, 25.647583)
    """
    if w > W_SWITCH:
        if w <= data.w_max:
            i = cell_index(w, data.shift, data.base)
            rf = data.f_rows
            rp = data.p_rows
            u = (w - rf[i, 0]) * rf[i, 1]  # F and P* share the cells
            return row_polynomial(rf, i, u), row_polynomial(rp, i, u)
        return np.nan, np.nan
    if w >= 0.0 and w <= data.w_max:
        p = w * math.sqrt(w)
        return w * p, p
    return np.nan, np.nan


@jit(inline=True)
@doc(_DOC)
def forward_values(data, w):
    """(F, P*, R, L) at interference w: loading energy, force, returned and dissipated energy.

    For the impact whose maximum interference is w, e^2 = R/F and 1 - e^2 = L/F.

    {params}

    Returns
    -------
    F : float
        Loading energy to w over U_c (-), :func:`F_forward`.
    P : float
        Force over P_c (-), :func:`P_forward`.
    R : float
        Energy returned by elastic unloading from w over U_c (-), :func:`returned_forward`.
    L : float
        Energy dissipated over U_c (-), F - R without cancellation (0 for w <= 1).
        All four NaN for w < 0, NaN, w > ``data.w_max`` or an unknown ``data.model`` (a jit
        kernel: it never raises).

    Notes
    -----
    R = P*(w) (w - w_res*(w)): JGM eq (38) with the elastic unloading of eq (32) and the unloading
    model's w_res* (eq 35, eqs 33-34 or Brake's).

    {examples}
    >>> F, P, R, L = forward.forward_values(d, 6.549856322605)  # w_m* of V1* = 10
    >>> round(F, 6), round(P, 6), round(R, 6), round(L, 6)
    (100.0, 14.530473, 68.679768, 31.320232)
    >>> round((R / F) ** 0.5, 6)  # e, as fastrest.direct.e_exact(10.0, 0.005, 0.33)
    0.828733
    """
    return forward_values_excess(data, w, w - 1.0)


@jit(inline=True)
@doc(_DOC)
def forward_values_excess(data, w, w1):
    """:func:`forward_values` with w1 = w - 1 given (documented internal).

    {params}
    w1 : float
        w - 1 (-), computed by the caller without cancellation (near the onset of yield L is
        proportional to it: the rough-surface solvers carry it beside w).

    Returns
    -------
    (float, float, float, float)
        F, P*, R, L as :func:`forward_values` (NaN likewise); L = 0 for w1 <= 0.

    Notes
    -----
    JGM eq (38) with the unloading model's w_res*, as :func:`forward_values`.

    Examples
    --------
    >>> from fastrest import forward
    >>> d = forward.forward_data(0.005, 0.3, w_max=10.0)
    >>> F, P, R, L = forward.forward_values_excess(d, 1.0 + 1e-12, 1e-12)
    >>> bool(abs(L / 1e-12 - 1.02 * 0.54 / 6.9) < 1e-9)
    True
    """
    # fields read up front: a field read inside a rarely taken branch slows the caller's loop
    model, eps_y, nu, w_max = data.model, data.eps_y, data.nu, data.w_max
    law, et_ratio = data.law, data.et_ratio
    if not (w >= 0.0 and w <= w_max and model >= 0 and model < N_MODELS):
        return np.nan, np.nan, np.nan, np.nan
    if w <= W_SWITCH:
        p = w * math.sqrt(w)
        f = w * p
    else:
        f = cell_polynomial(data.f_rows, cell_index(w, data.shift, data.base), w)
        p = _p_jg(data, w)
    if w1 <= 0.0:
        return f, p, f, 0.0  # elastic
    # the unloading model's energy split of an impact whose loading energy is f
    e2, loss, _, _, _ = restitution(model, f, w, w1, p, eps_y, nu, law, et_ratio)
    return f, p, e2 * f, loss * f


@jit(inline=True)
@doc(_DOC)
def returned_forward(data, w):
    """Energy returned by elastic unloading from w, over U_c: R(w) = P*(w) (w - w_res*(w)) (-).

    For the impact whose maximum interference is w, e^2 = R(w)/F(w) (JGM eq 16).

    {params}

    Returns
    -------
    float
        R (-); equal to F(w) for w <= 1 (elastic). NaN for w < 0, NaN, w > ``data.w_max`` or an
        unknown ``data.model`` (a jit kernel: it never raises).

    Notes
    -----
    JGM eq (38) normalised, with eq (32) and the unloading model's w_res* (eq 35, eqs 33-34 or
    Brake's): see :func:`forward_values`.

    {examples}
    >>> round(forward.returned_forward(d, 6.549856322605), 6)
    68.679768
    """
    return forward_values(data, w)[2]


@jit(inline=True)
@doc(_DOC)
def loss_forward(data, w):
    """Energy dissipated by loading to w and unloading, over U_c: L(w) = F(w) - R(w) (-).

    (1 - e^2) V1*^2 of the impact whose maximum interference is w.

    {params}

    Returns
    -------
    float
        L (-), computed without cancellation; 0 for w <= 1 (and for w <= 1.9 with Etsion or Brake
        unloading). NaN for w < 0, NaN, w > ``data.w_max`` or an unknown ``data.model`` (a jit
        kernel: it never raises).

    Notes
    -----
    JGM eqs (25), (38): the loading energy minus the energy eq (32) returns (see
    :func:`forward_values`).

    {examples}
    >>> round(forward.loss_forward(d, 6.549856322605), 6)
    31.320232
    >>> forward.loss_forward(d, 0.5)
    0.0
    """
    return forward_values(data, w)[3]


# --- building ----------------------------------------------------------------------------------

@jit
def _p_nodes(nodes, eps_y, nu, law, et_ratio, out):
    C = c_of_nu(nu)
    B = area_exponent(eps_y)
    for i in range(nodes.size):
        out[i] = p_star_above(law, nodes[i], eps_y, nu, C, B, et_ratio)


@jit
def _f_march(nodes, eps_y, nu, law, et_ratio, out):
    """F at increasing nodes (all > 1.9): one pass of law_integral with Neumaier summation."""
    C = c_of_nu(nu)
    B = area_exponent(eps_y)
    s = F_SWITCH
    comp = 0.0
    w_prev = W_SWITCH
    for i in range(nodes.size):
        inc = 2.5 * law_integral(w_prev, nodes[i], eps_y, nu, C, B, law, et_ratio)
        t = s + inc
        if abs(s) >= abs(inc):
            comp += (s - t) + inc
        else:
            comp += (inc - t) + s
        s = t
        out[i] = s + comp
        w_prev = nodes[i]


#: ``law_rows`` of a ForwardData built with ``contact_cells=False``: one row of NaN.
_NO_LAW_ROWS = np.full((1, LAW_ROW), np.nan)
_NO_LAW_ROWS.flags.writeable = False


def _is_number(x):
    return isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, (bool, np.bool_))


@keyword_only("w_max", old=lambda args: _is_number(args[2]))
def forward_data(eps_y: float, nu: float, unloading: str = "jcg", *, w_max: float, extrapolate: bool = False,
                 bits_per_octave: int = BITS_PER_OCTAVE, et_ratio: float = 0.0,
                 loading: str | None = None, contact_cells: bool = True) -> ForwardData:
    """Tabulate the forward map of one material up to interference ``w_max``.

    Parameters
    ----------
    eps_y : float
        Sy/E' (-), > 0 (validated range 0.0005-0.01; outside: ValidityWarning).
    nu : float
        Poisson's ratio of the yielding material, 0 <= nu < 0.5.
    unloading : {"jcg", "etsion", "brake"}
        Residual-interference model, JGM eq (35), (33) or Brake's (:mod:`fastrest.unloading`).
    w_max : float
        Largest normalised interference omega/omega_c to serve (-), >= 0, keyword-only (the largest
        allowed: ``fastrest.limit(eps_y, nu, unloading).omega_m_star``). Only the cells up to it
        are computed (cost grows with log(w_max/1.9): 250 cells and a few ms for w_max = 425).
        Passing it positionally (third, before ``unloading``) is deprecated.
    extrapolate : bool
        Allow w_max above 425 (JGM's range), up to the point where a/R = 1 (and the unloading
        model's end).
    bits_per_octave : int, optional
        Cells per octave of w are 2^bits_per_octave, a whole number in [1, 10]; default
        :data:`BITS_PER_OCTAVE` (5: ~5e-15 relative on F).
    et_ratio : float, optional
        Tangent modulus over Young's modulus Et/E (-), 0 <= et_ratio < 1; default 0.
    loading : {None, "jackson-green", "ghaednia"}, optional
        The loading law (:func:`fastrest.P_star`); None picks it from ``et_ratio``.
    contact_cells : bool, optional
        Build ``law_rows``, the contact law's cells (:mod:`fastrest.law_cells`; default True).
        False leaves one row of NaN there (``fastrest.jit.contact_force`` then gives NaN above
        w = 1): for multi-asperity code that never steps a contact law, ~10 % faster to build.

    Returns
    -------
    ForwardData
        Immutable; pass it to the ``*_forward`` kernels, in Python or inside jitted code.

    Raises
    ------
    TypeError
        eps_y, nu, w_max or et_ratio not a single real number; ``extrapolate`` not True or False.
    ValueError
        eps_y not finite and > 0; nu outside [0, 0.5); w_max negative or not finite; w_max past
        w* = 425 (without ``extrapolate``), past a/R = 1 or past the unloading model's end (the
        message names the limit); an unknown ``unloading`` or ``loading``; et_ratio outside
        [0, 1), or > 0 with ``loading="jackson-green"``; ``bits_per_octave`` outside [1, 10].

    Warns
    -----
    ValidityWarning
        eps_y or nu outside the validated 0.0005 <= eps_y <= 0.01, 0.2 <= nu <= 0.45; JCG or
        Etsion unloading with et_ratio > 0 (:func:`fastrest.unloading.warn_if_unfitted`).

    Notes
    -----
    Tabulates the loading energy F(w) (JGM eqs 19, 25) above w = 1.9 by one cumulative march of
    Gauss-Legendre quadrature, and P*(w) (eq 9), on bit-indexed degree-5 cells
    (:mod:`fastrest.interpolation`); agrees with :func:`fastrest.loading_energy` to ~1e-15
    relative (tests/test_rough.py asserts <= 1e-12).

    Examples
    --------
    >>> from fastrest import forward
    >>> d = forward.forward_data(0.005, 0.33, "etsion", w_max=50.0)
    >>> d.model == forward.ETSION, d.w_max
    (True, 50.0)
    >>> forward.forward_data(0.005, 0.33, w_max=500.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    ValueError: w_max = 500.0 is beyond w* = 425, the largest interference the model covers ...
    """
    model = unloading_code(unloading)
    eps_y = float(check_eps_y(real_scalar(eps_y, "eps_y")))
    nu = float(check_nu(real_scalar(nu, "nu")))
    w_max = real_scalar(w_max, "w_max")
    bits_per_octave = check_count(bits_per_octave, "bits_per_octave", 1, 10)
    warn_if_outside_validated(eps_y, nu)
    if not (math.isfinite(w_max) and w_max >= 0.0):
        raise ValueError(f"w_max must be finite and >= 0 (normalised interference); got {w_max!r}")
    extrapolate = check_bool(extrapolate, "extrapolate")
    contact_cells = check_bool(contact_cells, "contact_cells")
    et_ratio = real_scalar(et_ratio, "et_ratio")
    law = resolve_loading(loading, et_ratio)
    warn_if_unfitted(unloading, et_ratio)
    lim = float(w_upper_model(eps_y, nu, extrapolate, model, law.code, et_ratio))  # the unloading model may end first
    if w_max > lim:
        raise_interference_out_of_range(w_max, eps_y, nu, extrapolate, "w_max", unloading)
    C, B = float(c_of_nu(nu)), float(area_exponent(eps_y))
    shift = MANTISSA_BITS - bits_per_octave
    if w_max <= W_SWITCH:  # closed forms only: one dummy cell
        return ForwardData(model, eps_y, nu, C, B, w_max, shift, 0, np.zeros((1, 8)), np.zeros((1, 8)), law.code,
                           et_ratio, _contact_rows(contact_cells, w_max, None, None, eps_y, nu, model, law.code,
                                                   et_ratio))
    base, edges = _whole_cells(w_max, bits_per_octave)
    nodes = chebyshev_nodes(edges)
    f_vals = np.empty(nodes.size)
    _f_march(np.ascontiguousarray(nodes.ravel()), eps_y, nu, law.code, et_ratio, f_vals)
    f_rows = np.ascontiguousarray(fit_cells(edges, share_edges(f_vals.reshape(nodes.shape))))
    p_rows = _p_rows(edges, eps_y, nu, law.code, et_ratio)
    return ForwardData(model, eps_y, nu, C, B, w_max, shift, int(base), f_rows, p_rows, law.code, et_ratio,
                       _contact_rows(contact_cells, w_max, edges if bits_per_octave == LAW_BITS_PER_OCTAVE else None,
                                     p_rows, eps_y, nu, model, law.code, et_ratio))


def _whole_cells(w_max, bits_per_octave):
    """(base key, edges) of the bit-cells from 1.9 up to w_max, the last one whole: it ends at its
    natural boundary, not at w_max, so a table built for a larger w_max holds bit-identical rows
    for every w both cover."""
    base, edges = cell_edges(W_SWITCH, w_max, bits_per_octave)
    end_key = np.array([base + edges.shape[0]], dtype=np.int64) << np.int64(MANTISSA_BITS - bits_per_octave)
    edges[-1, 1] = end_key.view(np.float64)[0]
    return base, edges


def _p_rows(edges, eps_y, nu, law, et_ratio):
    """Rows of P* (eq 9 or the hardening law) on ``edges``."""
    nodes = chebyshev_nodes(edges)
    p_vals = np.empty(nodes.size)
    _p_nodes(np.ascontiguousarray(nodes.ravel()), eps_y, nu, law, et_ratio, p_vals)
    return np.ascontiguousarray(fit_cells(edges, share_edges(p_vals.reshape(nodes.shape))))


def _contact_rows(contact_cells, w_max, edges, p_rows, eps_y, nu, model, law, et_ratio):
    """``ForwardData.law_rows``: the NaN placeholder without ``contact_cells``; else the law's
    cells, which are always 2^LAW_BITS_PER_OCTAVE per octave: ``edges``/``p_rows`` when the table
    has those cells (None otherwise: the P* cells are fitted again at the law's width)."""
    if not contact_cells:
        return _NO_LAW_ROWS
    if w_max <= W_SWITCH:
        return law_rows(np.zeros((0, 2)), np.zeros((0, 8)), eps_y, nu, model, law, et_ratio)
    if edges is None:
        _, edges = _whole_cells(w_max, LAW_BITS_PER_OCTAVE)
        p_rows = _p_rows(edges, eps_y, nu, law, et_ratio)
    return law_rows(edges, p_rows, eps_y, nu, model, law, et_ratio)


def _forward_limit(eps_y, nu, *, extrapolate=False):
    return interference_limit(eps_y, nu, extrapolate=extrapolate)


__getattr__ = module_getattr(__name__)
alias(__name__, "forward_limit", "fastrest.limit(eps_y, nu, extrapolate=...).omega_m_star", lambda: _forward_limit)
