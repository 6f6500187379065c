"""Curves: the model for one material, tabulated once, evaluated in nanoseconds.

:func:`curve` builds a :class:`Curve` for one (eps_y, nu, unloading model) up to the largest
speed a scene needs. w_m*, e and 1 - e^2 are degree-5 polynomials on cells indexed by the float's
bits (:mod:`fastrest.interpolation`) over 1 < V1* <= v_max, fitted at each cell's Chebyshev points
to the direct solver (:mod:`fastrest.direct`) above V1* = 1.9^1.25 and to the exact closed forms
below it (Hertz loading, w_m* = V1*^0.8, JGM eqs 19, 33, 35; :mod:`fastrest.cells`). A cell
boundary sits exactly at 1.9^1.25, so no polynomial straddles the kink. For V1* <= 1 (elastic) the
values are exact: e = 1, 1 - e^2 = 0, w_m* = V1*^0.8.

Why polynomials for a closed form: the Hertz-range formula for e costs five libm calls (~45 ns
here), the cells ~3 ns; with 2^5 cells per octave they reproduce the exact closed form to a few
ulp (measured in tests/test_curve.py and bench/), i.e. they are an implementation of that closed
form in the way libm implements exp, not an approximation of the model.

The curve's data (:mod:`fastrest.curve_data`) is a :class:`~fastrest.curve_data.CurveData`
namedtuple of scalars and arrays: pass it to the jit functions of :mod:`fastrest.jit` from your own
Numba code. Several materials in one batch call: :mod:`fastrest.scene`.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any
from numpy.typing import ArrayLike, NDArray
import functools

import numba as nb
import numpy as np

from . import cells as _cells, curve_data as _curve_data, energy as _energy  # noqa: F401 (aliases below)
from ._deprecation import alias, module_getattr
from ._jit import compiled_entry, jit
from ._validation import (OMEGA_M_STAR_MAX, ExtrapolationWarning, as_float_array,
                          check_velocity, kernel_array, real_scalar, warn, warn_if_outside_validated)
from .curve_data import build_curve_data, check_inputs as check_curve_inputs, curve_array, curve_value
from .fastpath import curve_quantity, fast_scalar
from .limits import speed_limit
from .loading import LAWS, resolve as resolve_loading
from .unloading import get as unloading_model, warn_if_unfitted

if TYPE_CHECKING:
    # not bound at run time: fastrest.curve.CurveData is a deprecated alias (module __getattr__)
    from .curve_data import CurveData

__all__ = ["Curve", "curve"]

# Names that lived here before fastrest.curve_data, fastrest.cells and fastrest.scene: still
# importable from here for one release, with a DeprecationWarning naming their home. The scene's
# names are registered by fastrest.scene (it sits above this module).
__getattr__ = module_getattr(__name__)
for _name, _home in [(n, "cells") for n in ("HERTZ_BASE", "HERTZ_BITS_PER_OCTAVE", "HERTZ_EDGES", "HERTZ_SHIFT",
                                            "N_HERTZ", "closed_form", "hertz_rows", "jg_nodes")] + \
                    [(n, "curve_data") for n in ("BITS_PER_OCTAVE",)] + \
                    [(n, "jit") for n in ("CurveData", "e_curve", "loss_curve", "omega_m_curve")] + \
                    [("V_SWITCH", "energy")]:
    _module = {"cells": _cells, "curve_data": _curve_data, "jit": _curve_data, "energy": _energy}[_home]
    alias(__name__, _name, f"fastrest.{_home}.{_name}", functools.partial(getattr, _module, _name))
del _name, _home, _module


# --- the scalar fast path ---------------------------------------------------------------------

# Scalar calls from Python: the dispatcher's type resolution and unboxing a namedtuple of arrays
# cost more than the evaluation, so Curve's scalar path calls the compiled entry point of this
# kernel directly with one packed array (last row: v_max, shift, base, model, quantity).
@jit
def _packed_kernel(packed, v):
    # the last row is metadata; the cells keep their row numbers
    m = packed.shape[0] - 1
    return curve_value(packed, packed[m, 0], int(packed[m, 1]), int(packed[m, 2]), int(packed[m, 4]), v)


_SCALAR_SIG = (nb.float64[:, ::1], nb.float64)


def _scalar_entry():
    """The compiled entry point of :func:`_packed_kernel` (skips dispatch; ~60 ns faster)."""
    return compiled_entry(_packed_kernel, _SCALAR_SIG)


def _pack(data, what, rows):
    meta = np.zeros((1, rows.shape[1]))
    meta[0, :5] = (data.v_max, data.shift, data.base, data.model, what)
    return np.ascontiguousarray(np.vstack([rows, meta]))


# --- Curve ------------------------------------------------------------------------------------

_METHOD_DOC = """{summary}

Parameters
----------
v1_star : float or array_like
    Impact speed V1* = V1/V_c (-), V_c of JGM eq (28); 0 <= V1* <= ``v_max``.

Returns
-------
float or ndarray
    {returns} (-), shaped like ``v1_star``; a float for a scalar.

Raises
------
TypeError
    ``v1_star`` is not real (a string, boolean, None, complex ...).
ValueError
    V1* < 0, NaN, or past ``v_max`` (the message names v1_star and the limit).

Warns
-----
ExtrapolationWarning
    On a curve built with ``extrapolate=True``: V1* past ``v_limit`` (w_m* = 425).

Notes
-----
From the curve's degree-5 cells (:func:`~fastrest.curve_data.curve_value`): {notes}

Examples
--------
>>> import fastrest
>>> fastrest.curve(0.005, 0.33, v_max=20.0).{name}(0.5)
{example}
"""

#: (method name, summary, returns, notes, example at V1* = 0.5) of the three quantities, in the
#: order of their ``what`` code in :func:`curve_value`.
_QUANTITIES = (
    ("omega_m", "Normalised maximum interference w_m* = omega_m/omega_c at V1*.", "w_m*",
     "The energy balance, JGM eq (29); w_m* = V1*^0.8 below V1* = 1.9^1.25 (eq 19).", "0.5743491774985174"),
    ("e", "Coefficient of restitution e = V2/V1 at V1*.", "e",
     "JGM eqs (16), (38) with the curve's unloading model (eq 35 JCG, 33 Etsion, or Brake).", "1.0"),
    ("loss", "Dissipated fraction 1 - e^2 at V1*, accurate in relative terms as V1* -> 1.", "1 - e^2",
     "JGM eq (38); tabulated directly (not as 1 - e**2), so it keeps its relative accuracy where "
     "e -> 1.", "0.0"),
)


def _quantity_method(what: int) -> Callable[..., float | NDArray[np.float64]]:
    """The method for quantity ``what``: a scalar fast path, else the checked array path."""
    name, summary, returns, notes, example = _QUANTITIES[what]

    def method(self: Curve, v1_star: ArrayLike) -> float | NDArray[np.float64]:
        v = v1_star if type(v1_star) is float else fast_scalar(v1_star)
        if v is not None:  # fast scalar path (floats and NumPy real scalars)
            r = self._entry(self._packed[what], v)
            if r == r:
                return r
        return self._eval(what, v1_star)

    method.__name__ = name
    method.__qualname__ = f"Curve.{name}"
    method.__doc__ = _METHOD_DOC.format(summary=summary, returns=returns, notes=notes, name=name, example=example)
    return method


class Curve:
    """The JGM model for one material and unloading model, tabulated up to ``v_max``.

    Build with :func:`curve`. Methods take V1* = V1/V_c (dimensionless, scalar or array) and
    broadcast; a scalar in gives a float out. Speeds outside [0, v_max] raise ValueError (the
    jit functions in :mod:`fastrest.jit` return NaN instead). Curves pickle (the data travels,
    the compiled entry point is looked up again on arrival).

    Parameters
    ----------
    eps_y : float
        Sy/E' (-), the value the data was built for.
    nu : float
        Poisson's ratio (-).
    unloading : str
        Unloading model name of the data.
    data : CurveData
        From :func:`build_curve_data` (not checked against the other parameters).
    et_ratio : float, optional
        Tangent modulus over Young's modulus Et/E (-) the data was built for, keyword-only
        (default 0: elastic-perfectly plastic).
    loading : str, optional
        Loading law of the data (:mod:`fastrest.loading`), keyword-only; None: the default for
        ``et_ratio`` (Jackson-Green at 0, Ghaednia et al. 2019 above).

    Attributes
    ----------
    eps_y, nu : float
        Material parameters (-).
    unloading : str
        ``"jcg"`` (eq 35), ``"etsion"`` (eq 33) or ``"brake"``.
    et_ratio : float
        Et/E (-); 0 without strain hardening.
    loading : str
        The loading law's name, ``"jackson-green"`` or ``"ghaednia"``.
    v_max : float
        Largest V1* tabulated (-).
    v_limit : float
        V1* of w_m* = 425 (-); an extrapolated curve (``extrapolate=True``) extends past it.
    data : CurveData
        Numba-friendly data for :mod:`fastrest.jit` (``fastrest.jit.e_curve(data, v)``).

    Notes
    -----
    Evaluates JGM eqs (29) (w_m*) and (16), (38) (e) from degree-5 cells (:func:`curve_value`).
    The repr shows ``et_ratio`` and ``loading`` only where they are not the default.

    Examples
    --------
    >>> import fastrest
    >>> c = fastrest.curve(0.005, 0.33, v_max=20.0)
    >>> c.v_max, c.e(1.0)
    (20.0, 1.0)
    """

    #: Class defaults (elastic-perfectly plastic, Jackson-Green) for a pickle that lacks the fields.
    et_ratio: float = 0.0
    loading: str = LAWS["jackson-green"].name

    def __init__(self, eps_y: float, nu: float, unloading: str, data: CurveData, *, et_ratio: float = 0.0,
                 loading: str | None = None) -> None:
        self.eps_y, self.nu, self.unloading, self.data = eps_y, nu, unloading, data
        self.et_ratio = real_scalar(et_ratio, "et_ratio")
        self.loading = resolve_loading(loading, self.et_ratio).name
        self.v_max = data.v_max
        self.v_limit = speed_limit(eps_y, nu, et_ratio=self.et_ratio, loading=self.loading)
        self._packed = [_pack(data, what, rows)
                        for what, rows in enumerate((data.omega_rows, data.e_rows, data.loss_rows))]
        self._entry = _scalar_entry()

    # The compiled entry point does not pickle: ship the data, compile (or load) it on arrival.
    def __getstate__(self) -> dict[str, Any]:
        state = self.__dict__.copy()
        del state["_entry"]
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        self._entry = _scalar_entry()

    def __repr__(self) -> str:
        law = f", et_ratio={self.et_ratio!r}" if self.et_ratio != 0.0 else ""
        if self.loading != resolve_loading(None, self.et_ratio).name:
            law += f", loading={self.loading!r}"
        return (f"Curve(eps_y={self.eps_y!r}, nu={self.nu!r}, unloading={self.unloading!r}{law}, "
                f"v_max={self.v_max!r}, cells={self.data.e_rows.shape[0]})")

    def _eval(self, what, v):
        a = as_float_array(v, "v1_star")
        flat = kernel_array(a)
        out: NDArray[np.float64] = np.empty(flat.size)
        curve_array(self.data, what, flat, out)
        if np.isnan(out).any():
            self._raise(flat[np.isnan(out)])
        out = out.reshape(a.shape)
        return float(out) if out.ndim == 0 else out

    def _raise(self, bad):
        check_velocity(bad, "v1_star")
        raise ValueError(f"v1_star = {float(bad[0])!r} is beyond this curve's v_max = {self.v_max!r}: "
                         + self._end_note())

    def _end_note(self):
        """Where this curve ends and how far a curve of its material may go (error messages)."""
        mat = f"eps_y = {self.eps_y!r}, nu = {self.nu!r}" + (f", et_ratio = {self.et_ratio!r}" if self.et_ratio else "")
        if self.v_max < self.v_limit:
            return (f"build the curve with a larger v_max, up to V1* = {self.v_limit:.10g}, the model's limit "
                    f"(w_m* = {OMEGA_M_STAR_MAX:g}) for {mat}")
        if self.v_max == self.v_limit:
            return (f"that is the model's limit (w_m* = {OMEGA_M_STAR_MAX:g}) for {mat}; extrapolate=True "
                    "extends a curve past it (outside the validated range)")
        end = speed_limit(self.eps_y, self.nu, extrapolate=True, unloading=self.unloading, et_ratio=self.et_ratio,
                          loading=self.loading)
        past = f"past the model's limit (w_m* = {OMEGA_M_STAR_MAX:g} at V1* = {self.v_limit:.10g})"
        if self.v_max >= end:
            return f"that is the end of the model extrapolated {past} for {mat}"
        return (f"the curve is extrapolated {past}; the extrapolated model ends at V1* = {end:.10g} for {mat} "
                "(a larger v_max where a curve can reach it; fastrest.direct computes up to the end)")

    # a float in gives a float out, a sequence an array (fastrest.fastpath.CurveQuantity)
    omega_m = curve_quantity(_quantity_method(0))
    e = curve_quantity(_quantity_method(1))
    loss = curve_quantity(_quantity_method(2))


def _warn_past_limit(method: Callable[..., Any]) -> Any:
    """``method`` of :class:`Curve`, then the ExtrapolationWarning check of an extrapolated curve."""
    @functools.wraps(method)
    def checked(self: _ExtrapolatedCurve, v1_star: ArrayLike) -> float | NDArray[np.float64]:
        out = method(self, v1_star)
        self._check(v1_star)
        return out

    return checked


class _ExtrapolatedCurve(Curve):
    """A :class:`Curve` built with ``extrapolate=True`` past w_m* = 425: every evaluation past
    ``v_limit`` warns (a subclass, so curves that do not extrapolate pay nothing for the check)."""

    def _check(self, v1_star):
        past = (v1_star > self.v_limit if type(v1_star) is float
                else np.any(np.asarray(v1_star, dtype=np.float64) > self.v_limit))
        if past:
            warn(f"V1* past {self.v_limit:.6g} (w_m* = {OMEGA_M_STAR_MAX:g}): extrapolated, the JG law "
                 "is not validated there", ExtrapolationWarning)

    omega_m = _warn_past_limit(Curve.omega_m)
    e = _warn_past_limit(Curve.e)
    loss = _warn_past_limit(Curve.loss)


def curve(eps_y: float, nu: float, unloading: str = "jcg", *, v_max: float | None = None,
          extrapolate: bool = False, et_ratio: float = 0.0, loading: str | None = None) -> Curve:
    """Build a :class:`Curve`: the model for one material, fast, up to the speed a scene needs.

    Parameters
    ----------
    eps_y : float
        Sy/E' (-), > 0; validated range 0.0005-0.01 (outside: ValidityWarning).
    nu : float
        Poisson's ratio of the yielding material (-), 0 <= nu < 0.5 (validated 0.2-0.45).
    unloading : {"jcg", "etsion", "brake"}
        Residual-interference model, JGM eq (35), (33) or Brake's (:mod:`fastrest.unloading`).
    v_max : float, optional
        Largest V1* = V1/V_c needed (-), keyword-only. Default: the model's limit, w_m* = 425. A
        larger value raises ValueError naming the limit.
    extrapolate : bool
        Allow w_m* > 425 up to a/R = 1 (ExtrapolationWarning), keyword-only.
    et_ratio : float
        Tangent modulus over Young's modulus Et/E (-) of the yielding material, 0 <= et_ratio < 1,
        keyword-only. Default 0: elastic-perfectly plastic (JGM). Above 0 the loading law is
        Ghaednia et al. (2019) (:mod:`fastrest.loading.ghaednia`); V1* stays V1/V_c of JGM eq (28).
    loading : {None, "jackson-green", "ghaednia"}
        Loading law (:mod:`fastrest.loading`), keyword-only; None picks it from ``et_ratio``.

    Returns
    -------
    Curve
        ``.e(v)``, ``.omega_m(v)``, ``.loss(v)`` at V1* in [0, v_max] (broadcast; ValueError past
        v_max), ``.v_max``, and ``.data`` for :mod:`fastrest.jit`. Accuracy against the direct
        solver: 1.1e-13 relative for e and w_m*, 3.5e-12 for 1 - e^2 (bench/STATED_FIGURES.md).

    Raises
    ------
    TypeError
        eps_y, nu, v_max or et_ratio is not a real number; extrapolate is not a bool.
    ValueError
        eps_y <= 0, nu outside [0, 0.5), et_ratio outside [0, 1), unknown ``unloading`` or
        ``loading``, ``loading="jackson-green"`` with et_ratio > 0, or v_max past the model's limit
        (w_m* = 425, or a/R = 1 with ``extrapolate``); the message names the parameter and limit.

    Warns
    -----
    ValidityWarning
        eps_y or nu outside the validated range (0.0005-0.01, 0.2-0.45); JCG or Etsion unloading
        with et_ratio > 0 (fitted without hardening; Brake's is the hardening law's pairing).
    ExtrapolationWarning
        With ``extrapolate=True``, when the curve extends past w_m* = 425.

    Notes
    -----
    Tabulates JGM eqs (29) (energy balance for w_m*), (38) with (33)/(35) (e) on degree-5 cells;
    see the module docstring.

    Examples
    --------
    >>> import fastrest
    >>> c = fastrest.curve(0.005, 0.33, v_max=200.0)
    >>> c.e([1.0, 20.0, 200.0]).round(4).tolist()
    [1.0, 0.7463, 0.4461]

    A material with strain hardening, Et/E = 0.01 (Brake unloading, the hardening law's pairing):

    >>> h = fastrest.curve(0.005, 0.33, "brake", v_max=200.0, et_ratio=0.01)
    >>> h
    Curve(eps_y=0.005, nu=0.33, unloading='brake', et_ratio=0.01, v_max=200.0, cells=280)
    >>> bool(h.e(20.0) > fastrest.curve(0.005, 0.33, "brake", v_max=200.0).e(20.0))
    True
    """
    return _curve(eps_y, nu, unloading, v_max, extrapolate, et_ratio, loading, True)


def _curve(eps_y, nu, unloading, v_max, extrapolate, et_ratio, loading, warn_unfitted):
    """:func:`curve`; ``warn_unfitted=False`` leaves the warning of JCG/Etsion unloading with
    hardening to the caller (a scene warns once, not once per material)."""
    eps_y, nu, v_max, extrapolate, _ = check_curve_inputs(eps_y, nu, v_max, extrapolate)
    et_ratio = real_scalar(et_ratio, "et_ratio")
    law = resolve_loading(loading, et_ratio).name  # validates et_ratio and loading
    model = unloading_model(unloading)
    warn_if_outside_validated(eps_y, nu)
    if warn_unfitted:
        warn_if_unfitted(model, et_ratio)
    data = build_curve_data(eps_y, nu, unloading, v_max=v_max, extrapolate=extrapolate, et_ratio=et_ratio,
                            loading=law)
    cls = _ExtrapolatedCurve if speed_limit(eps_y, nu, et_ratio=et_ratio, loading=law) < data.v_max else Curve
    c = cls(eps_y, nu, unloading, data, et_ratio=et_ratio, loading=law)
    if c.v_limit < data.v_max:
        warn(f"curve extends past w_m* = {OMEGA_M_STAR_MAX:g} (V1* = {c.v_limit:.6g}) to "
             f"V1* = {data.v_max:.6g}: extrapolated there; evaluations past it warn too", ExtrapolationWarning)
    return c
