"""The forward map of one asperity: maximum interference w* -> loading energy, force, returned energy.

The rest of fastrest answers "what is e for this impact speed" (the inverse map V1* -> w_m*).
Multi-asperity codes need the opposite direction: every asperity of a rough surface has its own
interference w_i* = omega_i / omega_c, fixed by the position of the flat, and one wants

    F(w)        loading energy up to w, over U_c (JGM eqs 19, 25: F = 1 - (W_ep)*; equal to the
                V1*^2 of a single sphere whose maximum interference is w);
                F = w^2.5 for w <= 1.9 (Hertz), F = 1.9^2.5 + (5/2) int_1.9^w P*_JG dz above
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
import math
from collections import namedtuple

import numpy as np

from ._jit import jit
from ._validation import (check_bool, check_count, check_eps_y, check_nu, real_scalar,
                          warn_if_outside_validated)
from .contact import W_SWITCH, area_exponent, c_of_nu, p_star_jg
from .energy import F_SWITCH, jg_integral
from .limits import omega_limit, raise_interference_out_of_range, w_upper_model
from .interpolation import (MANTISSA_BITS, cell_edges, cell_index, cell_polynomial,
                            chebyshev_nodes, fit_cells, row_polynomial, share_edges)
from .unloading import BRAKE, ETSION, JCG, N_MODELS, restitution, unloading_code

__all__ = ["ForwardData", "forward_data", "forward_limit", "F_forward", "P_forward",
           "P_table_forward", "FP_table_forward", "returned_forward", "loss_forward",
           "forward_values", "JCG", "ETSION", "BRAKE"]

#: Cells per octave of w (2^K). K = 5: max relative error ~5e-15 on F (K = 4: ~5e-13), measured
#: against energy.f_star_kernel over 0.0005 <= eps_y <= 0.01 (tests/test_rough.py asserts <= 1e-12).
BITS_PER_OCTAVE = 5

ForwardData = namedtuple("ForwardData", ["model", "eps_y", "nu", "C", "B", "w_max", "shift", "base",
                                         "f_rows", "p_rows"])
ForwardData.__doc__ = """Numba-friendly forward map of one material (see :func:`forward_data`).

model: 0 = JCG unloading (eq 35), 1 = Etsion (eq 33); eps_y, nu: material (-); C = C(nu) (eq 5),
B = 0.14 exp(23 eps_y) (eq 10); w_max: largest w* served (-); shift, base: cell-index parameters;
f_rows: (ncell, 8) float64 rows [center, 1/half_width, c0..c5] of F on (1.9, w_top], where w_top
>= w_max is the end of the bit-cell holding w_max; p_rows: the same for P* (used only by
:func:`P_table_forward`).
"""




@jit(inline=True)
def _p_jg(data, w):
    """JG branch of P* (eq 9) for this material: :func:`fastrest.contact.p_star_jg`."""
    return p_star_jg(w, data.eps_y, 0.0, data.C, data.B)


# --- scalar kernels (call these from @njit code) -----------------------------------------------

@jit(inline=True)
def F_forward(data, w):
    """Loading energy to interference w over U_c, F(w) = 1 - (W_ep)*(w) (-); NaN outside [0, w_max]."""
    if w > W_SWITCH:
        if w <= data.w_max:
            return cell_polynomial(data.f_rows, cell_index(w, data.shift, data.base), w)
        return np.nan
    if w >= 0.0 and w <= data.w_max:
        return w * (w * math.sqrt(w))  # = w * P*, as forward_values
    return np.nan


@jit(inline=True)
def P_forward(data, w):
    """Contact force at interference w over P_c, P*(w) (JG law, eqs 9, 14); NaN outside [0, w_max].

    Exact formula (no table): Hertz w^1.5 up to w = 1.9, the JG fit above.
    """
    if w > W_SWITCH:
        if w <= data.w_max:
            return _p_jg(data, w)
        return np.nan
    if w >= 0.0 and w <= data.w_max:
        return w * math.sqrt(w)
    return np.nan


@jit(inline=True)
def P_table_forward(data, w):
    """P*(w) from the table (within ~1e-14 of :func:`P_forward`, ~7x cheaper above w = 1.9).

    For Newton slopes and other places where the last digits do not matter; reported forces use
    the exact :func:`P_forward`. NaN outside [0, w_max].
    """
    if w > W_SWITCH:
        if w <= data.w_max:
            return cell_polynomial(data.p_rows, cell_index(w, data.shift, data.base), w)
        return np.nan
    if w >= 0.0 and w <= data.w_max:
        return w * math.sqrt(w)
    return np.nan


@jit(inline=True)
def FP_table_forward(data, w):
    """(F(w), P*(w)) with P* from its table: one cell lookup for both (NaN outside [0, w_max]).

    The pair a Newton iteration on the energy balance needs (energy and its slope, the force);
    about 3x cheaper than :func:`F_forward` plus :func:`P_forward` above w = 1.9.
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
def forward_values(data, w):
    """(F, P*, R, L) at interference w: loading energy, force, returned and dissipated energy.

    Energies over U_c, force over P_c. R = P*(w) (w - w_res*(w)) (JGM eq 38 with the unloading
    model's w_res*), L = F - R without cancellation. All NaN outside [0, w_max] or for an unknown
    unloading model.
    """
    if not (w >= 0.0 and w <= data.w_max and data.model >= 0 and data.model < N_MODELS):
        return np.nan, np.nan, np.nan, np.nan
    if w <= W_SWITCH:
        p = w * math.sqrt(w)
        f = w * p
    else:
        f = cell_polynomial(data.f_rows, cell_index(w, data.shift, data.base), w)
        p = _p_jg(data, w)
    if w <= 1.0:
        return f, p, f, 0.0  # elastic
    # the unloading model's energy split of an impact whose loading energy is f
    e2, loss, _, _, _ = restitution(data.model, f, w, w - 1.0, p, data.eps_y, data.nu)
    return f, p, e2 * f, loss * f


@jit(inline=True)
def returned_forward(data, w):
    """Energy returned by elastic unloading from w over U_c, P*(w) (w - w_res*(w)); NaN outside [0, w_max]."""
    return forward_values(data, w)[2]


@jit(inline=True)
def loss_forward(data, w):
    """Energy dissipated by loading to w and unloading, over U_c: F(w) - R(w) (0 for w <= 1)."""
    return forward_values(data, w)[3]


# --- building ----------------------------------------------------------------------------------

@jit
def _p_nodes(nodes, eps_y, nu, out):
    C = c_of_nu(nu)
    B = area_exponent(eps_y)
    for i in range(nodes.size):
        out[i] = p_star_jg(nodes[i], eps_y, nu, C, B)


@jit
def _f_march(nodes, eps_y, nu, out):
    """F at increasing nodes (all > 1.9): one pass of jg_integral with Neumaier summation."""
    C = c_of_nu(nu)
    B = area_exponent(eps_y)
    s = F_SWITCH
    comp = 0.0
    w_prev = W_SWITCH
    for i in range(nodes.size):
        inc = 2.5 * jg_integral(w_prev, nodes[i], eps_y, nu, C, B)
        t = s + inc
        if abs(s) >= abs(inc):
            comp += (s - t) + inc
        else:
            comp += (inc - t) + s
        s = t
        out[i] = s + comp
        w_prev = nodes[i]


def forward_limit(eps_y, nu, *, extrapolate=False):
    """Largest w* a :class:`ForwardData` may serve: 425 (JGM's range) or, extrapolating, a/R = 1."""
    eps_y = float(check_eps_y(real_scalar(eps_y, "eps_y")))
    nu = float(check_nu(real_scalar(nu, "nu")))
    return omega_limit(eps_y, nu, extrapolate=check_bool(extrapolate, "extrapolate"))


def forward_data(eps_y, nu, w_max, unloading="jcg", *, extrapolate=False,
                 bits_per_octave=BITS_PER_OCTAVE):
    """Tabulate the forward map of one material up to interference ``w_max``.

    Parameters
    ----------
    eps_y : float
        Sy/E' (-), > 0 (validated range 0.0005-0.01; outside: ValidityWarning).
    nu : float
        Poisson's ratio of the yielding material, 0 <= nu < 0.5.
    w_max : float
        Largest normalised interference omega/omega_c to serve (-), >= 0. Only the cells up to it
        are computed (cost grows with log(w_max/1.9): 250 cells and a few ms for w_max = 425).
    unloading : {"jcg", "etsion", "brake"}
        Residual-interference model, JGM eq (35), (33) or Brake's (:mod:`fastrest.unloading`).
    extrapolate : bool
        Allow w_max above 425 (JGM's range), up to the point where a/R = 1.

    Returns
    -------
    ForwardData

    Raises
    ------
    ValueError
        For invalid material or w_max, or w_max beyond the model's range.
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
    lim = float(w_upper_model(eps_y, nu, extrapolate, model))  # the unloading model may end first
    if w_max > lim:
        raise_interference_out_of_range(w_max, eps_y, nu, extrapolate, "w_max", unloading)
    C, B = float(c_of_nu(nu)), float(area_exponent(eps_y))
    shift = MANTISSA_BITS - bits_per_octave
    if w_max <= W_SWITCH:  # closed forms only: one dummy cell
        return ForwardData(model, eps_y, nu, C, B, w_max, shift, 0, np.zeros((1, 8)), np.zeros((1, 8)))
    base, edges = cell_edges(W_SWITCH, w_max, bits_per_octave)
    # Serve whole bit-cells: the last cell ends at its natural boundary, not at w_max, so a table
    # built for a larger w_max holds bit-identical rows for every w both cover.
    end_key = np.array([base + edges.shape[0]], dtype=np.int64) << np.int64(shift)
    edges[-1, 1] = end_key.view(np.float64)[0]
    nodes = chebyshev_nodes(edges)
    flat = np.ascontiguousarray(nodes.ravel())
    f_vals = np.empty(nodes.size)
    _f_march(flat, eps_y, nu, f_vals)
    p_vals = np.empty(nodes.size)
    _p_nodes(flat, eps_y, nu, p_vals)
    f_rows = np.ascontiguousarray(fit_cells(edges, share_edges(f_vals.reshape(nodes.shape))))
    p_rows = np.ascontiguousarray(fit_cells(edges, share_edges(p_vals.reshape(nodes.shape))))
    return ForwardData(model, eps_y, nu, C, B, w_max, shift, int(base), f_rows, p_rows)
