"""A self-contained C99 header with a scene's cells: ``fastrest export c``.

The header holds, for each material k of ``--materials``, the rows [center, 1/half_width, c0..c5]
of :mod:`fastrest.curve` (w_m*, and e and 1 - e^2 of every unloading model) as static arrays of
hexadecimal float literals (exact), and inline evaluators that follow
:func:`fastrest.curve.curve_value` operation by operation: the cell from the float's bits, u =
(v - center) * (1/half_width), Estrin's scheme with ``fma``. The only floating-point operations
outside ``fma`` are that subtraction and product, u*u, (u*u)*(u*u), (V1* - 1) * r and pow(V1*, 0.8):
none can be contracted into an fma by a compiler, so the C results equal the Python path's
bit for bit (tests/test_export_c.py compares 1e5+ points, cell boundaries included).
"""
import math
import os

import numpy as np

from .._validation import real_scalar
from ..cells import HERTZ_BASE, HERTZ_SHIFT, N_HERTZ
from ..curve import curve
from ..curve_data import build_curve_data
from ..energy import V_SWITCH
from ..interpolation import ROW
from ..limits import v1_star_limit
from .. import unloading as _unloading
from ._io import check_target, provenance, write_files

__all__ = ["MAX_MATERIALS", "parse_materials", "scene_curves", "header_text", "write_header"]

#: Most materials in one header (each adds ~420 kB of rows and a curve build).
MAX_MATERIALS = 256


def parse_materials(items, option="materials"):
    """[(eps_y, nu), ...] from ``EPS_Y:NU`` strings; ValueError naming ``option`` otherwise."""
    if isinstance(items, (str, bytes)) or not hasattr(items, "__len__"):
        raise TypeError(f"{option} must be a list of 'EPS_Y:NU' strings, got {type(items).__name__}")
    if len(items) > MAX_MATERIALS:
        raise ValueError(f"{option}: at most {MAX_MATERIALS} materials in one header; got {len(items)}")
    out = []
    for s in items:
        parts = str(s).split(":")
        try:
            if len(parts) != 2:
                raise ValueError
            e, n = float(parts[0]), float(parts[1])
        except ValueError:
            raise ValueError(f"{option}: expected EPS_Y:NU (e.g. 0.005:0.33); got {s!r}") from None
        out.append((e, n))
    if not out:
        raise ValueError(f"{option}: give at least one EPS_Y:NU material")
    return out


def _check_materials(materials):
    if isinstance(materials, (str, bytes)) or not hasattr(materials, "__len__"):
        raise TypeError(f"materials must be a list of (eps_y, nu) pairs, got {type(materials).__name__}")
    if not 1 <= len(materials) <= MAX_MATERIALS:
        raise ValueError(f"materials must hold 1 to {MAX_MATERIALS} (eps_y, nu) pairs; got {len(materials)}")
    for k, m in enumerate(materials):
        if isinstance(m, (str, bytes)) or not hasattr(m, "__len__") or len(m) != 2:
            raise TypeError(f"materials[{k}] must be an (eps_y, nu) pair, got {m!r}")


def scene_curves(materials, v_max=None, option="v_max"):
    """Curve data per (material, unloading model): list over materials of lists over model codes.

    Each material's curve reaches ``v_max`` (a V1*), by default its own w_m* = 425 speed;
    ``materials`` holds 1 to :data:`MAX_MATERIALS` (eps_y, nu) pairs.
    """
    _check_materials(materials)
    if v_max is not None:
        v_max = real_scalar(v_max, option)
        if not (v_max > 0 and math.isfinite(v_max)):
            raise ValueError(f"{option} must be a finite V1* > 0; got {v_max!r}")
    out = []
    for k, (e, n) in enumerate(materials):
        lim = v1_star_limit(e, n)
        if v_max is not None and v_max > lim:
            raise ValueError(f"{option} = {v_max!r} is past material {k}'s (eps_y = {e!r}, nu = {n!r}) limit "
                             f"w_m* = 425 at V1* = {lim:.10g}")
        # curve() validates eps_y and nu (ValueError naming them) and warns outside the validated range
        first = curve(e, n, _unloading.NAMES[0], v_max=v_max)
        out.append([first.data] + [build_curve_data(e, n, name, v_max=first.v_max) for name in _unloading.NAMES[1:]])
    return out


def _hex(x):
    x = float(x)
    if math.isnan(x):
        return "NAN"
    if math.isinf(x):
        return "INFINITY" if x > 0 else "-INFINITY"
    return x.hex()


def _rows_literal(rows, indent="    "):
    return ",\n".join(indent + "{" + ", ".join(_hex(x) for x in r) + "}" for r in rows)


_EVAL = r"""
/* Row layout: [center, 1/half_width, c0, c1, c2, c3, c4, c5]; value = sum c_i u^i,
   u = (v - center) * (1/half_width), by Estrin's scheme with fma (as fastrest.interpolation). */
static inline double fastrest__poly(const double *r, double v)
{
    double u = (v - r[0]) * r[1];
    double u2 = u * u;
    return fma(u2 * u2, fma(u, r[7], r[6]), fma(u2, fma(u, r[5], r[4]), fma(u, r[3], r[2])));
}

/* what: 0 w_m*, 1 e, 2 1 - e^2; rows: that quantity's rows (Hertz rows first, then every
   material's JG rows). The rule of fastrest.curve.curve_value. */
static inline double fastrest__value(const double (*rows)[8], int k, int what, double v)
{
    if (k < 0 || k >= FASTREST_N_MATERIALS)
        return NAN;
    if (v > 1.0) {
        if (v <= fastrest_v_max[k]) {
            int64_t b;
            int hertz = v <= FASTREST_V_SWITCH;
            double r;
            memcpy(&b, &v, sizeof b);
            r = fastrest__poly(rows[hertz ? (b >> FASTREST_HERTZ_SHIFT) - FASTREST_HERTZ_BASE
                                          : (b >> FASTREST_SHIFT) - fastrest_base[k]], v);
            if (what == 2 && hertz)
                r *= v - 1.0;
            return r;
        }
        return NAN;
    }
    if (v >= 0.0 && v <= fastrest_v_max[k]) {
        if (what == 0)
            return pow(v, 0.8);
        return what == 1 ? 1.0 : 0.0;
    }
    return NAN;
}

/* Normalised maximum interference w_m* (JGM eq 29) of material k at V1* = V1/V_c.
   NaN for V1* < 0, NaN, V1* > fastrest_v_max[k] or an unknown k. */
static inline double fastrest_omega_m(int k, double v1_star)
{
    return fastrest__value(fastrest_omega_rows, k, 0, v1_star);
}

/* Coefficient of restitution e (JGM eq 38) of material k at V1*; unloading: FASTREST_JCG,
   FASTREST_ETSION, FASTREST_BRAKE. NaN outside the domain or for an unknown k or unloading. */
static inline double fastrest_e(int k, double v1_star, int unloading)
{
    if (unloading < 0 || unloading >= FASTREST_N_UNLOADING)
        return NAN;
    return fastrest__value(fastrest_e_rows[unloading], k, 1, v1_star);
}

/* Dissipated fraction 1 - e^2 of material k at V1* (relative accuracy kept as V1* -> 1). */
static inline double fastrest_loss(int k, double v1_star, int unloading)
{
    if (unloading < 0 || unloading >= FASTREST_N_UNLOADING)
        return NAN;
    return fastrest__value(fastrest_loss_rows[unloading], k, 2, v1_star);
}
"""


def header_text(materials, curves, name="fastrest_scene.h", command=None):
    """The header's text for ``materials`` and their :func:`scene_curves`."""
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
    lines = [f"/* {name}: generated by fastrest {prov['fastrest_version']} "
             f"(`{command or 'fastrest export c'}`). Do not edit.",
             " *",
             " * Coefficient of restitution of an elastic-perfectly plastic sphere on a rigid flat,",
             " * Jackson, Green & Marghitu (2010), doi:10.1007/s11071-009-9591-z, tabulated per material as",
             " * fastrest.curve does (degree-5 cells, ~1e-13 relative against the direct solver).",
             " * Unloading models: " + "; ".join(f"{m.code} = {m.short}: {m.label}" for m in _unloading.MODELS.values()),
             " * Materials (k: eps_y = Sy/E', nu, largest V1* tabulated):"]
    for k, ((e, n), c) in enumerate(zip(materials, curves)):
        lines.append(f" *   {k}: eps_y = {e!r}, nu = {n!r}, v_max = {c[0].v_max!r}")
    lines += [" * Evaluate with fastrest_e(k, v1_star, unloading), fastrest_omega_m(k, v1_star),",
              " * fastrest_loss(k, v1_star, unloading); V1* = V1/V_c (JGM eq 28). NaN outside [0, v_max[k]].",
              " * C99, needs only libm (link with -lm). */",
              f"#ifndef {guard}", f"#define {guard}", "",
              "#include <math.h>", "#include <stdint.h>", "#include <string.h>", "",
              f"#define FASTREST_N_MATERIALS {len(materials)}",
              f"#define FASTREST_N_UNLOADING {nm}"]
    lines += [f"#define FASTREST_{m.short.upper()} {m.code}" for m in _unloading.MODELS.values()]
    lines += [f"#define FASTREST_V_SWITCH {_hex(V_SWITCH)} /* 1.9^1.25: end of Hertz loading */",
              f"#define FASTREST_HERTZ_SHIFT {HERTZ_SHIFT}",
              f"#define FASTREST_HERTZ_BASE INT64_C({HERTZ_BASE})",
              f"#define FASTREST_SHIFT {shift}", "",
              "/* largest V1* of each material */",
              "static const double fastrest_v_max[FASTREST_N_MATERIALS] = {"
              + ", ".join(_hex(c[0].v_max) for c in curves) + "};",
              "/* row of V1* > 1.9^1.25 for material k: (bits of V1*) >> FASTREST_SHIFT minus this */",
              "static const int64_t fastrest_base[FASTREST_N_MATERIALS] = {"
              + ", ".join(f"INT64_C({b})" for b in base) + "};", "",
              f"static const double fastrest_omega_rows[{nrow}][{ROW}] = {{",
              _rows_literal(omega), "};"]
    for field, name in (("e_rows", "e"), ("loss_rows", "loss")):
        lines.append(f"static const double fastrest_{name}_rows[FASTREST_N_UNLOADING][{nrow}][{ROW}] = {{")
        blocks = []
        for code in range(nm):
            blocks.append(f"  {{ /* {_unloading.NAMES[code]} */\n" + _rows_literal(cat(field, code)) + "\n  }")
        lines.append(",\n".join(blocks))
        lines.append("};")
    lines.append(_EVAL)
    lines.append(f"#endif /* {guard} */")
    return "\n".join(lines) + "\n"


def write_header(path, materials, v_max=None, command=None):
    """Build the curves and write the header atomically; returns (path, curves).

    ``path`` must be a regular file or a new path in a writable directory (checked first, as are
    ``materials`` and ``v_max``); a failed write (full disk) raises OSError naming ``path`` and
    leaves the old file intact.
    """
    path = check_target(path, "path", "the header")
    curves = scene_curves(materials, v_max)
    write_files({path: header_text(materials, curves, os.path.basename(path), command)}, "path", "the header")
    return path, curves
