"""The one place that sets fastrest's Numba options.

Every compiled kernel of the package is declared with :func:`jit`: on-disk caching always, no
``fastmath`` (it would drop the NaN checks the kernels rely on and change results), inlining and
threads only where a kernel asks for them.
"""
import numba as nb

__all__ = ["jit"]


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
