"""The pieces tables share with curves, imported in this one place.

Below V1* = 1.9^1.25 a table answers with the same material-independent closed-form cells as a
curve (``HERTZ_*``, ``hertz_rows``, :mod:`fastrest.cells`); above it both place their V1* nodes the
same way (``jg_nodes``), and both take Python and NumPy scalars through the same fast-path check
(:func:`fastrest.fastpath.fast_scalar`).
"""
from ..cells import HERTZ_BASE, HERTZ_SHIFT, N_HERTZ, hertz_rows, jg_nodes
from ..fastpath import fast_scalar

__all__ = ["HERTZ_BASE", "HERTZ_SHIFT", "N_HERTZ", "hertz_rows", "jg_nodes", "fast_scalar"]
