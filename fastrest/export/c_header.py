"""A self-contained C99 header with a scene's cells: ``fastrest export c``.

The header holds, for each material k of ``--materials``, the rows [center, 1/half_width, c0..c5]
of :mod:`fastrest.curve` (w_m*, and e and 1 - e^2 of every unloading model) as static arrays of
float literals (the shortest decimal that rounds back to each double, at most 17 digits: exact
under IEEE 754 rounding, in C99 and C++ of any standard), and inline evaluators that follow
:func:`fastrest.curve.curve_value` operation by operation: the cell from the float's bits, u =
(v - center) * (1/half_width), Estrin's scheme with ``fma``. The only floating-point operations
outside ``fma`` are that subtraction and product, u*u, (u*u)*(u*u), (V1* - 1) * r and pow(V1*, 0.8):
none can be contracted into an fma by a compiler, so the C results equal the Python path's
bit for bit (tests/test_export_c.py compares 1e5+ points, cell boundaries included).

A material may harden: ``EPS_Y:NU:ET_RATIO`` (or a triple (eps_y, nu, et_ratio), or a pair with
``Et``) tabulates the Ghaednia et al. (2019) loading law with Et/E = et_ratio (:func:`fastrest.curve`);
the header's opening comment then records each material's et_ratio and loading law. A header of
materials without hardening is unchanged, byte for byte.

Built from material pairs in SI units (:func:`impact_materials`: the options and ``--pairs`` file of
``fastrest export velocity``), the header also holds each pair's critical values (V_c, omega_c,
P_c, A_c, U_c, E', R', mass) and ``fastrest_v1_star(k, V)``, V (m/s) -> V1* = V/V_c.

The same text compiles unedited as CUDA (nvcc, and NVRTC at run time): under ``__CUDACC__`` every
function is ``__host__ __device__`` (``FASTREST_FN``) and every table has a ``__device__`` copy
``NAME_device`` beside the host's ``NAME`` (``FASTREST_TABLE``; ``FASTREST_ARRAY(NAME)`` picks the
copy of the code being compiled); under NVRTC (``__CUDACC_RTC__``) no system header is included.
Global rather than ``__constant__`` memory: one material's rows take ~160 kB, the constant bank 64 kB.
"""
from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any
if TYPE_CHECKING:
    from ..impact import Impact
import math
import os
import textwrap

import numpy as np

from .._validation import ValidityWarning, real_scalar, warn
from ..cells import HERTZ_BASE, HERTZ_SHIFT, N_HERTZ
from ..curve import _curve
from ..curve_data import build_curve_data
from ..energy import V_SWITCH
from ..impact import Impact
from ..interpolation import ROW
from ..limits import limit
from ..loading import resolve as resolve_loading
from .. import unloading as _unloading
from ._io import check_target, provenance, write_files

__all__ = ["MAX_MATERIALS", "CRITICAL_KEYS", "parse_materials", "impact_materials", "scene_curves", "header_text",
           "write_header"]

#: Most materials in one header (each adds ~370 kB of text, ~160 kB of tables, and a curve build).
MAX_MATERIALS = 256
#: Critical values of a pair written into a header built from physical properties (SI units), as
#: ``fastrest_<key>[k]``: keys of :meth:`fastrest.Impact.critical_values`.
CRITICAL_KEYS = {"V_c": "m/s", "omega_c": "m", "P_c": "N", "A_c": "m^2", "U_c": "J", "E_eff": "Pa",
                 "R_eff": "m", "mass": "kg", "Sy": "Pa", "C": "-"}


def parse_materials(items: Sequence[str], option: str = "materials") -> list[tuple[float, ...]]:
    """[(eps_y, nu), ...] from ``EPS_Y:NU`` strings, (eps_y, nu, et_ratio) from ``EPS_Y:NU:ET_RATIO``
    (Et/E, strain hardening); ValueError naming ``option`` otherwise."""
    if isinstance(items, (str, bytes)) or not hasattr(items, "__len__"):
        raise TypeError(f"{option} must be a list of 'EPS_Y:NU' strings, got {type(items).__name__}")
    if len(items) > MAX_MATERIALS:
        raise ValueError(f"{option}: at most {MAX_MATERIALS} materials in one header; got {len(items)}")
    out: list[tuple[float, ...]] = []
    for s in items:
        parts = str(s).split(":")
        try:
            if len(parts) not in (2, 3):
                raise ValueError
            m = tuple(float(x) for x in parts)
        except ValueError:
            raise ValueError(f"{option}: expected EPS_Y:NU or EPS_Y:NU:ET_RATIO (e.g. 0.005:0.33, "
                             f"0.005:0.33:0.01); got {s!r}") from None
        out.append(m)
    if not out:
        raise ValueError(f"{option}: give at least one EPS_Y:NU material")
    return out


def _check_materials(materials):
    if isinstance(materials, (str, bytes)) or not hasattr(materials, "__len__"):
        raise TypeError(f"materials must be a list of (eps_y, nu) pairs, got {type(materials).__name__}")
    if not 1 <= len(materials) <= MAX_MATERIALS:
        raise ValueError(f"materials must hold 1 to {MAX_MATERIALS} (eps_y, nu) pairs; got {len(materials)}")
    for k, m in enumerate(materials):
        if isinstance(m, (str, bytes)) or not hasattr(m, "__len__") or len(m) not in (2, 3):
            raise TypeError(f"materials[{k}] must be an (eps_y, nu) pair or (eps_y, nu, et_ratio) triple, got {m!r}")


def _triple(m):
    """(eps_y, nu, et_ratio) of a material given as a pair or a triple."""
    return tuple(m) if len(m) == 3 else (m[0], m[1], 0.0)


def scene_curves(materials: Sequence[tuple[float, ...]], v_max: float | None = None,
                 option: str = "v_max") -> list[Any]:
    """Curve data per (material, unloading model): list over materials of lists over model codes.

    Each material's curve reaches ``v_max`` (a V1*; or a list of one V1* or None per material), by
    default its own w_m* = 425 speed; ``materials`` holds 1 to :data:`MAX_MATERIALS` (eps_y, nu)
    pairs or (eps_y, nu, et_ratio) triples (strain hardening, Et/E; one ValidityWarning for the
    header where one hardens: JCG and Etsion unloading were fitted without hardening).
    """
    _check_materials(materials)
    if isinstance(v_max, (list, tuple)):
        if len(v_max) != len(materials):
            raise ValueError(f"{option} holds {len(v_max)} values for {len(materials)} materials")
        tops = list(v_max)
    else:
        tops = [v_max] * len(materials)
    for i, top in enumerate(tops):
        if top is not None:
            tops[i] = top = real_scalar(top, option)
            if not (top > 0 and math.isfinite(top)):
                raise ValueError(f"{option} must be a finite V1* > 0; got {top!r}")
    out = []
    hard = []
    for k, (m, v_max) in enumerate(zip(materials, tops)):
        e, n, h = _triple(m)
        try:  # curve() would say it too, but after the limit below: check et_ratio first
            h = real_scalar(h, "et_ratio")
            law = resolve_loading(None, h)
        except (TypeError, ValueError) as exc:
            raise type(exc)(f"materials[{k}]: {exc}") from None
        hard.append(h)
        lim = limit(e, n, et_ratio=h, loading=law.name).v1_star
        if v_max is not None and v_max > lim:
            raise ValueError(f"{option} = {v_max!r} is past material {k}'s (eps_y = {e!r}, nu = {n!r}"
                             + (f", et_ratio = {h!r}" if h > 0 else "") + f") limit w_m* = 425 at V1* = {lim:.10g}")
        # curve() validates eps_y and nu (ValueError naming them) and warns outside the validated range
        # (the header warns of unloading fitted without hardening once, below, not per material)
        first = _curve(e, n, _unloading.NAMES[0], v_max, False, h, law.name, False)
        out.append([first.data] + [build_curve_data(e, n, name, v_max=first.v_max, et_ratio=h, loading=law.name)
                                   for name in _unloading.NAMES[1:]])
    if any(x > 0.0 for x in hard):
        unfitted = [m.short for m in _unloading.MODELS.values() if not m.fits_hardening]
        warn(f"a material hardens (et_ratio > 0): the header's {' and '.join(unfitted)} unloading use models "
             "fitted to elastic-perfectly plastic finite elements, an extrapolation", ValidityWarning)
    return out


def impact_materials(impacts: Sequence[Impact], V_max: float | Sequence[float] | None = None,
                     names: Sequence[str] | None = None) -> tuple[Any, ...]:
    """(materials, v_max, critical) of a header built from :class:`fastrest.Impact` objects.

    Parameters
    ----------
    impacts : list of Impact
        1 to :data:`MAX_MATERIALS` material pairs (effective sphere on a flat, SI units).
    V_max : float or list of (float or None), optional
        Largest impact speed (m/s) to tabulate, one for all or one per impact (None: that pair's
        w_m* = 425 speed, the default).
    names : list of str, optional
        The pairs' names, for error messages.

    Returns
    -------
    (list of (eps_y, nu) or (eps_y, nu, et_ratio), list of (float or None), list of dict)
        For :func:`write_header`: the normalised materials (a triple with the impact's Et/E,
        :attr:`fastrest.Impact.et_ratio`, where it hardens), their largest V1* (V_max / V_c) and
        each impact's :meth:`~fastrest.Impact.critical_values`.

    Raises
    ------
    ValueError
        A V_max not finite and > 0, or past the pair's w_m* = 425 speed (the message gives that
        speed in m/s); a list of the wrong length.
    """
    if isinstance(impacts, (str, bytes)) or not hasattr(impacts, "__len__"):
        raise TypeError(f"impacts must be a list of fastrest.Impact, got {type(impacts).__name__}")
    if not 1 <= len(impacts) <= MAX_MATERIALS:
        raise ValueError(f"a header holds 1 to {MAX_MATERIALS} material pairs; got {len(impacts)}")
    tops = list(V_max) if isinstance(V_max, (list, tuple)) else [V_max] * len(impacts)
    if len(tops) != len(impacts):
        raise ValueError(f"V_max holds {len(tops)} values for {len(impacts)} pairs")
    materials, v_max, critical = [], [], []
    for k, (imp, top) in enumerate(zip(impacts, tops)):
        if not isinstance(imp, Impact):
            raise TypeError(f"impacts[{k}] must be a fastrest.Impact, got {type(imp).__name__}")
        crit = imp.critical_values()
        lim = limit(imp.eps_y, imp.nu, et_ratio=imp.et_ratio, loading=imp.loading).v1_star
        if top is not None:
            top = real_scalar(top, "V_max")
            if not (top > 0 and math.isfinite(top)):
                raise ValueError(f"V_max must be a finite speed > 0 (m/s); got {top!r}")
            if top / crit["V_c"] > lim * (1 + 1e-12):
                who = f"pair {names[k]!r}" if names and names[k] else f"pair {k}"
                raise ValueError(f"V_max = {top!r} m/s is past {who}'s limit w_m* = 425 at "
                                 f"V = {lim * crit['V_c']:.10g} m/s (V_c = {crit['V_c']:.6g} m/s)")
            top = min(top / crit["V_c"], lim)
        materials.append((imp.eps_y, imp.nu) + ((imp.et_ratio,) if imp.et_ratio > 0.0 else ()))
        v_max.append(top)
        critical.append(crit)
    return materials, v_max, critical


def _lit(x):
    """A C literal of the double x: the shortest decimal that rounds back to x (at most 17
    significant digits, which IEEE 754 / C99 Annex F compilers convert correctly rounded, hence
    exactly). Not hexadecimal: C++ before C++17 has no hexadecimal floating literals."""
    x = float(x)
    if math.isnan(x):
        return "FASTREST_NAN"
    if math.isinf(x):
        return "FASTREST_INFINITY" if x > 0 else "-FASTREST_INFINITY"
    return repr(x)


def _table(ctype, name, dims, values):
    """One FASTREST_TABLE line: a static const array (and its device copy under CUDA)."""
    return f"FASTREST_TABLE({ctype}, {name}, {dims}, {{{values}}});"


def _rows_literal(rows, indent="    "):
    return ",\n".join(indent + "{" + ", ".join(_lit(x) for x in r) + "}" for r in rows)


_EVAL = r"""
/* Row layout: [center, 1/half_width, c0, c1, c2, c3, c4, c5]; value = sum c_i u^i,
   u = (v - center) * (1/half_width), by Estrin's scheme with fma (as fastrest.interpolation). */
static inline FASTREST_FN double fastrest__poly(const double *r, double v)
{
    double u = (v - r[0]) * r[1];
    double u2 = u * u;
    return fma(u2 * u2, fma(u, r[7], r[6]), fma(u2, fma(u, r[5], r[4]), fma(u, r[3], r[2])));
}

/* The bits of a double as a signed 64-bit integer. */
static inline FASTREST_FN FASTREST_INT64 fastrest__bits(double v)
{
#if defined(__CUDA_ARCH__)
    return __double_as_longlong(v);
#else
    FASTREST_INT64 b;
    memcpy(&b, &v, sizeof b);
    return b;
#endif
}

/* what: 0 w_m*, 1 e, 2 1 - e^2; rows: that quantity's rows (Hertz rows first, then every
   material's JG rows). The rule of fastrest.curve.curve_value. */
static inline FASTREST_FN double fastrest__value(const double (*rows)[8], int k, int what, double v)
{
    double v_max;
    if (k < 0 || k >= FASTREST_N_MATERIALS)
        return FASTREST_NAN;
    v_max = FASTREST_ARRAY(fastrest_v_max)[k];
    if (v > 1.0) {
        if (v <= v_max) {
            FASTREST_INT64 b = fastrest__bits(v);
            int hertz = v <= FASTREST_V_SWITCH;
            double r;
            r = fastrest__poly(rows[hertz ? (b >> FASTREST_HERTZ_SHIFT) - FASTREST_HERTZ_BASE
                                          : (b >> FASTREST_SHIFT) - FASTREST_ARRAY(fastrest_base)[k]], v);
            if (what == 2 && hertz)
                r *= v - 1.0;
            return r;
        }
        return FASTREST_NAN;
    }
    if (v >= 0.0 && v <= v_max) {
        if (what == 0)
            return pow(v, 0.8);
        return what == 1 ? 1.0 : 0.0;
    }
    return FASTREST_NAN;
}

/* Normalised maximum interference w_m* (JGM eq 29) of material k at V1* = V1/V_c.
   NaN for V1* < 0, NaN, V1* > fastrest_v_max[k] or an unknown k. */
static inline FASTREST_FN double fastrest_omega_m(int k, double v1_star)
{
    return fastrest__value(FASTREST_ARRAY(fastrest_omega_rows), k, 0, v1_star);
}

/* Coefficient of restitution e (JGM eq 38) of material k at V1*; unloading: FASTREST_JCG,
   FASTREST_ETSION, FASTREST_BRAKE. NaN outside the domain or for an unknown k or unloading. */
static inline FASTREST_FN double fastrest_e(int k, double v1_star, int unloading)
{
    if (unloading < 0 || unloading >= FASTREST_N_UNLOADING)
        return FASTREST_NAN;
    return fastrest__value(FASTREST_ARRAY(fastrest_e_rows)[unloading], k, 1, v1_star);
}

/* Dissipated fraction 1 - e^2 of material k at V1* (relative accuracy kept as V1* -> 1). */
static inline FASTREST_FN double fastrest_loss(int k, double v1_star, int unloading)
{
    if (unloading < 0 || unloading >= FASTREST_N_UNLOADING)
        return FASTREST_NAN;
    return fastrest__value(FASTREST_ARRAY(fastrest_loss_rows)[unloading], k, 2, v1_star);
}
"""


_V1_STAR = r"""
/* V1* = V / V_c (JGM eq 30) of material pair k for a normal impact speed V (m/s): the argument of
   fastrest_e, fastrest_omega_m and fastrest_loss. NaN for an unknown k. */
static inline FASTREST_FN double fastrest_v1_star(int k, double V)
{
    if (k < 0 || k >= FASTREST_N_MATERIALS)
        return FASTREST_NAN;
    return V / FASTREST_ARRAY(fastrest_V_c)[k];
}
"""

# Portability block: C99, C++ and CUDA (nvcc, NVRTC) from one text. Under CUDA each table is
# defined twice from the same initializer (the host's `name`, the device's `name_device`: a
# namespace-scope array that device code reads must be __device__, and host code cannot read a
# __device__ one), both in nvcc's host and device passes (a __device__ variable's declaration must
# not depend on __CUDA_ARCH__); FASTREST_ARRAY picks the copy inside function bodies. __constant__
# memory (64 kB) is too small: one material's rows take ~160 kB.
_PORTABLE = r"""/* C99, C++ or CUDA. Under CUDA (__CUDACC__: nvcc, NVRTC) the functions are __host__ __device__ and
   every table has a device copy, NAME_device (global memory: the rows of one material, ~160 kB,
   do not fit in the 64 kB of __constant__ memory); FASTREST_ARRAY(NAME) is the copy of the code
   being compiled, e.g. FASTREST_ARRAY(fastrest_V_c)[k] in host and device code alike. NVRTC
   (__CUDACC_RTC__) has no system headers: none is included, and there are no host copies.
   Define FASTREST_FN before including to qualify the functions otherwise (e.g. __device__). */
#if !defined(__CUDACC_RTC__)
#include <math.h>
#include <stdint.h>
#include <string.h>
#define FASTREST_INT64 int64_t
#define FASTREST_INT64_C(c) INT64_C(c)
#define FASTREST_NAN NAN
#define FASTREST_INFINITY INFINITY
#else
#define FASTREST_INT64 long long
#define FASTREST_INT64_C(c) c##LL
#define FASTREST_NAN (0.0 / 0.0)
#define FASTREST_INFINITY (1.0 / 0.0)
#endif
#ifndef FASTREST_FN
#if defined(__CUDACC__)
#define FASTREST_FN __host__ __device__
#else
#define FASTREST_FN
#endif
#endif
#if defined(__CUDACC_RTC__)
#define FASTREST_TABLE(type, name, dims, ...) static __device__ const type name##_device dims = __VA_ARGS__
#elif defined(__CUDACC__)
#define FASTREST_TABLE(type, name, dims, ...) static const type name dims = __VA_ARGS__; \
    static __device__ const type name##_device dims = __VA_ARGS__
#else
#define FASTREST_TABLE(type, name, dims, ...) static const type name dims = __VA_ARGS__
#endif
#if defined(__CUDA_ARCH__)
#define FASTREST_ARRAY(name) name##_device
#else
#define FASTREST_ARRAY(name) name
#endif
#if defined(__CUDACC__)
#pragma nv_diagnostic push
#pragma nv_diag_suppress 177 /* a table's unused device copy: "declared but never referenced" */
#endif
"""


def header_text(materials: Sequence[tuple[float, ...]], curves: Sequence[Any], name: str = "fastrest_scene.h",
                command: str | None = None, critical: Sequence[dict[str, float]] | None = None,
                names: Sequence[str] | None = None) -> str:
    """The header's text for ``materials`` and their :func:`scene_curves`.

    ``critical``: each material pair's :meth:`fastrest.Impact.critical_values` (a header built from
    physical properties; adds :data:`CRITICAL_KEYS` arrays and ``fastrest_v1_star``); ``names``:
    each material's name, for the comments. A material given as (eps_y, nu, et_ratio) with
    et_ratio > 0 has its et_ratio and loading law in the opening comment.
    """
    materials = [_triple(m) for m in materials]
    laws = [resolve_loading(None, h) for _, _, h in materials]
    nm = len(_unloading.NAMES)
    shift = curves[0][0].shift
    # one row list per quantity: the Hertz rows (shared), then each material's JG rows
    sizes = [c[0].e_rows.shape[0] - N_HERTZ for c in curves]
    offset = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(np.int64)
    base = [int(c[0].base) - int(o) for c, o in zip(curves, offset)]
    for c in curves:
        for d in c[1:]:  # every model shares the material's cells
            assert d.base == c[0].base and d.e_rows.shape == c[0].e_rows.shape and d.shift == shift

    def cat(field, code):
        return np.concatenate([getattr(curves[0][code], field)[:N_HERTZ]]
                              + [getattr(c[code], field)[N_HERTZ:] for c in curves])

    omega = cat("omega_rows", 0)
    nrow = omega.shape[0]
    guard = "".join(ch if ch.isalnum() else "_" for ch in name.upper())
    if not guard[0].isalpha():
        guard = "FASTREST_" + guard
    prov = provenance()
    # the loading law of hardening materials (none: the comment of a JG header is unchanged)
    hardening = [" * " + line for law in {x.name: x for x in laws if x.hardening}.values()
                 for line in textwrap.wrap(f"Materials with et_ratio = Et/E > 0 harden: loading law {law.name!r}, "
                                           f"{law.label}, with E/Sy = (1 - nu^2)/eps_y; {law.reference}.", 94)]
    lines = [f"/* {name}: generated by fastrest {prov['fastrest_version']} "
             f"(`{command or 'fastrest export c'}`). Do not edit.",
             " *",
             " * Coefficient of restitution of an elastic-perfectly plastic sphere on a rigid flat,",
             " * Jackson, Green & Marghitu (2010), doi:10.1007/s11071-009-9591-z, tabulated per material as",
             " * fastrest.curve does (degree-5 cells, ~1e-13 relative against the direct solver).",
             *hardening,
             " * Unloading models: " + "; ".join(f"{m.code} = {m.short}: {m.label}" for m in _unloading.MODELS.values()),
             " * Materials (k: eps_y = Sy/E', nu, largest V1* tabulated):"]
    for k, ((e, n, h), c) in enumerate(zip(materials, curves)):
        label = f"{k} ({names[k]})" if names and names[k] else f"{k}"
        hard = f", et_ratio = {h!r} (loading: {laws[k].name})" if h > 0.0 else ""
        lines.append(f" *   {label}: eps_y = {e!r}, nu = {n!r}{hard}, v_max = {c[0].v_max!r}"
                     + (f" (V up to {c[0].v_max * critical[k]['V_c']:.6g} m/s, V_c = {critical[k]['V_c']:.6g} m/s)"
                        if critical else ""))
    lines += [" * Evaluate with fastrest_e(k, v1_star, unloading), fastrest_omega_m(k, v1_star),",
              " * fastrest_loss(k, v1_star, unloading); V1* = V1/V_c (JGM eq 30). NaN outside [0, v_max[k]]."]
    if critical:
        lines += [" * Built from physical properties: fastrest_v1_star(k, V) gives V1* of a speed V (m/s), and",
                  " * fastrest_<name>[k] the pair's critical values (SI units, FASTREST_HAS_CRITICAL 1)."]
    lines += [" * C99 or C++, needs only libm (link with -lm); compiles unedited as CUDA (nvcc, NVRTC). */",
              f"#ifndef {guard}", f"#define {guard}", "",
              _PORTABLE,
              f"#define FASTREST_N_MATERIALS {len(materials)}",
              f"#define FASTREST_N_UNLOADING {nm}"]
    lines += [f"#define FASTREST_{m.short.upper()} {m.code}" for m in _unloading.MODELS.values()]
    lines += [f"#define FASTREST_V_SWITCH {_lit(V_SWITCH)} /* 1.9^1.25: end of Hertz loading */",
              f"#define FASTREST_HERTZ_SHIFT {HERTZ_SHIFT}",
              f"#define FASTREST_HERTZ_BASE FASTREST_INT64_C({HERTZ_BASE})",
              f"#define FASTREST_SHIFT {shift}", "",
              "/* largest V1* of each material */",
              _table("double", "fastrest_v_max", "[FASTREST_N_MATERIALS]", ", ".join(_lit(c[0].v_max) for c in curves)),
              "/* row of V1* > 1.9^1.25 for material k: (bits of V1*) >> FASTREST_SHIFT minus this */",
              _table("FASTREST_INT64", "fastrest_base", "[FASTREST_N_MATERIALS]",
                     ", ".join(f"FASTREST_INT64_C({b})" for b in base)),
              "/* eps_y = Sy/E' (JGM eq 11) and nu of each material */",
              _table("double", "fastrest_eps_y", "[FASTREST_N_MATERIALS]", ", ".join(_lit(m[0]) for m in materials)),
              _table("double", "fastrest_nu", "[FASTREST_N_MATERIALS]", ", ".join(_lit(m[1]) for m in materials)),
              f"#define FASTREST_HAS_CRITICAL {1 if critical else 0}"]
    if critical:
        lines.append("/* critical values of each pair (JGM eqs 4-7, 23, 28; fastrest.Impact.critical_values) */")
        for key, unit in CRITICAL_KEYS.items():
            vals = [c[key] for c in critical]
            lines.append(_table("double", f"fastrest_{key}", "[FASTREST_N_MATERIALS]", ", ".join(_lit(v) for v in vals))
                         + f" /* {unit}: " + ", ".join(f"{v:.6g}" for v in vals) + " */")
    lines += ["",
              f"FASTREST_TABLE(double, fastrest_omega_rows, [{nrow}][{ROW}], {{",
              _rows_literal(omega), "});"]
    for field, name in (("e_rows", "e"), ("loss_rows", "loss")):
        lines.append(f"FASTREST_TABLE(double, fastrest_{name}_rows, [FASTREST_N_UNLOADING][{nrow}][{ROW}], {{")
        blocks = []
        for code in range(nm):
            blocks.append(f"  {{ /* {_unloading.NAMES[code]} */\n" + _rows_literal(cat(field, code)) + "\n  }")
        lines.append(",\n".join(blocks))
        lines.append("});")
    lines += ["#if defined(__CUDACC__)", "#pragma nv_diagnostic pop", "#endif", _EVAL]
    if critical:
        lines.append(_V1_STAR)
    lines.append(f"#endif /* {guard} */")
    return "\n".join(lines) + "\n"


def write_header(path: str | os.PathLike[str], materials: Sequence[tuple[float, ...]], v_max: float | None = None,
                 command: str | None = None, *, critical: Sequence[dict[str, float]] | None = None,
                 names: Sequence[str] | None = None) -> tuple[str | os.PathLike[str], list[Any]]:
    """Build the curves and write the header atomically; returns (path, curves).

    ``path`` must be a regular file or a new path in a writable directory (checked first, as are
    ``materials`` and ``v_max``, a V1* or a list of one per material); a failed write (full disk)
    raises OSError naming ``path`` and leaves the old file intact. ``critical`` and ``names``: a
    header from physical properties (:func:`impact_materials`), see :func:`header_text`.
    """
    path = check_target(path, "path", "the header")
    if critical is not None and len(critical) != len(materials):
        raise ValueError(f"critical holds {len(critical)} entries for {len(materials)} materials")
    curves = scene_curves(materials, v_max)
    write_files({path: header_text(materials, curves, os.path.basename(path), command, critical, names)},
                "path", "the header")
    return path, curves
