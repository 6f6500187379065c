"""Scenes: the curves of several materials, evaluated per point by material index.

:func:`scene` builds one :class:`~fastrest.curve.Curve` per (eps_y, nu[, et_ratio]), each only as far as its
``v_max``, and concatenates their cells into one :class:`SceneData`: the Hertz-range rows once
(they are the same for every material, :mod:`fastrest.cells`), then each material's JG rows. A
point with material index k is evaluated by :func:`scene_value`, the curves' own rule
(:func:`fastrest.curve_data.curve_value`) on material k's rows, so a scene gives bit for bit what
material k's curve gives. In Numba code: :func:`fastrest.jit.e_material`.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any
from numpy.typing import ArrayLike, NDArray
import math
from collections import namedtuple
from collections.abc import Iterable

import numba as nb
import numpy as np
from numba.extending import overload

from ._deprecation import alias
from ._doc import doc, paragraphs
from ._jit import jit
from ._validation import (OMEGA_M_STAR_MAX, ExtrapolationWarning, as_float_array, broadcast_named, check_velocity,
                          kernel_array, warn)
from ._validation import short_repr as _short
from .cells import N_HERTZ
from .curve import Curve, _curve
from .curve_data import curve_value
from .fastpath import scene_quantity
from .unloading import get as unloading_model, warn_if_unfitted

__all__ = ["SceneData", "material_index", "scene_value", "scene_array", "Scene", "scene"]

# The first parameters of the scene kernels, written once (fastrest._doc).
_DOC = paragraphs(params_data="""
    Parameters
    ----------
    data : SceneData
        The scene's data, ``Scene.data``.
    what : int
        0 w_m*, 1 e, 2 1 - e^2.
    """)

SceneData = namedtuple("SceneData", ["model", "v_max", "shift", "base", "offset", "omega_rows",
                                     "e_rows", "loss_rows"])
SceneData.__doc__ = """Numba-friendly data of a :class:`Scene`: the curves of several materials (a namedtuple).

Attributes
----------
model, shift : int
    Unloading model code of every material (0 JCG, 1 Etsion, 2 Brake); index shift of the JG cells.
v_max : ndarray
    Largest V1* (-) of each material, float64.
base, offset : ndarray
    int64 per material: its JG cells' base key; the number of JG rows of the materials before it.
omega_rows, e_rows, loss_rows : ndarray
    (nrow, 8) float64: the Hertz-range rows (shared), then each material's JG rows.

Notes
-----
Evaluated by :func:`scene_value` (JGM eqs 29, 38); in your own Numba code
:func:`fastrest.jit.e_material`.

Examples
--------
>>> import fastrest
>>> d = fastrest.scene([(0.005, 0.33), (0.002, 0.3)], v_max=20.0).data
>>> d.v_max.tolist(), int(d.offset[0])
([20.0, 20.0], 0)
"""


def material_index(k: Any) -> int:
    """Material index ``k`` as an int64 in Numba code (a Numba overload: jit code only).

    Parameters
    ----------
    k : int or float
        Any integer type, or an integer-valued float (as the Python API accepts).

    Returns
    -------
    int64
        ``k``; -1 (outside every scene, so the evaluation gives NaN) for booleans, fractions,
        negative or non-finite floats and unsigned values >= 2^62.

    Raises
    ------
    TypeError
        When called from Python: it is for Numba code.

    Notes
    -----
    A Numba overload (inlined): the index check of :func:`scene_value` costs a few selects.

    Examples
    --------
    >>> from fastrest.scene import material_index
    >>> material_index(2)
    Traceback (most recent call last):
    ...
    TypeError: material_index is for Numba code
    """
    raise TypeError("material_index is for Numba code")


# inline="never" (the default): an IR-inlined ``numba.extending.overload`` does not compile for
# CUDA (numba-cuda 0.30 mixes its IR classes with Numba's); LLVM still inlines the call on both
# targets (`python -m bench.stencil` unchanged).
@overload(material_index)
def _material_index_impl(k):
    if isinstance(k, nb.types.Boolean):
        return lambda k: np.int64(-1)
    if isinstance(k, nb.types.Integer):
        if k.signed:  # type: ignore[attr-defined]  # Numba's Integer types have it, its stubs do not
            return lambda k: np.int64(k)
        return lambda k: np.int64(k) if k < np.uint64(2**62) else np.int64(-1)
    if isinstance(k, nb.types.Float):
        return lambda k: np.int64(k) if (k >= 0.0 and k < 2.0**62 and k == math.floor(k)) else np.int64(-1)
    return None


@jit(inline=True)
@doc(_DOC)
def scene_value(data, what, k_in, v_in):
    """Quantity ``what`` of material k at V1* from a scene's data, in Numba code.

    {params_data}
    k_in : int or float
        Material index (:func:`material_index`).
    v_in : float
        V1* = V1/V_c (-), JGM eq (30).

    Returns
    -------
    float
        The quantity (-); NaN for an index outside the scene, or V1* < 0, NaN, or past material
        k's v_max (no exception).

    Notes
    -----
    :func:`fastrest.curve_data.curve_value` on material k's rows: JGM eqs (29), (16), (38).

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.scene import scene_value
    >>> s = fastrest.scene([(0.005, 0.33), (0.002, 0.3)], v_max=20.0)
    >>> scene_value(s.data, 1, 1, 0.5), scene_value(s.data, 1, 2, 0.5)
    (1.0, nan)
    """
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


@jit
@doc(_DOC)
def scene_array(data, what, k, v, out):
    """out[i] = quantity ``what`` of material k[i] at V1* = v[i] (0 w_m*, 1 e, 2 1 - e^2).

    {params_data}
    k, v : ndarray
        1-D int64 material indices and float64 V1* (-), of one length.
    out : ndarray
        1-D float64 (-), the length of ``v``; written in place.

    Notes
    -----
    NaN where :func:`scene_value` gives NaN; :class:`Scene` raises for them.

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> from fastrest.scene import scene_array
    >>> s = fastrest.scene([(0.005, 0.33), (0.002, 0.3)], v_max=20.0)
    >>> out = np.empty(2); scene_array(s.data, 1, np.array([0, 1]), np.array([0.5, 0.5]), out); out.tolist()
    [1.0, 1.0]
    """
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


_METHOD_DOC = """{summary} for each point's material.

Parameters
----------
v1_star : float or array_like
    Impact speed V1* = V1/V_c (-), V_c of JGM eq (28); 0 <= V1* <= the material's ``v_max``.
material : int or array_like of int
    Index into the materials given to :func:`scene` (integer-valued floats accepted); broadcast
    with ``v1_star``.

Returns
-------
float or ndarray
    {returns} (-), the broadcast shape; a float for scalars.

Raises
------
TypeError
    ``v1_star`` or ``material`` is not real, or ``material`` is boolean.
ValueError
    A fractional or out-of-range material index; V1* < 0, NaN or past that material's v_max; shapes
    that do not broadcast (each message names the parameter).

Warns
-----
ExtrapolationWarning
    V1* past w_m* = 425 for a material built with ``extrapolate=True``.

Notes
-----
{notes}

Examples
--------
>>> import fastrest
>>> s = fastrest.scene([(0.005, 0.33), (0.002, 0.3)], v_max=20.0)
>>> s.{name}([0.5, 0.5], [0, 1]).tolist()
{example}
"""

_QUANTITIES = (
    ("omega_m", "Normalised maximum interference w_m*", "w_m*", "JGM eq (29).", "[0.5743491774985174, 0.5743491774985174]"),
    ("e", "Coefficient of restitution e", "e", "JGM eqs (16), (38).", "[1.0, 1.0]"),
    ("loss", "Dissipated fraction 1 - e^2", "1 - e^2", "JGM eq (38), relative accuracy kept as V1* -> 1.",
     "[0.0, 0.0]"),
)


def _quantity_method(what: int) -> Callable[..., float | NDArray[np.float64]]:
    name, summary, returns, notes, example = _QUANTITIES[what]

    def method(self: Scene, v1_star: ArrayLike, material: ArrayLike) -> float | NDArray[np.float64]:
        return self._eval(what, v1_star, material)

    method.__name__ = name
    method.__qualname__ = f"Scene.{name}"
    method.__doc__ = _METHOD_DOC.format(summary=summary, returns=returns, notes=notes, name=name, example=example)
    return method


class Scene:
    """The curves of several materials (a scene), evaluated per point by material index.

    Build with :func:`scene`. ``e(v1_star, material)`` evaluates point i with the curve of
    material ``material[i]`` (integer index into the list given to :func:`scene`); both arguments
    broadcast. Scenes pickle.

    Parameters
    ----------
    curves : sequence of Curve
        One curve per material, all with the same unloading model and cells per octave (their
        loading laws and et_ratio may differ).

    Attributes
    ----------
    curves : list of Curve
        The materials' curves.
    data : SceneData
        For :func:`fastrest.jit.e_material` in Numba code.

    Raises
    ------
    ValueError
        No curves, or curves with different unloading models or cells per octave.

    Notes
    -----
    Each material evaluates JGM eqs (29), (16), (38) from its curve's cells, bit for bit as its
    :class:`~fastrest.curve.Curve` does.

    Examples
    --------
    >>> import fastrest
    >>> s = fastrest.Scene([fastrest.curve(0.005, 0.33, v_max=20.0), fastrest.curve(0.002, 0.3, v_max=20.0)])
    >>> len(s), s.e(1.0, 1)
    (2, 1.0)
    """

    def __init__(self, curves: Sequence[Curve]) -> None:
        self.curves = _sequence(curves, "curves", "a sequence of fastrest.Curve")
        if not self.curves:
            raise ValueError("curves is empty: a scene needs at least one material")
        for k, c in enumerate(self.curves):
            if not isinstance(c, Curve):
                raise TypeError(f"curves[{k}] must be a fastrest.Curve, got {_short(c)} ({type(c).__name__})")
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

    def __len__(self) -> int:
        return len(self.curves)

    def __repr__(self) -> str:
        return f"Scene({len(self.curves)} materials, unloading={self.curves[0].unloading!r})"

    def _eval(self, what, v1_star, material):
        v = as_float_array(v1_star, "v1_star")
        k = _material_indices(material, len(self))
        broadcast_named((v, "v1_star"), (k, "material"))
        v, k = np.broadcast_arrays(v, k)
        shape = v.shape
        vf = kernel_array(v)
        kf = kernel_array(k, np.int64)
        out: NDArray[np.float64] = np.empty(vf.size)
        scene_array(self.data, what, kf, vf, out)
        bad = np.isnan(out)
        if bad.any():
            kb = kf[bad]
            if ((kb < 0) | (kb >= len(self))).any():
                raise ValueError(f"material index out of range [0, {len(self) - 1}]: {int(kb[0])}")
            check_velocity(vf[bad], "v1_star")
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"v1_star = {float(vf[i])!r} is beyond v_max = {float(self.data.v_max[kf[i]])!r} "
                             f"of material {int(kf[i])}: "
                             + self.curves[int(kf[i])]._end_note().replace("the curve", "the scene"))
        if self._extrapolated and np.any(vf > self._v_limit[kf]):
            warn(f"V1* past w_m* = {OMEGA_M_STAR_MAX:g} for an extrapolated material of the scene: "
                 "the JG law is not validated there", ExtrapolationWarning)
        out = out.reshape(shape)
        return float(out) if out.ndim == 0 else out

    # a float in gives a float out, a sequence an array (fastrest.fastpath.SceneQuantity)
    omega_m = scene_quantity(_quantity_method(0))
    e = scene_quantity(_quantity_method(1))
    loss = scene_quantity(_quantity_method(2))


def scene(materials: Sequence[tuple[float, ...]], unloading: str = "jcg", *, v_max: float | None = None,
          extrapolate: bool = False, loading: str | None = None) -> Scene:
    """Build a :class:`Scene` from (eps_y, nu) pairs: one curve per material, only as far as needed.

    Parameters
    ----------
    materials : sequence of (eps_y, nu) or (eps_y, nu, et_ratio)
        Material parameters (-) of each material index 0, 1, ...: Sy/E' > 0 and Poisson's ratio
        0 <= nu < 0.5 (validated ranges 0.0005-0.01 and 0.2-0.45), and optionally the tangent
        modulus ratio Et/E, 0 <= et_ratio < 1 (strain hardening, :func:`fastrest.curve`; default 0).
        Pairs and triples may be mixed.
    unloading : {"jcg", "etsion", "brake"}
        Unloading model of every material, JGM eq (35), (33) or Brake's (:mod:`fastrest.unloading`).
    v_max : float or sequence of float, optional
        Largest V1* needed (-), for all materials or one per material, keyword-only (default: each
        material's w_m* = 425).
    extrapolate : bool
        Allow w_m* > 425 up to a/R = 1 (ExtrapolationWarning), keyword-only.
    loading : {None, "jackson-green", "ghaednia"}
        Loading law of every material (:mod:`fastrest.loading`), keyword-only; None: each
        material's default for its et_ratio (Jackson-Green at 0, Ghaednia et al. 2019 above).

    Returns
    -------
    Scene
        ``.e(v, k)``, ``.omega_m(v, k)``, ``.loss(v, k)``, and ``.data`` for :mod:`fastrest.jit`.

    Raises
    ------
    TypeError
        A material parameter or v_max is not a real number.
    ValueError
        A material that is not an (eps_y, nu) pair or (eps_y, nu, et_ratio) triple, v_max of the
        wrong length, or anything :func:`fastrest.curve` refuses (the message names the parameter).

    Warns
    -----
    ValidityWarning
        A material outside the validated range; JCG or Etsion unloading with a hardening material
        (once per scene).
    ExtrapolationWarning
        With ``extrapolate=True``, a material whose curve extends past w_m* = 425.

    Notes
    -----
    One :func:`fastrest.curve` per material (JGM eqs 29, 38 with 33 or 35).

    Examples
    --------
    >>> import fastrest
    >>> s = fastrest.scene([(0.005, 0.33), (0.002, 0.3)], v_max=[300.0, 200.0])
    >>> s.e([20.0, 20.0], [0, 1]).round(4).tolist()
    [0.7463, 0.7472]

    The second material hardening (Et/E = 0.01), with Brake unloading:

    >>> s = fastrest.scene([(0.005, 0.33), (0.005, 0.33, 0.01)], "brake", v_max=100.0)
    >>> s.e([20.0, 20.0], [0, 1]).round(4).tolist()
    [0.8598, 0.8649]
    """
    what = "an (eps_y, nu) pair or (eps_y, nu, et_ratio) triple"
    materials = _sequence(materials, "materials", "a sequence of (eps_y, nu) pairs or (eps_y, nu, et_ratio) triples")
    if not materials:
        raise ValueError("materials is empty: a scene needs at least one material")
    for k, m in enumerate(materials):
        if isinstance(m, (str, bytes, bytearray, dict)) or not isinstance(m, Iterable):
            raise TypeError(f"materials[{k}] must be {what}, got {_short(m)} ({type(m).__name__})")
        if np.ndim(m) != 1 or len(m) not in (2, 3):
            raise ValueError(f"materials[{k}] must be {what}; got {_short(m)}")
    model = unloading_model(unloading)
    if v_max is None:
        vm: list[Any] = [None] * len(materials)
    else:
        v = as_float_array(v_max, "v_max")
        if not (v.ndim == 0 or v.shape == (len(materials),)):
            raise ValueError(f"v_max must be one number or one per material ({len(materials)}); got shape {v.shape}")
        vm = np.broadcast_to(v, (len(materials),)).tolist()
    curves = []
    for k, (m, v) in enumerate(zip(materials, vm)):
        e, n, h = tuple(m) + ((0.0,) if len(m) == 2 else ())
        try:
            curves.append(_curve(e, n, unloading, v, extrapolate, h, loading, False))
        except (TypeError, ValueError) as exc:  # name the scene's parameter, then curve's words
            raise type(exc)(f"materials[{k}] = {_short(tuple(materials[k]))}: {exc}") from None
    warn_if_unfitted(model, [c.et_ratio for c in curves])  # once for the scene
    return Scene(curves)


def _sequence(x, name, what):
    """``list(x)`` for a sequence (a list, tuple, array or generator); TypeError naming ``name``
    for a number, string, mapping or anything else."""
    if isinstance(x, (str, bytes, bytearray, dict)) or not isinstance(x, Iterable) or isinstance(x, np.ma.MaskedArray):
        raise TypeError(f"{name} must be {what}, got {_short(x)} ({type(x).__name__})")
    return list(x)


# fastrest.curve held the scene's names before this module (deprecated there; registered here,
# where they are defined, so that fastrest.curve never imports this module)
for _name, _new in [("Scene", "fastrest.Scene"), ("scene", "fastrest.scene"), ("SceneData", "fastrest.jit.SceneData"),
                    ("scene_value", "`from fastrest.scene import scene_value`"),
                    ("material_index", "`from fastrest.scene import material_index`")]:
    alias("fastrest.curve", _name, _new, (lambda n: lambda: globals()[n])(_name))
del _name, _new
