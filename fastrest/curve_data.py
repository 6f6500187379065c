"""Curve data: the cells of one material and the jit functions that evaluate them.

:func:`build_curve_data` tabulates w_m*, e and 1 - e^2 of one (eps_y, nu, unloading model) as
degree-5 polynomials on cells indexed by the float's bits (:mod:`fastrest.interpolation`) over
1 < V1* <= v_max: the Hertz range's closed forms first (:mod:`fastrest.cells`), then the JG cells
fitted at their Chebyshev points to the direct solver (:mod:`fastrest.direct`). The result is a
:class:`CurveData` namedtuple of scalars and arrays, which :func:`curve_value` evaluates in Numba
code (one rule for curves and scenes). The Python objects around it: :mod:`fastrest.curve`
(:class:`~fastrest.curve.Curve`) and :mod:`fastrest.scene`; from your own Numba code:
:mod:`fastrest.jit`.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
from collections import namedtuple

import numpy as np

from ._jit import jit
from . import loading as _loading
from . import unloading as _unloading
from .cells import HERTZ_BASE, HERTZ_SHIFT, N_HERTZ, hertz_rows, jg_nodes
from .energy import V_SWITCH, f_star_kernel, omega_m_sorted_kernel
from .interpolation import MANTISSA_BITS, cell_edges, cell_polynomial_in_range, fit_cells, float_bits, share_edges
from ._validation import check_bool, check_count, check_eps_y, check_nu, check_velocity, real_scalar
from .limits import raise_out_of_range, speed_limit, w_upper_model

__all__ = ["BITS_PER_OCTAVE", "CurveData", "curve_value", "omega_m_curve", "e_curve", "loss_curve", "curve_array",
           "build_curve_data"]

#: Cells per octave of V1* (2^K); K = 5 measured to give ~4e-14 on e and w_m* (bench/, section 1).
BITS_PER_OCTAVE = 5
#: Largest K :func:`build_curve_data` takes (2^12 cells per octave: far past any accuracy need).
MAX_BITS_PER_OCTAVE = 12

CurveData = namedtuple("CurveData", ["model", "v_max", "shift", "base", "omega_rows", "e_rows", "loss_rows"])
CurveData.__doc__ = """Numba-friendly data of one :class:`~fastrest.curve.Curve` (a namedtuple).

Attributes
----------
model : int
    Unloading model code: 0 JCG (JGM eq 35), 1 Etsion (eq 33), 2 Brake.
v_max : float
    Largest V1* tabulated (-).
shift, base : int
    Index parameters of the JG cells: row = ((bits of V1*) >> shift) - base.
omega_rows, e_rows, loss_rows : ndarray
    (ncell, 8) float64 rows [center, 1/half_width, c0..c5] of w_m*, e and 1 - e^2: first the
    N_HERTZ rows of the Hertz-range closed forms (1 < V1* <= 1.9^1.25; for 1 - e^2 they hold
    (1 - e^2)/(V1* - 1)), then the JG cells from 1.9^1.25 to v_max.

Notes
-----
Built by :func:`build_curve_data`, evaluated by :func:`curve_value` (JGM eqs 29, 38). Pass it to
:func:`fastrest.jit.e_curve` in your own Numba code.

Examples
--------
>>> import fastrest
>>> d = fastrest.curve(0.005, 0.33, v_max=20.0).data
>>> d.model, d.v_max, d.e_rows.shape[1]
(0, 20.0, 8)
"""


# --- scalar kernels on CurveData (fastrest.jit re-exports these) ------------------------------

@jit(inline=True)
def curve_value(rows, v_max, shift, base, what, v_in):
    """Quantity ``what`` at V1* from one curve's cells: the one evaluation rule of curves and scenes.

    Parameters
    ----------
    rows : ndarray
        (ncell, 8) float64 cell rows of the quantity (:class:`CurveData`).
    v_max : float
        Largest V1* the rows cover (-).
    shift, base : int
        Index parameters of the JG cells: row = (bits of V1*) >> shift) - base.
    what : int
        0 w_m*, 1 e, 2 1 - e^2.
    v_in : float or int
        V1* = V1/V_c (-), JGM eq (30); float32 and integers are taken as the Python API takes them.

    Returns
    -------
    float
        The quantity (-); NaN for V1* < 0, NaN or V1* > v_max (a kernel: no exception).

    Notes
    -----
    1 < V1* <= v_max: the polynomial of V1*'s cell, the Hertz closed forms up to 1.9^1.25 (rows
    0..N_HERTZ-1, 2^6 cells per octave; JGM eqs 19, 33, 35), the JG model above (row
    key(V1*) - base; eqs 29, 38). 0 <= V1* <= 1: elastic, exact (w_m* = V1*^0.8, e = 1).

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.curve_data import curve_value
    >>> d = fastrest.curve(0.005, 0.33, v_max=20.0).data
    >>> curve_value(d.e_rows, d.v_max, d.shift, d.base, 1, 0.5)
    1.0
    """
    v = np.float64(v_in)  # float32 and integer speeds, as the Python API takes them
    if v > 1.0:
        if v <= v_max:
            # Hertz or JG cell by a select, not a branch: mixed speeds would mispredict
            hertz = v <= V_SWITCH
            b = float_bits(v)
            i = (b >> HERTZ_SHIFT) - HERTZ_BASE if hertz else (b >> shift) - base
            r = cell_polynomial_in_range(rows, i, v)   # 1 < v <= v_max: a row of a curve's own data
            if what == 2 and hertz:
                r *= v - 1.0
            return r
        return np.nan
    if v >= 0.0 and v <= v_max:
        if what == 0:
            return v**0.8
        return 1.0 if what == 1 else 0.0
    return np.nan


_KERNEL_DOC = """{what} at V1* from a curve's data, in Numba code.

Parameters
----------
data : CurveData
    ``Curve.data``.
v : float
    V1* = V1/V_c (-), JGM eq (30).

Returns
-------
float
    {what} (-); NaN for V1* < 0, NaN, or > ``data.v_max`` (no exception, no warning).

Notes
-----
{notes} See :func:`curve_value`.

Examples
--------
>>> import fastrest
>>> from fastrest.curve_data import {name}
>>> {name}(fastrest.curve(0.005, 0.33, v_max=20.0).data, 0.5)
{example}
"""


@jit
def omega_m_curve(data, v):
    return curve_value(data.omega_rows, data.v_max, data.shift, data.base, 0, v)


@jit
def e_curve(data, v):
    return curve_value(data.e_rows, data.v_max, data.shift, data.base, 1, v)


@jit
def loss_curve(data, v):
    return curve_value(data.loss_rows, data.v_max, data.shift, data.base, 2, v)


omega_m_curve.__doc__ = _KERNEL_DOC.format(what="w_m*", name="omega_m_curve", example="0.5743491774985174",
                                           notes="JGM eq (29), normalised maximum interference.")
e_curve.__doc__ = _KERNEL_DOC.format(what="e", name="e_curve", example="1.0",
                                     notes="JGM eqs (16), (38), coefficient of restitution.")
loss_curve.__doc__ = _KERNEL_DOC.format(what="1 - e^2", name="loss_curve", example="0.0",
                                        notes="Dissipated fraction of the impact energy, JGM eq (38).")


@jit
def curve_array(data, what, v, out):
    """out[i] = quantity ``what`` of the curve at V1* = v[i] (0 w_m*, 1 e, 2 1 - e^2).

    Parameters
    ----------
    data : CurveData
        ``Curve.data``.
    what : int
        0 w_m*, 1 e, 2 1 - e^2.
    v : ndarray
        1-D float64 V1* (-).
    out : ndarray
        1-D float64, the length of ``v``; written in place (-).

    Notes
    -----
    NaN where :func:`curve_value` gives NaN; the Python layer (:class:`~fastrest.curve.Curve`) raises for them.

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> from fastrest.curve_data import curve_array
    >>> out = np.empty(2)
    >>> curve_array(fastrest.curve(0.005, 0.33, v_max=20.0).data, 1, np.array([0.5, 50.0]), out)
    >>> out.tolist()
    [1.0, nan]
    """
    if what == 0:
        for i in range(v.size):
            out[i] = omega_m_curve(data, v[i])
    elif what == 1:
        for i in range(v.size):
            out[i] = e_curve(data, v[i])
    else:
        for i in range(v.size):
            out[i] = loss_curve(data, v[i])


# --- building ---------------------------------------------------------------------------------

def build_curve_data(eps_y: float, nu: float, unloading: str = "jcg", *, v_max: float | None = None, extrapolate: bool = False,
                     bits_per_octave: int = BITS_PER_OCTAVE, jg_values: Any = None, et_ratio: float = 0.0,
                     loading: Any = None) -> CurveData:
    """Tabulate one material: the :class:`CurveData` behind a :class:`~fastrest.curve.Curve`.

    Parameters
    ----------
    eps_y : float
        Sy/E' (-), > 0 and finite (validated as :func:`fastrest.curve` does, without its warning
        outside the validated range).
    nu : float
        Poisson's ratio (-), 0 <= nu < 0.5.
    unloading : {"jcg", "etsion", "brake"}
        Unloading model (:mod:`fastrest.unloading`).
    v_max : float, optional
        Largest V1* tabulated (-), finite and >= 0; default: the model's limit (w_m* = 425, or a/R = 1, or where the
        unloading model ends).
    extrapolate : bool
        Allow w_m* > 425 (keyword-only).
    bits_per_octave : int
        Cells per octave of V1* above the kink, 2^bits_per_octave, 1 <= bits_per_octave <= 12
        (keyword-only).
    et_ratio : float, optional
        Tangent modulus over Young's modulus Et/E (-), 0 <= et_ratio < 1 (keyword-only; default 0).
    loading : str, LoadingLaw or None, optional
        The loading law (:func:`fastrest.loading.resolve`; keyword-only).
    jg_values : callable, optional
        ``jg_values(v) -> (3, n)`` array of w_m*, e and 1 - e^2 at speeds v > 1.9^1.25, replacing the
        direct solver (bench/ builds a curve from a table this way; keyword-only).

    Returns
    -------
    CurveData
        The Hertz-range rows (:func:`fastrest.cells.hertz_rows`) and the JG cells up to ``v_max``.

    Raises
    ------
    TypeError
        eps_y, nu, v_max, et_ratio or bits_per_octave is not a real number; extrapolate is not a bool.
    ValueError
        eps_y <= 0 or not finite, nu outside [0, 0.5), v_max < 0 or not finite, et_ratio outside
        [0, 1), bits_per_octave outside [1, 12]; unknown ``unloading``; ``v_max`` past the model's
        limit, or past where a curve may tabulate an extrapolated model that ends (the message
        names the limit).

    Notes
    -----
    Above V1* = 1.9^1.25 the cells interpolate the energy balance (JGM eq 29) and the unloading
    model's restitution (eqs 33-38) at their Chebyshev-Lobatto points.

    Examples
    --------
    >>> from fastrest.curve_data import build_curve_data
    >>> d = build_curve_data(0.005, 0.33, "jcg", v_max=20.0)
    >>> d.v_max, d.e_rows.shape[1]
    (20.0, 8)
    """
    eps_y, nu, v_max, extrapolate, bits_per_octave = check_inputs(eps_y, nu, v_max, extrapolate, bits_per_octave)
    unit = _unloading.get(unloading)
    model = unit.code
    law = _loading.resolve(loading, real_scalar(et_ratio, "et_ratio"))  # validates et_ratio and loading
    w_hi = w_upper_model(eps_y, nu, extrapolate, model, law.code, et_ratio)
    limit = speed_limit(eps_y, nu, extrapolate=extrapolate, unloading=unloading, et_ratio=et_ratio, loading=law)
    if v_max is not None and v_max > limit:
        raise_out_of_range(np.array([v_max]), np.array([eps_y]), np.array([nu]), extrapolate, "v_max", unloading,
                           et_ratio=et_ratio, loading=law)
    if unit.cells_end < w_hi:  # extrapolating towards an unloading model's end: stop short of it
        w_hi = unit.cells_end
        short = float(np.sqrt(f_star_kernel(w_hi, eps_y, nu, law.code, et_ratio)))
        if v_max is not None and v_max > short:
            raise ValueError(
                f"v_max = {v_max!r} is past V1* = {short:.10g} (w_m* = {w_hi:.6g}), the end of what a curve "
                f"tabulates for {unit.short} unloading: towards the end of {unit.equation} (w_m* = "
                f"{unit.omega_end:.6g}, V1* = {limit:.10g}) e falls to 0 like a square root, which the "
                "curve's polynomial cells cannot follow at its accuracy; use fastrest.direct there")
        limit = short
    if v_max is None:
        v_max = limit
    shift = MANTISSA_BITS - bits_per_octave
    hertz = hertz_rows(model)
    if v_max <= V_SWITCH:  # closed forms only
        return CurveData(model, float(v_max), shift, 0, *[np.ascontiguousarray(h) for h in hertz])
    base, edges = cell_edges(V_SWITCH, v_max, bits_per_octave)
    flat = jg_nodes(edges, v_max)
    if jg_values is None:
        vals = np.empty((3, flat.size))
        omega_m_sorted_kernel(flat, eps_y, nu, w_hi, law.code, et_ratio, vals[0])
        _restitution_array(flat, vals[0], eps_y, nu, model, law.code, et_ratio, vals[1:])
    else:
        vals = np.asarray(jg_values(flat))
    vals = share_edges(vals.reshape(3, edges.shape[0], -1))
    rows = [np.ascontiguousarray(np.concatenate([h, fit_cells(edges, q)])) for h, q in zip(hertz, vals)]
    # JG cell of key k is row k - base + N_HERTZ
    return CurveData(model, float(v_max), shift, int(base) - N_HERTZ, *rows)


def check_inputs(eps_y, nu, v_max, extrapolate, bits_per_octave=BITS_PER_OCTAVE):
    """The inputs of :func:`build_curve_data` and :func:`fastrest.curve`, validated (one rule, the
    same messages): TypeError for non-numbers, ValueError out of range."""
    eps_y = real_scalar(eps_y, "eps_y")
    nu = real_scalar(nu, "nu")
    check_eps_y(eps_y)
    check_nu(nu)
    if v_max is not None:
        v_max = float(check_velocity(real_scalar(v_max, "v_max"), "v_max"))
    extrapolate = check_bool(extrapolate, "extrapolate")
    bits_per_octave = check_count(bits_per_octave, "bits_per_octave", 1, MAX_BITS_PER_OCTAVE)
    return eps_y, nu, v_max, extrapolate, bits_per_octave


@jit
def _restitution_array(v, w, eps_y, nu, model, law, et_ratio, out):
    """out[:, i] = (e, 1 - e^2) at V1* = v[i] with w_m* = w[i] (w > 1.9)."""
    for i in range(v.size):
        e, loss, _, _ = _unloading.restitution_kernel(v[i], w[i], w[i] - 1.0, eps_y, nu, model, law, et_ratio)
        out[0, i] = e
        out[1, i] = loss
