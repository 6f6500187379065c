"""The compiled table evaluator: the kernels that interpolate a :class:`~fastrest.tables.TableData`.

Evaluation at (V1*, eps_y, nu): the degree-5 polynomial of V1*'s cell at each of the 6 x 6 nearest
material nodes, combined with 6-point Lagrange weights in the mapped C(nu) eps_y and in nu. Below
1.9^1.25 the answer does not depend on the material: the closed forms (Hertz loading), evaluated by
the same few-ulp cells as :mod:`fastrest.curve`; V1* <= 1 is exact (elastic). A query whose
interpolated w_m* exceeds 425 (by more than :data:`OMEGA_LIMIT_TOL`) gives NaN.

Names: ``*_kernel`` evaluate one point (NaN outside the table), ``*_array`` loop over flat arrays
into ``out``. :func:`table_array` and :func:`interpolant_array` are documented internals for tests
and bench, as is the Numba intrinsic :func:`stencil_coefficients` (jitted callers only, so not in
``__all__``); users call :class:`~fastrest.tables.Table` methods or :mod:`fastrest.jit`.

Speed (``python -m bench.stencil``): the kernels read the table's arrays through data pointers taken
before any branch (no reference counting per point) and sum the stencil in vector lanes.
"""
import math

import numba as nb
import numpy as np
from llvmlite import ir
from numba.core import types
from numba.extending import intrinsic

from .._jit import fmul_rn, is_cuda, jit, mul_rn
from .._validation import EDGE_TOL, OMEGA_M_STAR_MAX
from ..loading.jackson_green import omega_star_limit_kernel
from ..critical import c_of_nu
from ..energy import V_SWITCH
from ..interpolation import cell_index, data_pointer, estrin5, pointer_cell_polynomial, two_level_index
from ..cells import HERTZ_BASE, HERTZ_SHIFT, N_HERTZ
from .grid import STENCIL_EPS, STENCIL_NU

__all__ = ["OMEGA_LIMIT_TOL", "OMEGA_LIMIT", "EPS_Y_AR_BINDS", "table_value_kernel", "table_value", "table_array",
           "table_array_parallel", "interpolant_array"]

#: The w_m* <= 425 check is made on the interpolated w_m*, with the table's accuracy as tolerance.
OMEGA_LIMIT_TOL = 1e-9
#: Largest interpolated w_m* a table answers for.
OMEGA_LIMIT = OMEGA_M_STAR_MAX * (1.0 + OMEGA_LIMIT_TOL)
#: Below this eps_y the JG law's end (a/R = 1, eq 12) lies past w* = 425 for every 0 <= nu <= 0.5
#: (it reaches 425 at eps_y = 0.010223 for nu = 0.5, 0.0141 for nu = 0; tested), so only wider
#: tables pay for the per-point a/R limit.
EPS_Y_AR_BINDS = 0.0102

@jit(inline=True)
def _first_node(pos, m, n):
    """First node of the m-point stencil centred at ``pos`` (in node spacings), moved inside [0, n)."""
    i = int(math.floor(pos)) - (m // 2 - 1)
    if i < 0:
        return 0
    if i > n - m:
        return n - m
    return i


@jit(inline=True)
def _lagrange6(x, x0, inv_h, n):
    """First index and weights of the 6-node Lagrange stencil at x on a uniform grid."""
    pos = mul_rn(x - x0, inv_h)  # mul_rn: pos - i is not fused on CUDA either (fastrest._jit)
    i = _first_node(pos, 6, n)
    t = pos - i
    t1, t2, t3, t4, t5 = t - 1.0, t - 2.0, t - 3.0, t - 4.0, t - 5.0
    # a flat (index, w0..w5) tuple: a nested weights tuple trips Numba's parfor array analysis
    # when this is inlined into a parallel loop (AssertionError "Dimension mismatch")
    return (i, -t1 * t2 * t3 * t4 * t5 / 120.0, t * t2 * t3 * t4 * t5 / 24.0,
            -t * t1 * t3 * t4 * t5 / 12.0, t * t1 * t2 * t4 * t5 / 12.0,
            -t * t1 * t2 * t3 * t5 / 24.0, t * t1 * t2 * t3 * t4 / 120.0)


@jit(inline=True)
def table_value_kernel(tab, q, v, eps_y, nu):
    """One tabulated quantity at one point (jit, inlined into the caller's loop).

    Parameters
    ----------
    tab : TableData
        The table's data (``fastrest.load_table().data``).
    q : int
        Index into :data:`~fastrest.tables.QUANTITIES`: 0 w_m*, 1 + 2 code e, 2 + 2 code 1 - e^2 of
        the unloading model with that code (JCG 0, Etsion 1, Brake 2).
    v : float
        V1* = V1/V_c (-), JGM eq (30).
    eps_y, nu : float
        The material: Sy/E' (-) and Poisson's ratio (-).

    Returns
    -------
    float
        The quantity (-); NaN outside the table (eps_y, nu or V1* out of range, w_m* > 425, or past
        a/R = 1 for eps_y > 0.0102) or for invalid input (including a q the table does not hold).
        No exception: callers check for NaN (the Table methods raise the named ValueError).

    Notes
    -----
    The 6 x 6 Lagrange stencil across (xi, nu) of each node's degree-5 cell polynomial in V1*; below
    V1* = 1.9^1.25 the closed forms (Hertz loading, JGM eq 19, elastic unloading); w_m* from
    JGM eq (29), e from eq (38).

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.tables import table_value_kernel
    >>> round(table_value_kernel(fastrest.load_table().data, 1, 5.0, 0.005, 0.33), 6)
    0.898078
    """
    # float32 and integer inputs, as the Python API takes them; q is checked by _interpolate, after
    # it has read the table (no branch before: see there)
    return _interpolate(tab, q, np.float64(v), np.float64(eps_y), np.float64(nu), True)


#: Former name of :func:`table_value_kernel` (same object).
table_value = table_value_kernel


@jit(inline=True)
def _interpolate(tab, q, v, eps_y, nu, check_limit):
    # The table is read here, in straight-line code before any branch, and its arrays as data
    # pointers: an array, or ``tab`` itself (a tuple of arrays), still alive after a branch is
    # reference-counted on every call with atomic instructions, which also keep the processor
    # from overlapping consecutive points (Numba; `python -m bench.stencil`: ~118 vs ~74 ns per
    # point).
    # (The same effect made a namedtuple field read inside a rarely taken branch ~7x slower.)
    eps_lo, eps_hi, nu_lo, nu_hi, v_top, v_safe = tab.eps_lo, tab.eps_hi, tab.nu_lo, tab.nu_hi, tab.v_top, tab.v_safe
    hertz = data_pointer(tab.hertz)
    cells = data_pointer(tab.cells)
    cell_block = data_pointer(tab.cell_block)
    block_cell0 = data_pointer(tab.block_cell0)
    g = (data_pointer(tab.coef), data_pointer(tab.block_offset), block_cell0, data_pointer(tab.block_inv_h),
         data_pointer(tab.block_n), data_pointer(tab.block_qstride), tab.xi0, tab.nu0, tab.inv_h_nu, tab.n_nu)
    map_rate = tab.map_rate
    split = (tab.v_split, tab.shift_fine, tab.base_fine, tab.shift, tab.base)
    n_quantities = tab.n_quantities
    if not (q >= 0 and q < n_quantities):
        return np.nan
    # a material a few ulp outside an edge (0.001 + 0.0005 * 18 = 0.010000000000000002) is at
    # the edge: clamped there, never extrapolated further
    e_lo, e_hi, n_lo, n_hi = eps_lo, eps_hi, nu_lo, nu_hi
    if not (eps_y >= e_lo * (1.0 - EDGE_TOL) and eps_y <= e_hi * (1.0 + EDGE_TOL)
            and nu >= n_lo * (1.0 - EDGE_TOL) and nu <= n_hi * (1.0 + EDGE_TOL)):
        return np.nan
    eps_y = min(max(eps_y, e_lo), e_hi)
    nu = min(max(nu, n_lo), n_hi)
    if not v > V_SWITCH:
        if v > 1.0:  # Hertz loading: the closed forms' cells, the same for every material
            r = pointer_cell_polynomial(hertz, q * N_HERTZ + cell_index(v, HERTZ_SHIFT, HERTZ_BASE), v)
            return r * (v - 1.0) if q > 0 and q % 2 == 0 else r  # the losses
        if v >= 0.0:  # elastic, exact
            if q == 0:
                return v**0.8
            return 1.0 if q % 2 == 1 else 0.0
        return np.nan
    if not v <= v_top:
        return np.nan
    cell = two_level_index(v, split[0], split[1], split[2], split[3], split[4])
    u = mul_rn(v - cells[2 * cell], cells[2 * cell + 1])  # u + 1.0 below: not fused on CUDA either
    c_eps_y = c_of_nu(nu) * eps_y
    xi = math.expm1(map_rate * c_eps_y) / map_rate if map_rate > 0.0 else c_eps_y
    b = cell_block[cell]
    blend = cell == block_cell0[b] and b > 0
    w_lim = OMEGA_LIMIT
    check = check_limit and v > v_safe
    if check and eps_y > EPS_Y_AR_BINDS:  # the law may end (a/R = 1) before w* = 425
        w_lim = min(w_lim, omega_star_limit_kernel(eps_y, nu) * (1.0 + OMEGA_LIMIT_TOL))
    if not (blend or (check and q != 0)):  # the common case, straight-line
        r = _block_value(g, q, b, cell, u, xi, nu)
        if check and not r <= w_lim:
            return np.nan
        return r
    # otherwise one more call site of the (inlined) stencil sum, in loops: passes over (w_m* for
    # the limit check, then q) and over (this block, the previous one for a blended cell)
    r = np.nan
    for p in range(2 if check and q != 0 else 1):
        qq = 0 if p == 0 and check and q != 0 else q
        val = 0.0
        for k in range(2 if blend else 1):
            x = _block_value(g, qq, b - k, cell, u, xi, nu)
            if k == 0:
                val = x
            else:  # smoothstep from the previous block's grid (left edge) to this block's (right)
                t = min(max(0.5 * (u + 1.0), 0.0), 1.0)
                val = x + mul_rn(t * t * (3.0 - mul_rn(2.0, t)), val - x)
        if check and qq == 0 and not val <= w_lim:
            return np.nan
        r = val
    return r


@jit(inline=True)
def _block_value(g, q, b, cell, u, xi, nu):
    """Quantity q in ``cell`` interpolated across materials on block b's grid; ``g`` is the
    table's (coef, block_offset, block_cell0, block_inv_h, block_n, block_qstride, xi0, nu0,
    inv_h_nu, n_nu), the arrays as data pointers. The first cell of a block b > 0 is blended by
    :func:`_interpolate` from the previous block's grid at its left edge (where the previous cell
    ends on that grid) to its own at its right edge, so the table is continuous across block
    boundaries to a few ulp although the two grids interpolate materials differently (by up to
    the table's error, ~1e-10)."""
    coef, offset, cell0, inv_h, block_n, qstride, xi0, nu0, inv_h_nu, n_nu = g
    n = block_n[b]
    i, e0, e1, e2, e3, e4, e5 = _lagrange6(xi, xi0, inv_h[b], n)
    j, n0, n1, n2, n3, n4, n5 = _lagrange6(nu, nu0, inv_h_nu, n_nu)
    row = 6 * n_nu  # one eps_y node's coefficients
    first = offset[b] + ((cell - cell0[b]) * n + i) * row + 6 * j + q * qstride[b]
    c0, c1, c2, c3, c4, c5 = stencil_coefficients(coef, first, row, (e0, e1, e2, e3, e4, e5),
                                                   (n0, n1, n2, n3, n4, n5))
    return estrin5(u, c0, c1, c2, c3, c4, c5)


def _splat(builder, x, n):
    """An n-lane vector of the double x."""
    vec = ir.VectorType(ir.DoubleType(), n)
    v = builder.insert_element(ir.Constant(vec, ir.Undefined), x, ir.Constant(ir.IntType(32), 0))
    return builder.shuffle_vector(v, ir.Constant(vec, ir.Undefined), ir.Constant(ir.VectorType(ir.IntType(32), n),
                                                                                  [0] * n))


@intrinsic
def stencil_coefficients(typingctx, coef, first, row, we, wn):
    """The 6 x 6 stencil's combined polynomial coefficients (jit intrinsic; documented internal).

    Parameters
    ----------
    coef : CPointer(float64)
        Data pointer of a table's coefficients (``data_pointer(tab.coef)``).
    first : int
        Index in ``coef`` of the stencil's first node: 6 coefficients p_ab[0..5] per node, the 6
        nu nodes b of one eps_y node consecutive.
    row : int
        Stride between eps_y nodes a (6 x n_nu).
    we, wn : tuple of 6 float
        Lagrange weights in xi (eps_y) and nu (-).

    Returns
    -------
    tuple of 6 float
        c_k = sum_a sum_b (we[a] wn[b]) p_ab[k], k = 0..5: the coefficients of the interpolated
        cell polynomial (-).

    Notes
    -----
    Each c_k is the sequence of roundings of the scalar loop
    ``for a: for b: w = we[a] * wn[b]; c_k += w * p_ab[k]`` (a multiply, then an add: fused ones
    lengthen the dependency chain, measured ~10 % slower), with the six k in vector lanes (4 + 2):
    the same numbers as that loop, a third of the instructions (``python -m bench.stencil``).
    On CUDA the same sums one coefficient at a time, each product rounded on its own
    (``mul.rn.f64``: not fused into the addition, so the same numbers again; ``fastrest._jit``).
    Callable from jitted code only.
    """
    f64 = types.float64
    if not (isinstance(coef, types.CPointer) and coef.dtype == f64 and isinstance(first, types.Integer)
            and isinstance(row, types.Integer) and we == types.UniTuple(f64, STENCIL_EPS)
            and wn == types.UniTuple(f64, STENCIL_NU)):
        return None
    sig = types.UniTuple(f64, 6)(coef, first, row, we, wn)

    def codegen(context, builder, signature, args):
        p, first_, row_, we_, wn_ = args
        i64 = ir.IntType(64)
        first_ = context.cast(builder, first_, signature.args[1], types.int64)
        row_ = context.cast(builder, row_, signature.args[2], types.int64)
        if is_cuda(builder):  # the same sums, one coefficient at a time, products never fused
            acc = [ir.Constant(ir.DoubleType(), 0.0)] * 6
            for a in range(STENCIL_EPS):
                ea = builder.extract_value(we_, a)
                start = builder.add(first_, builder.mul(row_, ir.Constant(i64, a)))
                for b in range(STENCIL_NU):
                    w = builder.fmul(ea, builder.extract_value(wn_, b))
                    node = builder.add(start, ir.Constant(i64, 6 * b))
                    for k in range(6):
                        x = builder.load(builder.gep(p, [builder.add(node, ir.Constant(i64, k))]), align=8)
                        acc[k] = builder.fadd(acc[k], fmul_rn(builder, w, x))
            return context.make_tuple(builder, signature.return_type, acc)
        lanes = (4, 2)  # lanes of coefficients 0-3 and 4-5
        acc = [ir.Constant(ir.VectorType(ir.DoubleType(), n), [0.0] * n) for n in lanes]
        for a in range(STENCIL_EPS):
            ea = builder.extract_value(we_, a)
            start = builder.add(first_, builder.mul(row_, ir.Constant(i64, a)))
            for b in range(STENCIL_NU):
                w = builder.fmul(ea, builder.extract_value(wn_, b))
                node = builder.gep(p, [builder.add(start, ir.Constant(i64, 6 * b))])
                for m, (n, k0) in enumerate(zip(lanes, (0, 4))):
                    vec = ir.VectorType(ir.DoubleType(), n)
                    x = builder.load(builder.bitcast(builder.gep(node, [ir.Constant(i64, k0)]), vec.as_pointer()),
                                     align=8)
                    acc[m] = builder.fadd(acc[m], builder.fmul(_splat(builder, w, n), x))
        out = [builder.extract_element(acc[m], ir.Constant(ir.IntType(32), k)) for m, n in enumerate(lanes)
               for k in range(n)]
        return context.make_tuple(builder, signature.return_type, out)

    return sig, codegen


@jit
def interpolant_array(tab, q, v, eps_y, nu, out):
    """out[k]: quantity q at (v[k], eps_y[k], nu[k]) without the w_m* <= 425 check (documented internal).

    For measuring the interpolant's error right at the limit (:mod:`fastrest.tables.error`).

    Parameters
    ----------
    tab, q, v, eps_y, nu, out
        As :func:`table_array`.

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> out = np.empty(1)
    >>> interpolant_array(fastrest.load_table().data, 0, np.array([5.0]), np.array([0.005]), np.array([0.33]), out)
    >>> round(float(out[0]), 6)
    3.673079
    """
    for k in range(v.size):
        out[k] = _interpolate(tab, q, v[k], eps_y[k], nu[k], False)


@jit
def table_array(tab, q, v, eps_y, nu, out):
    """out[k] = :func:`table_value_kernel` (tab, q, v[k], eps_y[k], nu[k]) (documented internal).

    Parameters
    ----------
    tab : TableData
    q : int
        Quantity index (see :func:`table_value_kernel`).
    v, eps_y, nu : ndarray
        Flat float64 arrays of equal size: V1* (-), Sy/E' (-), Poisson's ratio (-).
    out : ndarray
        Flat float64 array written in place; NaN where the table has no answer.

    Notes
    -----
    The Table methods validate their input, call this (or :func:`table_array_parallel`) and raise
    for NaN; tests and bench call it directly.

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> out = np.empty(2)
    >>> table_array(fastrest.load_table().data, 1, np.array([5.0, 1e6]), np.full(2, 0.005), np.full(2, 0.33), out)
    >>> round(float(out[0]), 6), bool(np.isnan(out[1]))
    (0.898078, True)
    """
    for k in range(v.size):
        out[k] = table_value_kernel(tab, q, v[k], eps_y[k], nu[k])


@jit(parallel=True)
def table_array_parallel(tab, q, v, eps_y, nu, out):
    """:func:`table_array` on all cores (same numbers; documented internal).

    Parameters
    ----------
    tab, q, v, eps_y, nu, out
        As :func:`table_array`.

    Notes
    -----
    Call it through :func:`fastrest._threads.run_parallel` (a thread-unsafe Numba threading layer
    must not be entered from two threads at once); the Table methods use it from
    :data:`~fastrest.tables.PARALLEL_MIN_POINTS` points on.

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> tab, v, e, n = fastrest.load_table().data, np.array([5.0, 10.0]), np.full(2, 0.005), np.full(2, 0.33)
    >>> out, ref = np.empty(2), np.empty(2)
    >>> table_array_parallel(tab, 1, v, e, n, out); table_array(tab, 1, v, e, n, ref)
    >>> bool((out == ref).all()), round(float(out[0]), 6)  # the same numbers
    (True, 0.898078)
    """
    for k in nb.prange(v.size):
        out[k] = table_value_kernel(tab, q, v[k], eps_y[k], nu[k])
