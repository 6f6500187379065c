"""The one place that sets fastrest's Numba options.

Every compiled kernel of the package is declared with :func:`jit`: on-disk caching always, no
``fastmath`` (it would drop the NaN checks the kernels rely on and change results), inlining and
threads only where a kernel asks for them.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any, cast
import warnings

import numba as nb
from llvmlite import ir
from numba.core import cgutils, types
from numba.extending import intrinsic

__all__ = ["jit", "compiled_entry", "mul_rn", "is_cuda", "fmul_rn"]


def jit(fn: Callable[..., Any] | None = None, *, inline: bool = False, parallel: bool = False) -> Any:
    """``numba.njit(cache=True)`` with fastrest's policy; ``inline=True`` inlines the kernel into
    its callers' loops (Numba IR inlining), ``parallel=True`` enables ``prange``.

    Where Numba finds no writable cache directory (a read-only install without a writable HOME or
    ``NUMBA_CACHE_DIR``), kernels are compiled without on-disk caching, with one RuntimeWarning
    (:data:`NO_CACHE_WARNING`) per process."""
    # Typed ``Any``: a kernel's types are Numba's, inferred from each call, so mypy treats the
    # compiled dispatchers (and the functions they were made from) as untyped.
    opts: dict[str, Any] = dict(cache=True)
    if inline:
        opts["inline"] = "always"
    if parallel:
        opts["parallel"] = True

    def wrap(f: Callable[..., Any]) -> Any:
        if not _CACHING[0]:
            return nb.njit(**{k: v for k, v in opts.items() if k != "cache"})(f)
        try:
            return nb.njit(**opts)(f)
        except RuntimeError as exc:  # numba.core.caching: "cannot cache function ...: no locator available"
            if "no locator available" not in str(exc):
                raise
            _CACHING[0] = False
            warnings.warn(NO_CACHE_WARNING, RuntimeWarning, stacklevel=2)
            return nb.njit(**{k: v for k, v in opts.items() if k != "cache"})(f)

    return wrap if fn is None else wrap(fn)


#: The one warning of a process where Numba finds no writable cache directory for fastrest.
NO_CACHE_WARNING = ("fastrest: Numba cannot cache compiled kernels here (no writable directory: the package's "
                    "__pycache__, NUMBA_CACHE_DIR and the user cache directory under HOME are all unwritable); "
                    "kernels are compiled again in every process (seconds per function). Set NUMBA_CACHE_DIR "
                    "to a writable directory to cache them.")
#: [False] once a kernel could not be cached: the rest are compiled without caching, warned once.
_CACHING = [True]


def compiled_entry(kernel: Any, sig: tuple[Any, ...]) -> Any:
    """The compiled C entry point of jit ``kernel`` for the signature ``sig`` (a tuple of Numba
    types), compiling it if needed; the dispatcher itself if Numba does not expose one.

    Calling the entry point skips the dispatcher's type resolution, which for a namedtuple of
    arrays costs microseconds: scalar fast paths called from Python use it. This is the one place
    fastrest reaches into Numba's dispatcher internals (``overloads``, ``entry_point``).
    """
    kernel.compile(sig)
    cres = kernel.overloads.get(tuple(sig))
    return getattr(cres, "entry_point", None) or kernel


# --- Two targets: the CPU and CUDA compile the same kernels (docs/architecture.md, "Two targets") ---
# Without fastmath, LLVM on the CPU never fuses a * b + c into one fused multiply-add; CUDA's
# compilers (NVVM, then ptxas) do by default, which changes the last bit. Where a product feeds an
# addition in a kernel, the product is written ``mul_rn(a, b)``: a plain multiply on the CPU (the
# same instruction as ``a * b``) and ``mul.rn.f64`` on CUDA, which neither compiler fuses
# (tests/test_cuda_compile.py checks that no kernel of fastrest.jit leaves a product feeding an
# addition). Explicit fused multiply-adds are ``fastrest.interpolation.fma`` on both targets.

def is_cuda(builder: Any) -> bool:
    """True when an intrinsic's codegen emits code for CUDA (an NVPTX module), False for the CPU."""
    return str(getattr(builder.module, "triple", "")).startswith("nvptx")


def fmul_rn(builder: Any, a: Any, b: Any) -> Any:
    """IR of a * b (doubles) rounded on its own, for intrinsics' codegen: ``fmul`` on the CPU,
    ``llvm.nvvm.mul.rn.d`` (never contracted into a fused multiply-add) on CUDA."""
    if not is_cuda(builder):
        return builder.fmul(a, b)
    dbl = ir.DoubleType()
    fn = cgutils.get_or_insert_function(builder.module, ir.FunctionType(dbl, [dbl, dbl]), "llvm.nvvm.mul.rn.d")
    return builder.call(fn, [a, b])


@intrinsic
def _mul_rn(typingctx: Any, a: Any, b: Any) -> Any:
    if not all(isinstance(x, types.Float) and x.bitwidth == 64 for x in (a, b)):
        return None
    sig = types.float64(types.float64, types.float64)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        return fmul_rn(builder, args[0], args[1])

    return sig, codegen


_mul_rn.__doc__ = """a * b of two float64, rounded on its own: never fused into a following addition, on either
target (jit code only; the CPU instruction is the one ``a * b`` gives)."""
#: The same intrinsic, typed as what jit code calls it with (mypy sees the typing context otherwise).
mul_rn = cast("Callable[[float, float], float]", _mul_rn)

