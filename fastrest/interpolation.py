"""Piecewise-polynomial interpolation on cells indexed by the bits of the float.

The fast paths tabulate smooth functions of V1* on (1, 1.9^1.25] and (1.9^1.25, v_max]. Cells follow the binary
representation of V1*: each octave [2^E, 2^(E+1)) is split into 2^K equal cells, so the cell of a
positive float v is ``(bits(v) >> (52 - K)) - base``: an integer shift, no logarithm (the log is the
dominant cost of a uniform-in-log grid). Cells are therefore geometric across octaves and uniform
within one, with relative width between 2^-K and 2^(1-K).

Each cell stores one 64-byte row ``[center, 1/half_width, c0, ..., c5]``; the value is the degree-5
polynomial sum c_k u^k in u = (v - center)/half_width in [-1, 1], interpolating the function at the
cell's 6 Chebyshev-Lobatto points cos(k pi/5) (:data:`CHEB_U`), which include both ends: neighbouring
cells interpolate the same value at their shared edge, so the piecewise polynomial is continuous
there to a few ulp (and a monotone function stays monotone across cell edges). A cell boundary sits
exactly at V1* = 1.9^1.25 and the last cell ends at v_max, so no cell straddles the kink at w* = 1.9
or the end of the domain; a cell starting at the kink takes the JG side's limit there (the builders
evaluate that node one ulp inside the cell). :data:`GAUSS_U` (first-kind Chebyshev points, never at
the ends) serves functions that may not be evaluated at a cell's ends (a user's height pdf).
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray

import math

import numpy as np
from llvmlite import ir
from numba.core import cgutils, types
from numba.extending import intrinsic

from ._jit import jit

__all__ = ["DEGREE", "ROW", "MANTISSA_BITS", "CHEB_U", "GAUSS_U", "VALUES_TO_COEFFS", "float_bits",
           "fma", "select", "fdiv", "data_pointer", "row_in_range", "estrin5", "cell_key", "cell_edges", "two_level_cells", "chebyshev_nodes",
           "share_edges", "values_to_coeffs", "fit_cells", "cell_index", "two_level_index", "row_polynomial",
           "cell_polynomial", "cell_polynomial_in_range", "pointer_cell_polynomial"]

DEGREE = 5
ROW = DEGREE + 3  # center, 1/half_width, DEGREE + 1 coefficients
MANTISSA_BITS = 52

#: Chebyshev-Lobatto points on [-1, 1] (both ends included), increasing; the ends exactly -1 and 1.
#: (math.cos: NumPy's vectorised cos may differ in the last bit between CPU instruction sets, and
#: the table files store these points.)
CHEB_U = np.array([-1.0] + [-math.cos(math.pi * k / DEGREE) for k in range(1, DEGREE)] + [1.0])
#: Chebyshev points of the first kind (interior only).
GAUSS_U = np.array([math.cos(math.pi * (k + 0.5) / (DEGREE + 1)) for k in range(DEGREE, -1, -1)])
_TO_COEFFS = {id(CHEB_U): np.linalg.inv(np.vander(CHEB_U, DEGREE + 1, increasing=True)),
              id(GAUSS_U): np.linalg.inv(np.vander(GAUSS_U, DEGREE + 1, increasing=True))}
VALUES_TO_COEFFS = _TO_COEFFS[id(CHEB_U)]


@intrinsic
def float_bits(typingctx, x):
    """Reinterpret a float64 as its int64 bit pattern (an LLVM bitcast: free)."""
    if not isinstance(x, types.Float) or x.bitwidth != 64:
        return None
    sig = types.int64(types.float64)

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(64))

    return sig, codegen


@intrinsic
def fma(typingctx, a, b, c):
    """a * b + c with one rounding (llvm.fma: a single instruction on FMA hardware).

    More accurate than the two-rounding a * b + c and shorter in latency; Numba does not contract
    a * b + c by itself without fastmath, which fastrest avoids (it would also drop NaN checks).
    """
    if not all(isinstance(x, types.Float) and x.bitwidth == 64 for x in (a, b, c)):
        return None
    sig = types.float64(types.float64, types.float64, types.float64)

    def codegen(context, builder, signature, args):
        return builder.fma(*args)

    return sig, codegen


@intrinsic
def select(typingctx, c, a, b):
    """``a if c else b`` as one LLVM ``select``: both values are computed, no branch.

    Numba writes ``a if c else b`` as a branch; a kernel stepping contacts in different states
    (loading, unloading, apart) then mispredicts it. ``a`` and ``b`` are both float64 or both
    int64; ``c`` a boolean (one comparison: a select on a combination of comparisons compiles to a
    branch on x86).
    """
    if not isinstance(c, types.Boolean):
        return None
    if all(isinstance(x, types.Float) and x.bitwidth == 64 for x in (a, b)):
        ty = types.float64
    elif all(isinstance(x, types.Integer) and x.bitwidth == 64 and x.signed for x in (a, b)):
        ty = types.int64
    else:
        return None
    sig = ty(types.boolean, ty, ty)

    def codegen(context, builder, signature, args):
        return builder.select(args[0], args[1], args[2])

    return sig, codegen


@intrinsic
def fdiv(typingctx, a, b):
    """a / b of two float64, IEEE (b = 0 gives inf or NaN): no ZeroDivisionError check, which
    Numba adds to ``/`` in a caller compiled with ``error_model="python"`` (the default) and which
    is a branch."""
    if not all(isinstance(x, types.Float) and x.bitwidth == 64 for x in (a, b)):
        return None
    sig = types.float64(types.float64, types.float64)

    def codegen(context, builder, signature, args):
        return builder.fdiv(args[0], args[1])

    return sig, codegen


@intrinsic
def data_pointer(typingctx, a):
    """The data pointer of a C-contiguous array (a ``CPointer``: ``p[k]`` reads element k, flat).

    Kernels that take a tuple of arrays (a table) read its arrays through these pointers: a
    pointer is not reference-counted, while an array (or the tuple) that lives past a branch of
    an inlined kernel costs two atomic instructions per array per call, which also stop the
    processor from overlapping consecutive calls (``python -m bench.stencil``: a table loop ~118 vs
    ~74 ns per point).
    The array must outlive the pointer: it does while the caller holds the table (a TableData
    passed in from Python); a table built in jitted code and dropped at the call is not supported
    (keeping it alive in the kernel brings the per-point reference counting back).
    """
    if not (isinstance(a, types.Array) and a.layout == "C"):
        return None
    sig = types.CPointer(a.dtype)(a)

    def codegen(context, builder, signature, args):
        return context.make_array(signature.args[0])(context, builder, args[0]).data

    return sig, codegen


def cell_key(v: float, bits_per_octave: int) -> int:
    """Python twin of the kernels' raw cell key: (bits of v) >> (52 - K)."""
    return int(np.float64(v).view(np.int64)) >> (MANTISSA_BITS - bits_per_octave)


def cell_edges(v_lo: float, v_hi: float, bits_per_octave: int) -> tuple[int, NDArray[np.float64]]:
    """Cells covering [v_lo, v_hi] (v_lo > 0): (base key, array of [lo, hi] per cell).

    The first cell is cut to start at v_lo and the last to end at v_hi (or, when v_hi is exactly a
    cell's start, to span [v_hi, v_hi + 1 ulp], so that v_hi still has a cell).
    """
    shift = MANTISSA_BITS - bits_per_octave
    base = cell_key(v_lo, bits_per_octave)
    top = cell_key(v_hi, bits_per_octave)
    keys = np.arange(base, top + 1, dtype=np.int64)
    lo = (keys << shift).view(np.float64).copy()
    hi = ((keys + 1) << shift).view(np.float64).copy()
    lo[0] = v_lo
    # v_hi itself must index a cell: if it is exactly a cell's start, that cell spans one ulp
    hi[-1] = v_hi if lo[-1] < v_hi else np.nextafter(v_hi, np.inf)
    return base, np.stack([lo, hi], axis=1)


def two_level_cells(v_lo: float, v_split: float, v_hi: float, bits_fine: int,
                    bits: int) -> tuple[int, int, NDArray[np.float64]]:
    """Cells over [v_lo, v_hi]: 2^bits_fine per octave below ``v_split`` (a power of two), 2^bits
    from it on. Returns (base_fine, base, edges): the row of v is ``key_fine(v) - base_fine`` for
    v < v_split and ``key(v) - base`` otherwise (a compare and a select; see :func:`two_level_index`).
    """
    if v_split <= v_lo:  # no fine region
        base, edges = cell_edges(v_lo, v_hi, bits)
        return base, base, edges
    if v_hi < v_split:
        base_f, edges = cell_edges(v_lo, v_hi, bits_fine)
        return base_f, base_f, edges
    shift = MANTISSA_BITS - bits_fine
    base_f = cell_key(v_lo, bits_fine)
    keys = np.arange(base_f, cell_key(v_split, bits_fine), dtype=np.int64)
    fine = np.stack([(keys << shift).view(np.float64), ((keys + 1) << shift).view(np.float64)], axis=1)
    fine[0, 0] = v_lo
    base, coarse = cell_edges(v_split, v_hi, bits)
    return base_f, base - fine.shape[0], np.concatenate([fine, coarse])


def chebyshev_nodes(edges: NDArray[np.float64], u: NDArray[np.float64] = CHEB_U) -> NDArray[np.float64]:
    """The interpolation points of every cell, shape (ncell, DEGREE + 1), increasing; with the
    default Lobatto points the first and last are the cell's edges exactly (shared with the
    neighbours)."""
    center = 0.5 * (edges[:, 0] + edges[:, 1])
    half = 0.5 * (edges[:, 1] - edges[:, 0])
    nodes = center[:, None] + half[:, None] * u[None, :]
    if u is CHEB_U:
        nodes[:, 0], nodes[:, -1] = edges[:, 0], edges[:, 1]
    return nodes


def share_edges(values: NDArray[np.float64]) -> NDArray[np.float64]:
    """Make each cell's first value the previous cell's last (last axis: nodes, the one before:
    cells): the two are the same point, and a marching solver may have computed them an ulp apart."""
    values[..., 1:, 0] = values[..., :-1, -1]
    return values


def values_to_coeffs(values: NDArray[np.float64], u: NDArray[np.float64] = CHEB_U) -> NDArray[np.float64]:
    """Monomial coefficients (in u) of the degree-5 polynomials through values at the points ``u``
    (default :data:`CHEB_U`; last axis).

    The values' first entry is taken out before the matrix product and added back to c0: the
    higher coefficients are then computed from differences, which are exact and small, instead of
    by cancellation between large terms (that cost ~10 ulp; this keeps a cell within ~1-2 ulp of
    what it interpolates). A constant cell gets exactly [value, 0, ..., 0].
    """
    ref = values[..., :1]
    coeffs = (values - ref) @ _TO_COEFFS[id(u)].T
    coeffs[..., 0] += ref[..., 0]
    return coeffs


def fit_cells(edges: NDArray[np.float64], values: NDArray[np.float64], u: NDArray[np.float64] = CHEB_U) -> NDArray[np.float64]:
    """Rows [center, 1/half_width, c0..c5] from function values at :func:`chebyshev_nodes` (points ``u``).

    ``values`` has shape (..., ncell, DEGREE + 1); the result (..., ncell, ROW).
    """
    center = 0.5 * (edges[:, 0] + edges[:, 1])
    half = 0.5 * (edges[:, 1] - edges[:, 0])
    rows = np.empty(values.shape[:-1] + (ROW,))
    rows[..., 0] = center
    rows[..., 1] = 1.0 / half
    rows[..., 2:] = values_to_coeffs(values, u)
    return rows


@jit(inline=True)
def cell_index(v, shift, base):
    """Index of the cell holding v > 0 (no bounds check)."""
    return (float_bits(v) >> shift) - base


@jit(inline=True)
def two_level_index(v, v_split, shift_fine, base_fine, shift, base):
    """Row of v > 0 in a :func:`two_level_cells` layout (no bounds check)."""
    b = float_bits(v)
    return (b >> shift_fine) - base_fine if v < v_split else (b >> shift) - base


@jit(inline=True)
def estrin5(u, c0, c1, c2, c3, c4, c5):
    """sum c_k u^k, k = 0..5, by Estrin's scheme with fused multiply-adds: three dependent levels
    instead of Horner's five (the one evaluation order of every cell polynomial)."""
    u2 = u * u
    return fma(u2 * u2, fma(u, c5, c4), fma(u2, fma(u, c3, c2), fma(u, c1, c0)))


@intrinsic
def row_in_range(typingctx, rows, i):
    """True when ``i`` (an integer) is a row of ``rows``: 0 <= i < n for a (n, >= ROW) array, or
    for a 1-d array of n * ROW values (rows laid end to end); False for anything else (a negative
    or too large index, a 2-d array with fewer than ROW columns).

    One unsigned compare (a negative index wraps to a huge one). A :func:`data_pointer` carries
    no length: for it this is the constant True (no code); pointers exist only in jit code, whose
    caller holds the array and computes the index from it.
    """
    if not isinstance(i, types.Integer):
        return None
    if isinstance(rows, types.CPointer):
        def codegen(context, builder, signature, args):
            return context.get_constant(types.boolean, True)
        return types.boolean(rows, i), codegen
    if not (isinstance(rows, types.Array) and rows.ndim in (1, 2)):
        return None

    def codegen(context, builder, signature, args):  # noqa: F811
        aryty, ity = signature.args
        ary = context.make_array(aryty)(context, builder, args[0])
        shape = cgutils.unpack_tuple(builder, ary.shape, aryty.ndim)
        idx = context.cast(builder, args[1], ity, types.int64)
        row = ir.Constant(ir.IntType(64), ROW)
        if aryty.ndim == 2:
            ok = builder.icmp_unsigned("<", idx, shape[0])
            return builder.and_(ok, builder.icmp_signed(">=", shape[1], row))
        return builder.icmp_unsigned("<", idx, builder.udiv(shape[0], row))

    return types.boolean(rows, i), codegen


@jit(inline=True)
def row_polynomial(rows, i, u):
    """Row i's polynomial at the local coordinate u in [-1, 1] (:func:`estrin5`); NaN when ``i``
    is not a row of ``rows`` (:func:`row_in_range`)."""
    if not row_in_range(rows, i):
        return math.nan
    i = np.uint64(i)  # row indices are never negative: skip Numba's wraparound (latency)
    return estrin5(u, rows[i, 2], rows[i, 3], rows[i, 4], rows[i, 5], rows[i, 6], rows[i, 7])


@jit(inline=True)
def cell_polynomial_in_range(rows, i, v):
    """:func:`cell_polynomial` without the row check, for a caller whose ``i`` is a row of ``rows``
    by construction (a curve's speed checked against its v_max): the check measurably slowed the
    scene path (bench/BOUNDS_AB.md)."""
    k = np.uint64(i)
    return estrin5((v - rows[k, 0]) * rows[k, 1], rows[k, 2], rows[k, 3], rows[k, 4], rows[k, 5],
                   rows[k, 6], rows[k, 7])


@jit(inline=True)
def cell_polynomial(rows, i, v):
    """Evaluate row i's polynomial at v; NaN when ``i`` is not a row of ``rows``."""
    if not row_in_range(rows, i):
        return math.nan
    return cell_polynomial_in_range(rows, i, v)


@jit(inline=True)
def pointer_cell_polynomial(rows, i, v):
    """:func:`cell_polynomial` on the :func:`data_pointer` of a (n, ROW) array of rows (or on
    such rows laid end to end in a 1-d array: NaN when ``i`` is not one of them)."""
    if not row_in_range(rows, i):
        return math.nan
    k = ROW * i
    return estrin5((v - rows[k]) * rows[k + 1], rows[k + 2], rows[k + 3], rows[k + 4], rows[k + 5],
                   rows[k + 6], rows[k + 7])
