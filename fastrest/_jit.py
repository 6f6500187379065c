"""The one place that sets fastrest's Numba options.

Every compiled kernel of the package is declared with :func:`jit`: on-disk caching always, no
``fastmath`` (it would drop the NaN checks the kernels rely on and change results), inlining and
threads only where a kernel asks for them.
"""
import numba as nb

__all__ = ["jit", "compiled_entry"]


def jit(fn=None, *, inline=False, parallel=False):
    """``numba.njit(cache=True)`` with fastrest's policy; ``inline=True`` inlines the kernel into
    its callers' loops (Numba IR inlining), ``parallel=True`` enables ``prange``."""
    opts = dict(cache=True)
    if inline:
        opts["inline"] = "always"
    if parallel:
        opts["parallel"] = True

    def wrap(f):
        return nb.njit(**opts)(f)

    return wrap if fn is None else wrap(fn)


def compiled_entry(kernel, sig):
    """The compiled C entry point of jit ``kernel`` for the signature ``sig`` (a tuple of Numba
    types), compiling it if needed; the dispatcher itself if Numba does not expose one.

    Calling the entry point skips the dispatcher's type resolution, which for a namedtuple of
    arrays costs microseconds: scalar fast paths called from Python use it. This is the one place
    fastrest reaches into Numba's dispatcher internals (``overloads``, ``entry_point``).
    """
    kernel.compile(sig)
    cres = kernel.overloads.get(tuple(sig))
    return getattr(cres, "entry_point", None) or kernel
