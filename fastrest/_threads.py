"""Fastrest's parallel kernels called from several Python threads.

Numba's ``workqueue`` threading layer (what Numba uses when neither OpenMP nor TBB is available)
is not thread-safe: two Python threads entering parallel kernels at once abort the process
("Concurrent access has been detected"). Under that layer (or before Numba has chosen one),
:func:`run_parallel` lets one thread at a time into a parallel kernel; the others run the serial
kernel when there is one (table batches, rough-surface sweeps), else wait. Under ``omp`` and
``tbb``, which are thread-safe, nothing is serialised. Results are the same either way (the
parallel kernels sum in fixed blocks).
"""
import threading

import numba

__all__ = ["run_parallel", "layer_is_thread_safe"]

_LOCK = threading.RLock()
_SAFE_LAYERS = ("omp", "tbb")


def layer_is_thread_safe():
    """True once Numba runs a thread-safe layer (omp, tbb); False for workqueue or not yet chosen."""
    try:
        return numba.threading_layer() in _SAFE_LAYERS  # type: ignore[attr-defined]  # not in numba's __all__
    except ValueError:  # no parallel kernel has run yet: the layer is not chosen
        return False


def run_parallel(parallel, serial, *args):
    """``parallel(*args)``, unless another thread is inside a parallel kernel under a layer that
    is not thread-safe: then ``serial(*args)`` if ``serial`` is given, else wait for it."""
    if layer_is_thread_safe():
        return parallel(*args)
    if _LOCK.acquire(blocking=serial is None):
        try:
            return parallel(*args)
        finally:
            _LOCK.release()
    return serial(*args)
