"""Explicit rough surfaces with the sums over their summits on the GPU (:func:`rough_impact`,
re-exported by :mod:`fastrest.cuda`)."""
import math
import weakref
from typing import Any

import numpy as np
from numba import float64 as _f8

from ..rough import explicit as _explicit
from ..rough.explicit import summit_w
from ..rough.surface import RoughSurface
from ..rough.common import FAILED as _FAILED, MAX_ITER as _MAX_ITER, NEEDS_TABLE as _NEEDS_TABLE, OK as _OK, \
    ONSET_BAND as _ONSET_BAND, energy_excess as _energy_excess
from ._device import SIMULATOR, THREADS_PER_BLOCK, _is_device_array, cuda, to_device

__all__ = ["ROUGH_BLOCKS", "rough_impact"]

# --- rough surfaces: explicit summits on the device ----------------------------------------------

#: Blocks (at most) of the rough-surface sums; each thread adds every (blocks x threads)-th summit.
ROUGH_BLOCKS = 2 if SIMULATOR else 2048
_ROUGH_THREADS = 8 if SIMULATOR else THREADS_PER_BLOCK  # a power of two (tree reduction)
_ROUGH_KERNELS: dict[str, Any] = {}
_ROUGH_ROWS = {"hertz": _explicit._hertz_row, "jg": _explicit._jg_row, "impact": _explicit._impact_row}


def _rough_kernel_function(row):
    """The Python source of a kernel summing ``row(data, w, d, r_i, onset)`` (4 values) over the summits
    in contact, exactly as :func:`fastrest.rough.explicit._block_sums` does on the CPU: block b
    writes its partial sums to ``part[b]``.

    Summation order: thread t of block b adds summits i = b T + t, i + G, i + 2G, ... (G = blocks x
    T threads) in that order; the T thread sums of a block are added pairwise in shared memory (t +=
    t + T/2, T/4, ..., 1); the host adds the block sums in block order. The order is fixed for a
    given number of summits (results do not depend on the run), and differs from the CPU's (blocks
    of 8192 consecutive summits).
    """
    tpb = _ROUGH_THREADS

    def kernel(data, h, r, descending, x, delta, onset, part):
        sm = cuda.shared.array((tpb, 4), _f8)
        t = cuda.threadIdx.x
        i = cuda.grid(1)
        stride = cuda.gridsize(1)
        s0 = s1 = s2 = s3 = 0.0
        while i < h.size:
            if h[i] + x > 0.0:
                w, d = summit_w(h[i], r[i], x, delta)
                r0, r1, r2, r3 = row(data, w, d, r[i], onset)
                s0 += r0
                s1 += r1
                s2 += r2
                s3 += r3
            elif descending:  # heights tallest first: the rest of this thread's summits are lower
                break
            i += stride
        sm[t, 0] = s0
        sm[t, 1] = s1
        sm[t, 2] = s2
        sm[t, 3] = s3
        cuda.syncthreads()
        half = tpb // 2
        while half > 0:
            if t < half:
                for k in range(4):
                    sm[t, k] += sm[t + half, k]
            cuda.syncthreads()
            half //= 2
        if t == 0:
            for k in range(4):
                part[cuda.blockIdx.x, k] = sm[0, k]

    kernel.__name__ = kernel.__qualname__ = f"fastrest_rough_sums_{row.__name__.strip('_')}"
    return kernel


class _RoughSums:
    """The per-summit sums of one surface on the device: heights h and radius ratios r (ones for one
    radius) copied once, a partial-sum array; the host keeps h and r (None for one radius) for
    :func:`~fastrest.rough.explicit.x_reaching` and :func:`~fastrest.rough.explicit.largest_w`."""

    def __init__(self, h, r, descending):
        self.h = cuda.to_device(np.ascontiguousarray(h))
        self.r = cuda.to_device(np.ascontiguousarray(_explicit.radius_ratios(r, h.size)))
        self.h_host, self.r_host, self.descending = h, r, bool(descending)
        n = h.size
        self.blocks = max(1, min(ROUGH_BLOCKS, (n + _ROUGH_THREADS - 1) // _ROUGH_THREADS))
        self.part = cuda.device_array((self.blocks, 4), dtype=np.float64)
        self.tables: list[Any] = []  # (host ForwardData, its device copy)

    def on_device(self, data):
        """The device copy of the forward table ``data`` (one kept: the latest)."""
        for host, dev in self.tables:
            if host is data:
                return dev
        dev = to_device(data)
        self.tables[:] = [(data, dev)]
        return dev

    def __call__(self, kind, data, x, delta):
        if kind not in _ROUGH_KERNELS:
            _ROUGH_KERNELS[kind] = cuda.jit(_rough_kernel_function(_ROUGH_ROWS[kind]))
        onset = abs(delta) < _ONSET_BAND
        _ROUGH_KERNELS[kind][self.blocks, _ROUGH_THREADS](data, self.h, self.r, self.descending, x, delta, onset,
                                                            self.part)
        return _explicit._add_blocks(self.part.copy_to_host())


def _rough_approach(sums, kind, data, e_hi, e_lo, x0, d0, w_table, w_model):
    """(status, x, delta): :func:`fastrest.rough.explicit._approach` with the sums on the device
    (the same safeguarded Newton step, :func:`~fastrest.rough.explicit._advance`, on the host)."""
    w_cap = _explicit.x_reaching(sums.h_host, sums.r_host, min(w_table, w_model))
    st = _explicit._start(x0, d0)
    X, D, LO_X = _explicit._X, _explicit._D, _explicit._LO_X
    for _ in range(_MAX_ITER):
        if st[X] > w_cap:
            if not (w_table >= w_model and st[LO_X] < w_cap):
                return _NEEDS_TABLE, st[X], st[D]
            st[X], st[D] = w_cap, w_cap - 1.0
        t = sums(kind, data, float(st[X]), float(st[D]))
        if _explicit._advance(st, t[0], t[1], t[2], t[3], e_hi, e_lo):
            return (_OK if st[X] <= w_cap else _NEEDS_TABLE), st[X], st[D]
    return _FAILED, st[X], st[D]


_ROUGH_DEVICE: "weakref.WeakKeyDictionary[Any, _RoughSums]" = weakref.WeakKeyDictionary()


def rough_impact(surface: Any, V1: Any, M: float, unloading: str = "jcg", *, extrapolate: bool = False) -> Any:
    """:meth:`fastrest.rough.RoughSurface.impact` of an explicit surface, the sums over summits on the GPU.

    Parameters
    ----------
    surface : fastrest.rough.RoughSurface
        An explicit surface (``heights=``). Its summit heights are copied to the device on the
        first call and kept there while the surface lives (later calls copy nothing but the forward
        table when it grows).
    V1, M, unloading, extrapolate
        As :meth:`~fastrest.rough.RoughSurface.impact`: host values (speeds in m/s, a float or a
        NumPy array; mass in kg), not device arrays.

    Returns
    -------
    fastrest.rough.RoughImpact
        As :meth:`~fastrest.rough.RoughSurface.impact`, equal to it to the solver's accuracy
        (below).

    Raises
    ------
    TypeError
        ``surface`` not a RoughSurface, or a statistical one (``gw=``: no summits to put on the
        device; use its ``impact``); ``V1`` a device array; and what ``impact`` raises.
    ValueError
        As :meth:`~fastrest.rough.RoughSurface.impact`.

    Notes
    -----
    Each step of the deepest-approach solve (:mod:`fastrest.rough.explicit`: safeguarded Newton
    on sum_i F(w_i) = E, JGM eq 29 per summit) needs sums over every summit: of the energy terms
    F(w_i), of their magnitudes, of the forces P*(w_i) and of the summits counted from the onset;
    at the solution, sum P*, sum L (eq 38), the contact and yield counts. One kernel launch forms
    each set of sums, every thread calling the CPU's per-summit functions
    (``explicit._hertz_row``, ``_jg_row``, ``_impact_row`` over :mod:`fastrest.rough.common`,
    compiled for the GPU from the same source); the Newton/bisection step runs on the host
    (``explicit._advance``), so the iteration is the CPU's. Only the summation order differs
    (``_rough_kernel_function``): e, the loss 1 - e^2 and the other fields agree with the CPU
    path to a few 1e-15 relative on small surfaces (tests/test_cuda.py measures it under the
    simulator; the rounding of a sum of N terms grows at most like N eps, ~1e-12 at N = 1e4 in the
    worst case, and like sqrt(N) eps in practice), far inside the CPU path's stated accuracy
    (docs/rough.md). On a GPU the per-summit functions also run through libdevice's
    ``pow``/``exp``, within ~1e-15 relative of the CPU's libm per summit.

    Examples
    --------
    >>> import fastrest, fastrest.cuda
    >>> from fastrest import rough
    >>> s = rough.RoughSurface(fastrest.Material(200e9, 0.3, 1e9), 1e-4, heights=[0.0, 1e-8, 3e-8])
    >>> g, c = fastrest.cuda.rough_impact(s, 0.1, 1e-3), s.impact(0.1, 1e-3)
    >>> abs(g.e - c.e) < 1e-12, g.n_contact == c.n_contact
    (True, True)
    """
    if not isinstance(surface, RoughSurface):
        raise TypeError(f"surface must be a fastrest.rough.RoughSurface, got {type(surface).__name__}")
    if surface.kind != "explicit":
        raise TypeError("surface must be an explicit RoughSurface (heights=): a statistical surface (gw=) has no "
                        "summits to put on the GPU; call its impact() on the CPU")
    if _is_device_array(V1) and not isinstance(V1, np.ndarray):
        raise TypeError("V1 must be host speeds (a float or a NumPy array, m/s), got a device array: the summit "
                        "sums run on the GPU, the speeds stay on the host (copy_to_host())")
    sums = _ROUGH_DEVICE.get(surface)
    if sums is None:
        sums = _ROUGH_DEVICE[surface] = _RoughSums(surface._h, surface._r, surface._descending)

    def solve(e_hi, e_lo, unloading, extrapolate, M):
        x0, d0 = np.empty(e_hi.size), np.empty(e_hi.size)
        for k in range(e_hi.size):  # explicit._hertz_approach_array, the sums on the device
            x = e_hi[k]**0.4
            d = x - 1.0
            if 0.5 <= x <= 2.0:
                d = math.expm1(0.4 * math.log1p(_energy_excess(e_hi[k], e_lo[k], 1.0)))
            status, x0[k], d0[k] = _rough_approach(sums, "hertz", 0.0, e_hi[k], e_lo[k], x, d, math.inf,
                                                   math.inf)
            if status != _OK:
                raise RuntimeError("rough-surface solver (Hertz estimate) did not converge (please report)")

        def run(data, w_model):  # explicit._explicit_impacts_array
            dev = sums.on_device(data)
            out = np.zeros((8, e_hi.size))
            for k in range(e_hi.size):
                status, x, d = _rough_approach(sums, "jg", dev, e_hi[k], e_lo[k], x0[k], d0[k], data.w_max,
                                               w_model)
                w_top = _explicit.largest_w(sums.h_host, sums.r_host, x)
                out[0, k], out[1, k], out[2, k], out[3, k] = status, w_top, x, w_top
                if status == _OK:
                    out[4:, k] = sums("impact", dev, float(x), float(d))
            return out

        return surface._solve(run, 2.0 * float(_explicit.largest_w(sums.h_host, sums.r_host, float(x0.max()))),
                              e_hi, unloading, extrapolate, M)

    return surface._impact(V1, M, unloading, extrapolate, solve)

