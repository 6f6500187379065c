"""Scene curves: the model for one material, tabulated once, evaluated in nanoseconds.

:func:`curve` builds a :class:`Curve` for one (eps_y, nu, unloading model) up to the largest
speed a scene needs. w_m*, e and 1 - e^2 are degree-5 polynomials on cells indexed by the float's
bits (:mod:`fastrest.interpolation`) over 1 < V1* <= v_max, fitted at each cell's Chebyshev points
to the direct solver (:mod:`fastrest.direct`) above V1* = 1.9^1.25 and to the exact closed forms
below it (Hertz loading, w_m* = V1*^0.8, JGM eqs 19, 33, 35). A cell boundary sits exactly at
1.9^1.25, so no polynomial straddles the kink. For V1* <= 1 (elastic) the values are exact: e = 1,
1 - e^2 = 0, w_m* = V1*^0.8.

Why polynomials for a closed form: the Hertz-range formula for e costs five libm calls (~45 ns
here), the cells ~3 ns; with 2^5 cells per octave they reproduce the exact closed form to a few
ulp (measured in tests/test_curve.py and bench/), i.e. they are an implementation of that closed
form in the way libm implements exp, not an approximation of the model.

The curve's data is a :class:`CurveData` namedtuple of scalars and arrays: pass it to the
``@njit`` functions of :mod:`fastrest.jit` from your own Numba code.
"""
import math
from collections import namedtuple

import numba as nb
import numpy as np
from numba.extending import overload

from ._validation import (OMEGA_M_STAR_MAX, ExtrapolationWarning, as_float_array, broadcast_named, check_bool, check_eps_y, check_nu,
                          check_velocity, real_scalar, warn, warn_if_outside_validated)
from .energy import V_SWITCH, f_star_kernel, omega_m_sorted_kernel
from .contact import W_SWITCH
from .interpolation import (MANTISSA_BITS, cell_edges, cell_polynomial, chebyshev_nodes, fit_cells, float_bits,
                            share_edges)
from ._jit import compiled_entry
from .limits import raise_out_of_range, v1_star_limit, w_upper_model
from . import unloading as _unloading

#: Cells per octave of V1* (2^K); K = 5 measured to give ~4e-14 on e and w_m* (bench/, section 1).
BITS_PER_OCTAVE = 5

CurveData = namedtuple("CurveData", ["model", "v_max", "shift", "base", "omega_rows", "e_rows", "loss_rows"])
CurveData.__doc__ = """Numba-friendly data of one :class:`Curve`.

model: 0 = JCG (eq 35), 1 = Etsion (eq 33); v_max: largest V1* tabulated; shift, base: index
parameters of the JG cells (row = (bits of V1*) >> shift) - base); *_rows: (ncell, 8) float64
arrays of [center, 1/half_width, c0..c5] for w_m*, e, 1 - e^2: first the N_HERTZ rows of the
Hertz-range closed forms (1 < V1* <= 1.9^1.25; for 1 - e^2 they hold (1 - e^2)/(V1* - 1)), then
the JG cells from 1.9^1.25 to v_max.
"""


# --- closed forms below the JG range ----------------------------------------------------------

@nb.njit(cache=True)
def closed_form(v, model):
    """(w_m*, e, 1 - e^2) for 0 <= v <= 1.9^1.25 (Hertz loading), exact (JGM eqs 19, 38 and the
    unloading model's residual). The same for every material: under Hertz loading P_m* = w_m*^1.5
    and every registered unloading model's w_res* depends on w_m* alone (tests/test_unloading.py)."""
    if v <= 1.0:
        return v**0.8, 1.0, 0.0
    lv = math.log(v)
    w = min(math.exp(0.8 * lv), W_SWITCH)
    # eps_y and nu are not read under Hertz loading: NaN would show if a model did
    e2, loss, _, _, _ = _unloading.restitution(model, v * v, w, math.expm1(0.8 * lv), w**1.5, np.nan, np.nan)
    return w, math.sqrt(e2), loss


@nb.njit(cache=True)
def hertz_node_values(v, model):
    """(w_m*, e, (1 - e^2)/(V1* - 1)) at 1 < v <= 1.9^1.25: what the Hertz-range cells fit.

    The loss is fitted divided by V1* - 1 (exact in floating point for 1 < V1* <= 2) and multiplied
    back on evaluation, so 1 - e^2 keeps its relative accuracy as V1* -> 1.
    """
    out = np.empty((3, v.size))
    for i in range(v.size):
        w, e, loss = closed_form(v[i], model)
        out[0, i] = w
        out[1, i] = e
        out[2, i] = loss / (v[i] - 1.0)
    return out


#: Cells per octave of the Hertz-range cells (2^6): the closed forms to ~1e-16 (measured in
#: tests/test_curve.py; 2^5 leaves ~5e-15 on w_m* = V1*^0.8 near V1* = 2).
HERTZ_BITS_PER_OCTAVE = 6
HERTZ_SHIFT = MANTISSA_BITS - HERTZ_BITS_PER_OCTAVE


def _hertz_layout():
    base, edges = cell_edges(1.0, V_SWITCH, HERTZ_BITS_PER_OCTAVE)
    return int(base), edges


HERTZ_BASE, HERTZ_EDGES = _hertz_layout()
#: Rows of the Hertz-range cells, which come first in every curve's row arrays.
N_HERTZ = HERTZ_EDGES.shape[0]


def hertz_rows(model):
    """Cell rows (w_m*, e, (1 - e^2)/(V1* - 1)) of the closed forms over 1 < V1* <= 1.9^1.25."""
    nodes = chebyshev_nodes(HERTZ_EDGES)
    nodes[0, 0] = np.nextafter(1.0, 2.0)  # (1 - e^2)/(V1* - 1) is 0/0 at 1: its limit, one ulp in
    vals = hertz_node_values(nodes.ravel(), model).reshape((3,) + nodes.shape)
    return fit_cells(HERTZ_EDGES, share_edges(vals))


# --- scalar kernels on CurveData (the public njit API re-exports these) ----------------------

@nb.njit(cache=True, inline="always")
def curve_value(rows, v_max, shift, base, what, v_in):
    """Quantity ``what`` (0 w_m*, 1 e, 2 1 - e^2) at V1* = v from one curve's cells.

    1 < V1* <= v_max: the polynomial of V1*'s cell: the Hertz closed forms up to 1.9^1.25 (rows
    0..N_HERTZ-1, 2^6 cells per octave), the JG model above (row key(V1*) - base). 0 <= V1* <= 1:
    elastic, exact. NaN for V1* < 0, NaN or V1* > v_max. The one evaluation rule of curves and scenes.
    """
    v = np.float64(v_in)  # float32 and integer speeds, as the Python API takes them
    if v > 1.0:
        if v <= v_max:
            # Hertz or JG cell by a select, not a branch: mixed speeds would mispredict
            hertz = v <= V_SWITCH
            b = float_bits(v)
            i = (b >> HERTZ_SHIFT) - HERTZ_BASE if hertz else (b >> shift) - base
            r = cell_polynomial(rows, i, v)
            if what == 2 and hertz:
                r *= v - 1.0
            return r
        return np.nan
    if v >= 0.0 and v <= v_max:
        if what == 0:
            return v**0.8
        return 1.0 if what == 1 else 0.0
    return np.nan


@nb.njit(cache=True)
def omega_m_curve(data, v):
    """w_m*(V1*) from a curve; NaN for V1* < 0, NaN, or > data.v_max."""
    return curve_value(data.omega_rows, data.v_max, data.shift, data.base, 0, v)


@nb.njit(cache=True)
def e_curve(data, v):
    """e(V1*) from a curve; NaN for V1* < 0, NaN, or > data.v_max."""
    return curve_value(data.e_rows, data.v_max, data.shift, data.base, 1, v)


@nb.njit(cache=True)
def loss_curve(data, v):
    """1 - e^2 at V1* from a curve; NaN for V1* < 0, NaN, or > data.v_max."""
    return curve_value(data.loss_rows, data.v_max, data.shift, data.base, 2, v)


@nb.njit(cache=True)
def _curve_array(data, what, v, out):
    if what == 0:
        for i in range(v.size):
            out[i] = omega_m_curve(data, v[i])
    elif what == 1:
        for i in range(v.size):
            out[i] = e_curve(data, v[i])
    else:
        for i in range(v.size):
            out[i] = loss_curve(data, v[i])


# Scalar calls from Python: the dispatcher's type resolution and unboxing a namedtuple of arrays
# cost more than the evaluation, so Curve's scalar path calls the compiled entry point of this
# kernel directly with one packed array (last row: v_max, shift, base, model, quantity).
@nb.njit(cache=True)
def _scalar_packed(packed, v):
    # the last row is metadata; the cells keep their row numbers
    m = packed.shape[0] - 1
    return curve_value(packed, packed[m, 0], int(packed[m, 1]), int(packed[m, 2]), int(packed[m, 4]), v)


_SCALAR_SIG = (nb.float64[:, ::1], nb.float64)


def _scalar_entry():
    """The compiled entry point of :func:`_scalar_packed` (skips dispatch; ~60 ns faster)."""
    return compiled_entry(_scalar_packed, _SCALAR_SIG)


#: Scalar types the fast paths take as they are (float64 is a float subclass) or convert exactly.
_FAST_FLOAT = (float, np.float64)
_FAST_CONVERT = (np.float32, np.float16, np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16,
                 np.uint32, np.uint64)


def _fast_scalar(x):
    """``x`` as a float if it is a real scalar the fast path may take (a Python float, a NumPy
    float or integer scalar: what a loop over an array yields, or a Python int within float range);
    None otherwise (booleans, strings, arrays: the checked path decides)."""
    t = type(x)
    if t in _FAST_FLOAT:
        return x
    if t in _FAST_CONVERT:
        return float(x)
    if t is int and -2**53 <= x <= 2**53:
        return float(x)
    return None


def _pack(data, what, rows):
    meta = np.zeros((1, rows.shape[1]))
    meta[0, :5] = (data.v_max, data.shift, data.base, data.model, what)
    return np.ascontiguousarray(np.vstack([rows, meta]))


# --- building ---------------------------------------------------------------------------------

def build_curve_data(eps_y, nu, unloading="jcg", v_max=None, extrapolate=False,
                     bits_per_octave=BITS_PER_OCTAVE, jg_values=None):
    """Tabulate one material: returns :class:`CurveData` (no validation of eps_y/nu here).

    ``jg_values(v)``, if given, replaces the direct solver above 1.9^1.25: it returns the (3, n)
    array of w_m*, e and 1 - e^2 at the speeds v (used by bench/ to build a curve from a table).
    """
    unit = _unloading.get(unloading)
    model = unit.code
    w_hi = w_upper_model(eps_y, nu, extrapolate, model)
    limit = v1_star_limit(eps_y, nu, extrapolate=extrapolate, unloading=unloading)
    if v_max is not None and v_max > limit:
        raise_out_of_range(np.array([v_max]), np.array([eps_y]), np.array([nu]), extrapolate, "v_max", unloading)
    if unit.cells_end < w_hi:  # extrapolating towards an unloading model's end: stop short of it
        w_hi = unit.cells_end
        short = float(np.sqrt(f_star_kernel(w_hi, eps_y, nu)))
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
        w = np.empty(flat.size)
        omega_m_sorted_kernel(flat, eps_y, nu, w_hi, w)
        vals = np.concatenate([w[None], _restitution_at(flat, w, eps_y, nu, model)])
    else:
        vals = np.asarray(jg_values(flat))
    vals = share_edges(vals.reshape(3, edges.shape[0], -1))
    rows = [np.ascontiguousarray(np.concatenate([h, fit_cells(edges, q)])) for h, q in zip(hertz, vals)]
    # JG cell of key k is row k - base + N_HERTZ
    return CurveData(model, float(v_max), shift, int(base) - N_HERTZ, *rows)


def jg_nodes(edges, v_top):
    """The cells' interpolation points above the kink, flattened and increasing, kept inside
    (1.9^1.25, v_top]: the first cell's left end takes the JG side's limit (one ulp above the
    kink), and in cells a few ulp wide no rounded point falls outside (nodes an ulp from where the
    fit places them change values by ~1e-16 relative)."""
    nodes = chebyshev_nodes(edges)
    return np.ascontiguousarray(np.clip(nodes, np.nextafter(V_SWITCH, np.inf), v_top).ravel())


@nb.njit(cache=True)
def _restitution_at(v, w, eps_y, nu, model):
    out = np.empty((2, v.size))
    for i in range(v.size):
        e, loss, _, _ = _unloading.restitution_kernel(v[i], w[i], w[i] - 1.0, eps_y, nu, model)
        out[0, i] = e
        out[1, i] = loss
    return out


class Curve:
    """The JGM model for one material and unloading model, tabulated up to ``v_max``.

    Build with :func:`curve`. Methods take V1* = V1/V_c (dimensionless, scalar or array) and
    broadcast; a scalar in gives a float out. Speeds outside [0, v_max] raise ValueError (the
    jitted functions in :mod:`fastrest.jit` return NaN instead).

    Attributes
    ----------
    eps_y, nu : float
        Material parameters (-).
    unloading : str
        ``"jcg"`` (eq 35) or ``"etsion"`` (eq 33).
    v_max : float
        Largest V1* tabulated (-).
    data : CurveData
        Numba-friendly data for :mod:`fastrest.jit` (``fastrest.jit.e_curve(data, v)``).
    """

    def __init__(self, eps_y, nu, unloading, data):
        self.eps_y, self.nu, self.unloading, self.data = eps_y, nu, unloading, data
        self.v_max = data.v_max
        #: V1* of w_m* = 425; an extrapolated curve (``extrapolate=True``) extends past it.
        self.v_limit = v1_star_limit(eps_y, nu)
        self._packed = [_pack(data, what, rows)
                        for what, rows in enumerate((data.omega_rows, data.e_rows, data.loss_rows))]
        self._entry = _scalar_entry()

    # The compiled entry point does not pickle: ship the data, compile (or load) it on arrival.
    def __getstate__(self):
        state = self.__dict__.copy()
        del state["_entry"]
        return state

    def __setstate__(self, state):
        self.__dict__.update(state)
        self._entry = _scalar_entry()

    def __repr__(self):
        return (f"Curve(eps_y={self.eps_y!r}, nu={self.nu!r}, unloading={self.unloading!r}, "
                f"v_max={self.v_max!r}, cells={self.data.e_rows.shape[0]})")

    def _eval(self, what, v):
        a = as_float_array(v, "v1_star")
        flat = np.ascontiguousarray(a).ravel()
        out = np.empty(flat.size)
        _curve_array(self.data, what, flat, out)
        if np.isnan(out).any():
            self._raise(flat[np.isnan(out)])
        out = out.reshape(a.shape)
        return float(out) if out.ndim == 0 else out

    def _raise(self, bad):
        check_velocity(bad, "v1_star")
        raise ValueError(f"v1_star = {float(bad[0])!r} is beyond this curve's v_max = {self.v_max!r} "
                         "(build the curve with a larger v_max)")

    def omega_m(self, v1_star):
        """Normalised maximum interference w_m* at V1* (-), JGM eq (29)."""
        v = v1_star if type(v1_star) is float else _fast_scalar(v1_star)
        if v is not None:  # fast scalar path (floats and NumPy real scalars)
            r = self._entry(self._packed[0], v)
            if r == r:
                return r
        return self._eval(0, v1_star)

    def e(self, v1_star):
        """Coefficient of restitution at V1* (-), JGM eqs (16), (38)."""
        v = v1_star if type(v1_star) is float else _fast_scalar(v1_star)
        if v is not None:  # fast scalar path (floats and NumPy real scalars)
            r = self._entry(self._packed[1], v)
            if r == r:
                return r
        return self._eval(1, v1_star)

    def loss(self, v1_star):
        """Dissipated fraction 1 - e^2 at V1* (-), accurate in relative terms as V1* -> 1."""
        v = v1_star if type(v1_star) is float else _fast_scalar(v1_star)
        if v is not None:  # fast scalar path (floats and NumPy real scalars)
            r = self._entry(self._packed[2], v)
            if r == r:
                return r
        return self._eval(2, v1_star)


class _ExtrapolatedCurve(Curve):
    """A :class:`Curve` built with ``extrapolate=True`` past w_m* = 425: every evaluation past
    ``v_limit`` warns (a subclass, so curves that do not extrapolate pay nothing for the check)."""

    def _check(self, v1_star):
        past = (v1_star > self.v_limit if type(v1_star) is float
                else np.any(np.asarray(v1_star, dtype=np.float64) > self.v_limit))
        if past:
            warn(f"V1* past {self.v_limit:.6g} (w_m* = {OMEGA_M_STAR_MAX:g}): extrapolated, the JG law "
                 "is not validated there", ExtrapolationWarning)

    def omega_m(self, v1_star):
        out = Curve.omega_m(self, v1_star)
        self._check(v1_star)
        return out

    def e(self, v1_star):
        out = Curve.e(self, v1_star)
        self._check(v1_star)
        return out

    def loss(self, v1_star):
        out = Curve.loss(self, v1_star)
        self._check(v1_star)
        return out


def curve(eps_y, nu, unloading="jcg", v_max=None, extrapolate=False):
    """Build a :class:`Curve`: the model for one material, fast, up to the speed a scene needs.

    Parameters
    ----------
    eps_y : float
        Sy/E' (-), > 0; validated range 0.0005-0.01 (outside: ValidityWarning).
    nu : float
        Poisson's ratio of the yielding material, 0 <= nu < 0.5 (validated 0.2-0.45).
    unloading : {"jcg", "etsion", "brake"}
        Residual-interference model, JGM eq (35), (33) or Brake's (:mod:`fastrest.unloading`).
    v_max : float, optional
        Largest V1* = V1/V_c needed (-). Default: the model's limit, w_m* = 425. A larger value
        raises ValueError naming the limit.
    extrapolate : bool
        Allow w_m* > 425 up to a/R = 1 (ExtrapolationWarning).

    Returns
    -------
    Curve
        ``.e(v)``, ``.omega_m(v)``, ``.loss(v)`` at V1* in [0, v_max] (broadcast; ValueError past
        v_max), ``.v_max``, and ``.data`` for :mod:`fastrest.jit`. Accuracy against the direct
        solver: ~1e-13 relative for e and w_m*, ~2e-12 for 1 - e^2 (README, bench/).

    Raises
    ------
    TypeError
        eps_y, nu or v_max is not a real number.
    ValueError
        eps_y <= 0, nu outside [0, 0.5), unknown ``unloading``, or v_max past the model's limit
        (w_m* = 425, or a/R = 1 with ``extrapolate``); the message names the parameter and limit.

    Warns
    -----
    ValidityWarning
        eps_y or nu outside the validated range (0.0005-0.01, 0.2-0.45).

    Examples
    --------
    >>> c = fastrest.curve(0.005, 0.33, v_max=200.0)       # doctest: +SKIP
    >>> c.e([2.0, 20.0, 200.0])                              # doctest: +SKIP
    """
    eps_y = real_scalar(eps_y, "eps_y")
    nu = real_scalar(nu, "nu")
    extrapolate = check_bool(extrapolate, "extrapolate")
    check_eps_y(eps_y)
    check_nu(nu)
    if v_max is not None:
        v_max = float(check_velocity(real_scalar(v_max, "v_max"), "v_max"))
    warn_if_outside_validated(eps_y, nu)
    data = build_curve_data(eps_y, nu, unloading, v_max, extrapolate)
    c = (_ExtrapolatedCurve if v1_star_limit(eps_y, nu) < data.v_max else Curve)(eps_y, nu, unloading, data)
    if c.v_limit < data.v_max:
        warn(f"curve extends past w_m* = {OMEGA_M_STAR_MAX:g} (V1* = {c.v_limit:.6g}) to "
             f"V1* = {data.v_max:.6g}: extrapolated there; evaluations past it warn too", ExtrapolationWarning)
    return c


# --- scenes: several materials, one batch call ------------------------------------------------

SceneData = namedtuple("SceneData", ["model", "v_max", "shift", "base", "offset", "omega_rows",
                                     "e_rows", "loss_rows"])
SceneData.__doc__ = """Numba-friendly data of a :class:`Scene`: the curves of several materials.

The *_rows arrays hold the Hertz-range rows (shared) and then each material's JG rows; per
material k: v_max[k], base[k] and offset[k], the number of JG rows of materials before k; model and
shift are shared. See :func:`fastrest.jit.e_scene`.
"""


def material_index(k):
    """Material index ``k`` as an int64 in Numba code: any integer type, or an integer-valued
    float (as the Python API accepts); -1 (outside every scene: NaN) for anything else."""
    raise TypeError("material_index is for Numba code")


@overload(material_index, inline="always")
def _material_index_impl(k):
    if isinstance(k, nb.types.Boolean):
        return lambda k: np.int64(-1)
    if isinstance(k, nb.types.Integer):
        if k.signed:
            return lambda k: np.int64(k)
        return lambda k: np.int64(k) if k < np.uint64(2**62) else np.int64(-1)
    if isinstance(k, nb.types.Float):
        return lambda k: np.int64(k) if (k >= 0.0 and k < 2.0**62 and k == math.floor(k)) else np.int64(-1)
    return None


@nb.njit(cache=True, inline="always")
def scene_value(data, what, k_in, v_in):
    """Quantity ``what`` (0 w_m*, 1 e, 2 1 - e^2) of material k at V1*; NaN outside its curve."""
    # the index check by selects, not an early return: with the branch the caller's loop was
    # 10x slower (measured 24 ns against 2.5 ns per point in a user's @njit loop)
    k = material_index(k_in)
    v = np.float64(v_in)  # float32 and integer speeds, as the Python API takes them
    ok = k >= 0 and k < data.v_max.size
    kk = k if ok else np.int64(0)
    rows = data.omega_rows if what == 0 else (data.e_rows if what == 1 else data.loss_rows)
    # material k's JG rows come after those of materials 0..k-1: shift its base key accordingly
    r = curve_value(rows, data.v_max[kk], data.shift, data.base[kk] - data.offset[kk], what, v)
    return r if ok else np.nan


@nb.njit(cache=True)
def _scene_array(data, what, k, v, out):
    for i in range(v.size):
        out[i] = scene_value(data, what, k[i], v[i])


def _material_indices(material, n):
    """Material indices as int64: integers, or integer-valued floats; TypeError for booleans and
    non-numbers, ValueError for fractions."""
    if isinstance(material, (bool, np.bool_)) or (isinstance(material, np.ndarray) and material.dtype == bool):
        raise TypeError(f"material must be integer indices into the scene's {n} materials, got booleans")
    k = np.asarray(material) if isinstance(material, np.ndarray) and material.dtype.kind in "iu" \
        else as_float_array(material, "material")
    if k.dtype.kind == "f":
        if not np.all(np.isfinite(k) & (k == np.floor(k))):
            raise ValueError(f"material must be integer indices into the scene's {n} materials; got {material!r}")
        k = k.astype(np.int64)
    return k


class Scene:
    """The curves of several materials (a scene), evaluated per point by material index.

    Build with :func:`scene`. ``e(v1_star, material)`` evaluates point i with the curve of
    material ``material[i]`` (integer index into the list given to :func:`scene`); both arguments
    broadcast. ``data`` (:class:`SceneData`) is for :func:`fastrest.jit.e_scene` in Numba code.
    """

    def __init__(self, curves):
        self.curves = list(curves)
        if not self.curves:
            raise ValueError("a scene needs at least one material")
        models = {c.data.model for c in self.curves}
        if len(models) != 1:
            raise ValueError("all curves of a scene must use the same unloading model")
        shifts = {c.data.shift for c in self.curves}
        if len(shifts) != 1:
            raise ValueError("all curves of a scene must use the same cells per octave")
        # the Hertz rows (the same for every material) once, then each material's JG rows
        sizes = [c.data.e_rows.shape[0] - N_HERTZ for c in self.curves]
        offset = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(np.int64)
        first = self.curves[0].data
        cat = [np.ascontiguousarray(np.concatenate([getattr(first, f)[:N_HERTZ]]
                                                   + [getattr(c.data, f)[N_HERTZ:] for c in self.curves]))
               for f in ("omega_rows", "e_rows", "loss_rows")]
        self._v_limit = np.array([c.v_limit if c.v_limit < c.v_max else math.inf for c in self.curves])
        self._extrapolated = bool(np.isfinite(self._v_limit).any())
        self.data = SceneData(models.pop(), np.array([c.v_max for c in self.curves]), shifts.pop(),
                              np.array([c.data.base for c in self.curves], dtype=np.int64), offset, *cat)

    def __len__(self):
        return len(self.curves)

    def __repr__(self):
        return f"Scene({len(self.curves)} materials, unloading={self.curves[0].unloading!r})"

    def _eval(self, what, v1_star, material):
        v = as_float_array(v1_star, "v1_star")
        k = _material_indices(material, len(self))
        broadcast_named((v, "v1_star"), (k, "material"))
        v, k = np.broadcast_arrays(v, k)
        shape = v.shape
        vf = np.ascontiguousarray(v).ravel()
        kf = np.ascontiguousarray(k, dtype=np.int64).ravel()
        out = np.empty(vf.size)
        _scene_array(self.data, what, kf, vf, out)
        bad = np.isnan(out)
        if bad.any():
            kb = kf[bad]
            if ((kb < 0) | (kb >= len(self))).any():
                raise ValueError(f"material index out of range [0, {len(self) - 1}]: {int(kb[0])}")
            check_velocity(vf[bad], "v1_star")
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"v1_star = {float(vf[i])!r} is beyond v_max = {float(self.data.v_max[kf[i]])!r} "
                             f"of material {int(kf[i])} (build the scene with a larger v_max)")
        if self._extrapolated and np.any(vf > self._v_limit[kf]):
            warn(f"V1* past w_m* = {OMEGA_M_STAR_MAX:g} for an extrapolated material of the scene: "
                 "the JG law is not validated there", ExtrapolationWarning)
        out = out.reshape(shape)
        return float(out) if out.ndim == 0 else out

    def omega_m(self, v1_star, material):
        """w_m* (-) at V1* for each point's material index."""
        return self._eval(0, v1_star, material)

    def e(self, v1_star, material):
        """Coefficient of restitution (-) at V1* for each point's material index."""
        return self._eval(1, v1_star, material)

    def loss(self, v1_star, material):
        """1 - e^2 (-) at V1* for each point's material index."""
        return self._eval(2, v1_star, material)


def scene(materials, unloading="jcg", v_max=None, extrapolate=False):
    """Build a :class:`Scene` from (eps_y, nu) pairs: one curve per material, only as far as needed.

    Parameters
    ----------
    materials : sequence of (eps_y, nu)
        Material parameters (-) of each material index 0, 1, ...
    unloading : {"jcg", "etsion", "brake"}
    v_max : float or sequence, optional
        Largest V1* needed, for all materials or per material (default: each material's w_m* = 425).
    """
    materials = list(materials)
    for k, m in enumerate(materials):
        if np.ndim(m) != 1 or len(m) != 2:
            raise ValueError(f"materials[{k}] must be an (eps_y, nu) pair; got {m!r}")
    if v_max is None:
        vm = [None] * len(materials)
    else:
        v = as_float_array(v_max, "v_max")
        if not (v.ndim == 0 or v.shape == (len(materials),)):
            raise ValueError(f"v_max must be one number or one per material ({len(materials)}); got shape {v.shape}")
        vm = np.broadcast_to(v, (len(materials),)).tolist()
    return Scene([curve(e, n, unloading, v, extrapolate) for (e, n), v in zip(materials, vm)])
