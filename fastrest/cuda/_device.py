"""fastrest.cuda's plumbing: numba-cuda (or the ImportError naming the gpu extra), data on the
device, argument checks and the one kernel factory; the public names are re-exported by
:mod:`fastrest.cuda`."""
from typing import Any, Callable

import numpy as np

try:
    import numba_cuda  # type: ignore[import-not-found,import-untyped,unused-ignore]  # noqa: F401  (numba's own numba.cuda is deprecated)
    from numba import cuda as _cuda_module
    from numba import float64 as _f8
    from numba.cuda.core import config as _cuda_config  # type: ignore[import-not-found,unused-ignore]
except ImportError as err:  # pragma: no cover - exercised in a subprocess by tests/test_cuda.py
    raise ImportError('fastrest.cuda needs numba-cuda: pip install "fastrest[gpu]" '
                      f"(import failed: {err})") from err

from .. import jit as _frj
from ..curve_data import CurveData
from ..force_law import STATE_SIZE, StackedLaws, check_state_count
from ..forward import ForwardData
from ..scene import SceneData
from ..tables import TableData

cuda: Any = _cuda_module


#: Threads per block of this module's kernels (one point or contact per thread).
THREADS_PER_BLOCK = 256

#: True under Numba's CUDA simulator (``NUMBA_ENABLE_CUDASIM=1`` before numba.cuda was imported).
SIMULATOR = bool(_cuda_config.ENABLE_CUDASIM)

_DATA_TYPES = (CurveData, SceneData, TableData, ForwardData, StackedLaws)



class _SimulatedDeviceArray(np.ndarray):  # type: ignore[type-arg,unused-ignore]
    """A data array "on the device" under the simulator: host memory, marked as copied (used only there)."""


_is_device_array: Callable[[Any], bool]
if SIMULATOR:
    from numba.cuda.simulator.cudadrv.devicearray import is_cuda_ndarray as _is_device_array  # type: ignore[import-not-found,unused-ignore]
else:
    _is_device_array = cuda.is_cuda_array


# --- data on the device -----------------------------------------------------------------------

def to_device(obj: Any, *, stream: Any = 0) -> Any:
    """Copy fastrest data or an array to the GPU.

    Parameters
    ----------
    obj : namedtuple, object with ``.data``, or array_like
        A :class:`~fastrest.jit.CurveData`, :class:`~fastrest.jit.SceneData`,
        :class:`~fastrest.jit.TableData`, contact law data (``ContactLaw.data``, a
        :class:`fastrest.forward.ForwardData`) or :class:`~fastrest.jit.StackedLaws`; or a
        :class:`~fastrest.Curve`, :class:`~fastrest.Scene`, :class:`~fastrest.Table` or
        :class:`~fastrest.ContactLaw` (their ``.data`` is copied); or a NumPy array (speeds V1* (-),
        interferences w (-), material indices, a state array of :data:`fastrest.jit.STATE_SIZE`
        columns ...), copied C-contiguous with its dtype.
    stream : numba.cuda stream, optional
        Stream of the copies (keyword-only; default the default stream).

    Returns
    -------
    namedtuple or device array
        The same namedtuple type with every array field a device array (scalars unchanged): pass
        it to your ``numba.cuda.jit`` kernels and to this module's functions; or the device array.
        Under the simulator the namedtuple's arrays stay in host memory (module docstring).

    Raises
    ------
    TypeError
        ``obj`` is none of the above (the message names its type).

    Examples
    --------
    >>> import numpy as np, fastrest, fastrest.cuda
    >>> d = fastrest.cuda.to_device(fastrest.curve(0.005, 0.33, v_max=100.0))
    >>> type(d).__name__, d.model, d.v_max
    ('CurveData', 0, 100.0)
    >>> fastrest.cuda.to_device(np.array([1.0, 2.0])).copy_to_host()
    array([1., 2.])
    """
    if not isinstance(obj, tuple) and isinstance(getattr(obj, "data", None), _DATA_TYPES):
        obj = obj.data
    if isinstance(obj, _DATA_TYPES):
        return type(obj)(*[_field_to_device(x, stream) for x in obj])
    if isinstance(obj, np.ndarray) or (isinstance(obj, (list, tuple)) and not hasattr(obj, "_fields")):
        a = np.ascontiguousarray(obj)
        if a.dtype.kind not in "biuf":
            raise TypeError(f"to_device: expected a numeric array, got dtype {a.dtype}")
        return cuda.to_device(a, stream=stream)
    if _is_device_array(obj):
        return obj
    raise TypeError("to_device: expected CurveData, SceneData, TableData, ContactLaw data (ForwardData), "
                    f"StackedLaws, a Curve/Scene/Table/ContactLaw or a NumPy array; got {type(obj).__name__}")


def _field_to_device(x, stream):
    if not isinstance(x, np.ndarray):
        return x
    a = np.ascontiguousarray(x)
    if SIMULATOR:
        return a.copy().view(_SimulatedDeviceArray)
    return cuda.to_device(a, stream=stream)


def new_state(n: int, *, stream: Any = 0) -> Any:
    """History rows of ``n`` virgin contacts on the device, for :func:`contact_force`.

    Parameters
    ----------
    n : int
        Number of contacts, >= 0.
    stream : numba.cuda stream, optional
        Stream of the fill (keyword-only).

    Returns
    -------
    device array
        (n, :data:`fastrest.jit.STATE_SIZE`) float64 zeros. Zero a contact's row again when it
        separates for good (a new contact) or after its force was NaN (history lost).

    Raises
    ------
    TypeError
        ``n`` is not an integer.
    ValueError
        ``n`` < 0, or its rows (32 bytes each) larger than the GPU's free memory (the message
        names n and the bytes; under the simulator, more than
        :data:`fastrest.force_law.MAX_CONTACTS` rows), checked before anything is allocated.

    Examples
    --------
    >>> import fastrest.cuda
    >>> fastrest.cuda.new_state(3).shape
    (3, 4)
    """
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)):
        raise TypeError(f"n must be an integer number of contacts, got {type(n).__name__}")
    n = check_state_count(n, _free_device_bytes(), "on the GPU")  # before any allocation
    return cuda.to_device(np.zeros((n, STATE_SIZE)), stream=stream)


def _free_device_bytes() -> int | None:
    """Free memory of the current GPU (bytes); None where it cannot be asked (the simulator)."""
    if SIMULATOR:
        return None
    try:
        return int(cuda.current_context().get_memory_info()[0])
    except Exception:  # no usable GPU: the allocation that follows raises numba-cuda's own error
        return None


# --- argument checks --------------------------------------------------------------------------

def _check_data(data, types, name, what):
    if not isinstance(data, types):
        hint = " (its .data, moved with fastrest.cuda.to_device)" if hasattr(data, "data") else ""
        raise TypeError(f"{name} must be {what} on the device{hint}; got {type(data).__name__}")
    for field, x in zip(data._fields, data):
        host = isinstance(x, np.ndarray) and not (SIMULATOR and isinstance(x, _SimulatedDeviceArray))
        if host:
            raise TypeError(f"{name} holds host arrays ({name}.{field} is a NumPy array): move it to the GPU once "
                            f"with fastrest.cuda.to_device({name})")


def _check_array(x, name, kind="f", ndim=1, n=None):
    """A device array of dtype kind ``kind`` ('f': float64, 'i': any integer) and ``ndim``."""
    if not _is_device_array(x):
        if isinstance(x, np.ndarray):
            raise TypeError(f"{name} must be a device array, got a NumPy array in host memory: copy it with "
                            f"fastrest.cuda.to_device({name}) (or numba.cuda.to_device)")
        raise TypeError(f"{name} must be a device array (numba.cuda.to_device, fastrest.cuda.to_device), "
                        f"got {type(x).__name__}")
    dt = np.dtype(x.dtype)
    if kind == "f" and dt != np.float64:
        raise TypeError(f"{name} must be float64, got {dt}")
    if kind == "i" and (dt.kind not in "iu"):
        raise TypeError(f"{name} must hold integer material indices, got {dt}")
    if len(x.shape) != ndim:
        raise ValueError(f"{name} must be {ndim}-D, got shape {tuple(x.shape)}")
    if n is not None and x.shape[0] != n:
        raise ValueError(f"{name} must have length {n} (that of v1_star or w), got shape {tuple(x.shape)}")
    return x


def _check_out(out, n, stream):
    if out is None:
        return cuda.device_array(n, dtype=np.float64, stream=stream)
    return _check_array(out, "out", "f", 1, n)


def _check_state(state, n):
    _check_array(state, "state", "f", 2)
    if state.shape != (n, STATE_SIZE):
        raise ValueError(f"state must have shape ({n}, {STATE_SIZE}) (one row of STATE_SIZE per contact, "
                         f"fastrest.cuda.new_state), got {tuple(state.shape)}")


def _check_code(unloading):
    if isinstance(unloading, (bool, np.bool_)) or not isinstance(unloading, (int, np.integer)):
        raise TypeError(f"unloading must be an integer model code (fastrest.jit.JCG, ETSION, BRAKE), "
                        f"got {type(unloading).__name__}")
    return int(unloading)


# --- the kernels: one factory --------------------------------------------------------------------

_KERNELS: dict[tuple[str, str], Any] = {}


def _kernel_function(fn, shape):
    """The Python source of a kernel applying jit function ``fn`` once per thread.

    ``shape``: "point" out[i] = fn(data, v[i]); "material" fn(data, v[i], k[i]); "table"
    fn(data, v[i], a[i], b[i]); "table_model" fn(data, v[i], a[i], b[i], code) with one model
    code for all; "contact" out[i] = fn(data, state row i, w[i]) and "stacked" fn(data, k[i],
    state row i, w[i]) update the row (through a thread-local copy: a row of the device array
    passed to a jit function would not run under the simulator, and the copy sits in registers).
    """
    if shape == "point":
        def kernel(data, v, out):
            i = cuda.grid(1)
            if i < out.size:
                out[i] = fn(data, v[i])
    elif shape == "material":
        def kernel(data, v, k, out):  # type: ignore[misc]
            i = cuda.grid(1)
            if i < out.size:
                out[i] = fn(data, v[i], k[i])
    elif shape == "table":
        def kernel(data, v, a, b, out):  # type: ignore[misc]
            i = cuda.grid(1)
            if i < out.size:
                out[i] = fn(data, v[i], a[i], b[i])
    elif shape == "table_model":
        def kernel(data, v, a, b, code, out):  # type: ignore[misc]
            i = cuda.grid(1)
            if i < out.size:
                out[i] = fn(data, v[i], a[i], b[i], code)
    elif shape == "contact":
        def kernel(data, state, w, out):  # type: ignore[misc]
            i = cuda.grid(1)
            if i < out.size:
                row = cuda.local.array(STATE_SIZE, _f8)
                for j in range(STATE_SIZE):
                    row[j] = state[i, j]
                out[i] = fn(data, row, w[i])
                for j in range(STATE_SIZE):
                    state[i, j] = row[j]
    elif shape == "stacked":
        def kernel(data, k, state, w, out):  # type: ignore[misc]
            i = cuda.grid(1)
            if i < out.size:
                row = cuda.local.array(STATE_SIZE, _f8)
                for j in range(STATE_SIZE):
                    row[j] = state[i, j]
                out[i] = fn(data, k[i], row, w[i])
                for j in range(STATE_SIZE):
                    state[i, j] = row[j]
    else:
        raise ValueError(f"unknown kernel shape {shape!r}")
    kernel.__name__ = kernel.__qualname__ = f"fastrest_{fn.__name__}_{shape}"
    return kernel


def _launch(name, shape, n, stream, *args):
    """Launch the kernel of jit function ``fastrest.jit.<name>`` over ``n`` threads (compiled once)."""
    key = (name, shape)
    if key not in _KERNELS:
        _KERNELS[key] = cuda.jit(_kernel_function(getattr(_frj, name), shape))
    if n > 0:
        blocks = (n + THREADS_PER_BLOCK - 1) // THREADS_PER_BLOCK
        _KERNELS[key][blocks, THREADS_PER_BLOCK, stream](*args)


