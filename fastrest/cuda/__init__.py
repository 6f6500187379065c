"""fastrest on an NVIDIA GPU: data on the device, and batch functions for users who write no kernel.

Every :mod:`fastrest.jit` function that compiles for CUDA is called from a ``numba.cuda.jit``
kernel exactly as from ``numba.njit`` code (the same source; docs/gpu.md lists which compile).
This module adds what such code needs around them, and ready-made kernels:

* :func:`to_device` copies a curve's, scene's, table's or contact law's data (a namedtuple of
  arrays: :class:`~fastrest.jit.CurveData`, :class:`~fastrest.jit.SceneData`,
  :class:`~fastrest.jit.TableData`, ``ContactLaw.data``, :class:`~fastrest.jit.StackedLaws`) to
  the GPU once, as the same namedtuple of device arrays: pass it to your kernels (a namedtuple of
  host arrays would be copied again at every launch). :func:`new_state` allocates the history rows
  of many contacts on the device.
* :func:`e_curve`, :func:`e_material`, :func:`e_table` (and their ``omega_m_``/``loss_``
  variants) evaluate one point per GPU thread on device arrays; :func:`contact_force` and
  :func:`contact_force_stacked` advance many contacts by one time step, each with its own state
  row. Every point outside the data's domain gives NaN, exactly as the jit functions do on the CPU.
* :func:`rough_impact` is ``RoughSurface.impact`` of an explicit rough surface with the sums over
  its summits on the GPU (the heights kept on the device; docs/gpu.md).

Needs numba-cuda (``pip install "fastrest[gpu]"``); ``import fastrest`` never does. Under Numba's
CUDA simulator (``NUMBA_ENABLE_CUDASIM=1``, no GPU) everything here runs, slowly, with the CPU's
numbers: there :func:`to_device` leaves the data's arrays in host memory (the simulator runs the
jit functions as compiled CPU code, which cannot read its simulated device arrays).

Arguments and their checks follow the jit functions' order (data, speed, material, model); arrays
must be 1-D device arrays of one length (float64; material indices any integer type), ``out``
float64 of that length (allocated when not given). A host (NumPy) array where a device array is
expected, a wrong dtype, shape or length raises TypeError or ValueError naming the argument.
"""
from ._device import SIMULATOR, THREADS_PER_BLOCK, new_state, to_device
from ._batch import (contact_force, contact_force_stacked, e_curve, e_material, e_table, loss_curve, loss_material,
                     loss_table, omega_m_curve, omega_m_material, omega_m_table)
from ._rough import ROUGH_BLOCKS, rough_impact

__all__ = ["THREADS_PER_BLOCK", "SIMULATOR", "to_device", "new_state", "omega_m_curve", "e_curve", "loss_curve",
           "omega_m_material", "e_material", "loss_material", "omega_m_table", "e_table", "loss_table",
           "contact_force", "contact_force_stacked", "rough_impact", "ROUGH_BLOCKS"]
