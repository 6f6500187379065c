"""The :class:`Table` object: a loaded multi-material table and its checked Python API."""
from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, NoReturn

import numba as nb
import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import unloading as _unloading
from .._deprecation import keyword_only, warn_deprecated
from .._doc import doc, fill, paragraphs
from .._jit import compiled_entry
from .._threads import run_parallel
from .._validation import (EPS_Y_VALIDATED, NU_VALIDATED, OMEGA_M_STAR_MAX, broadcast_inputs, check_eps_y,
                           check_nu, check_velocity, shaped, warn_if_outside_validated)
from ..limits import raise_out_of_range, speed_limit
from ..fastpath import fast_scalar, table_omega, table_quantity
from .accuracy import measure
from .data import table_data
from ._rectilinear import _check_n_check, _check_tol, dataset
from .kernel import table_array, table_array_parallel, table_value_kernel
from .w_star import energy_data, loading_energy_array, W_STAR_OMEGA_MAX

if TYPE_CHECKING:
    import xarray

    from .generation import GeneratedTable

__all__ = ["Table", "PARALLEL_MIN_POINTS"]

#: Batches at least this large use all cores (the threads' start-up costs ~10 us).
PARALLEL_MIN_POINTS = 20000
_EPS_LO, _EPS_HI = EPS_Y_VALIDATED
_NU_LO, _NU_HI = NU_VALIDATED

#: The Warns section of every evaluation of a table (and of the default table's functions) and
#: the parameters of its energies, written once (fastrest._doc).
TABLE_DOC = paragraphs(
    warns_table="""
        Warns
        -----
        ValidityWarning
            Only for tables wider than the paper's validated range, at points outside it.
        """,
    params_energy="""
        Parameters
        ----------
        w : float or array_like
            Normalised interference w* = omega/omega_c (-), 0 <= w* <= 425.
        eps_y : float or array_like
            Sy/E' (-), JGM eq (11); within the table's range.
        nu : float or array_like
            Poisson's ratio (-); within the table's range.
        """,
)

_QUANTITY_PARAMS = """
        Parameters
        ----------
        v1_star : float or array_like
            Normalised impact speed V1* = V1/V_c (-), JGM eq (30); >= 0 (V1* <= 1: elastic).
        eps_y : float or array_like
            Sy/E' (-), JGM eq (11); within the table's range (``grid["eps_y_min"]`` to ``grid["eps_y_max"]``).
        nu : float or array_like
            Poisson's ratio of the yielding material (-); within the table's range.{extra}

        Returns
        -------
        float or ndarray
            {returns}, broadcast over the inputs (a float for scalar inputs).

        Raises
        ------
        TypeError
            An input is not a real number (string, bool, None, complex).
        ValueError
            v1_star negative or NaN; eps_y or nu outside the table (the message gives its range);
            V1* past the model's limit w_m* = 425 (JGM section 3.3) or a/R = 1{raises}.

        {{warns_table}}

        Notes
        -----
        {notes} Interpolated (error: ``attrs["measured_error"]``); V1* <= 1.9^1.25 is the closed
        form (Hertz loading, JGM eq 19).

        Examples
        --------
        >>> import fastrest
        >>> t = fastrest.load_table()
        >>> {example}
        """
def _quantity_doc(summary, **fields):
    """The docstring of a quantity method: ``summary``, then :data:`_QUANTITY_PARAMS` formatted with
    ``fields``, its shared paragraphs (``{{name}}`` there) filled from :data:`TABLE_DOC`."""
    return summary + "\n" + fill(_QUANTITY_PARAMS.format(**fields), TABLE_DOC)


_DEPRECATED_DOC = """Deprecated name of :meth:`{new}` (the name :class:`~fastrest.Curve` and
        :class:`~fastrest.Scene` use); warns :class:`DeprecationWarning`.

        Parameters
        ----------
        v1_star, eps_y, nu, unloading
            As :meth:`{new}`.

        Returns
        -------
        float or ndarray
            As :meth:`{new}`.

        Examples
        --------
        >>> import warnings
        >>> import fastrest
        >>> t = fastrest.load_table()
        >>> with warnings.catch_warnings():
        ...     warnings.simplefilter("ignore", DeprecationWarning)
        ...     t.{old}(5.0, 0.005, 0.33) == t.{new}(5.0, 0.005, 0.33)
        True
        """

_UNLOADING = """
        unloading : {"jcg", "etsion", "brake"}
            Unloading model: Jackson-Chusoipin-Green, JGM eq (35) (default), Etsion et al., eq (33),
            or Brake (2015)."""


class Table:
    """A multi-material restitution table, evaluated at any (V1*, eps_y, nu) inside its grid.

    Built by :func:`~fastrest.tables.load_table` (a file), :func:`~fastrest.tables.build` or
    ``Table(generate(grid))``. Methods broadcast over their inputs; each point may have its own
    material. A Table pickles (its compiled entry point is rebuilt on first use).

    Parameters
    ----------
    gen : GeneratedTable
        The table's arrays (:func:`~fastrest.tables.generate`, or read from a file).
    attrs : dict, optional
        The file's root attributes (provenance, ``measured_error``).
    path : str, optional
        The file it was read from.

    Attributes
    ----------
    data : TableData
        Numba-friendly data for :mod:`fastrest.jit` (``fastrest.jit.e_table(data, v, eps_y, nu, JCG)``).
    energy : EnergyData
        The stored W* for :meth:`W_star` (a namedtuple of arrays).
    grid : dict
        Generation parameters (:func:`~fastrest.tables.normalise_grid`).
    cell_edges : ndarray
        (ncell, 2) V1* at the start and end of every interpolation cell above 1.9^1.25.
    block_cells : tuple of (int, int)
        (first cell, end cell) of every block of cells with its own material axis.
    attrs : dict
        The file's root attributes.
    path : str or None

    Examples
    --------
    >>> import fastrest
    >>> t = fastrest.load_table()
    >>> round(t.e(5.0, 0.005, 0.33), 6)
    0.898078
    """

    def __init__(self, gen: GeneratedTable, attrs: dict[str, Any] | None = None,
                 path: str | os.PathLike[str] | None = None) -> None:
        self.data = table_data(gen)
        self.energy = energy_data(gen)
        self.grid = gen.grid
        self.cell_edges = gen.edges
        self.block_cells = tuple((b.cell0, b.cell1) for b in gen.blocks)
        self._entry = None
        self._codes: dict[str, int] = {}  # unloading name -> code, for the names this table holds
        self.attrs = attrs or {}
        self.path = path

    # the compiled entry point does not pickle: dropped, rebuilt on the first scalar call (and
    # the model-code cache refilled)
    def __getstate__(self) -> dict[str, Any]:
        state = self.__dict__.copy()
        state["_entry"] = None
        state["_codes"] = {}
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        self.__dict__.setdefault("_codes", {})  # pickled before this cache existed

    def __repr__(self) -> str:
        g = self.grid
        return (f"Table(eps_y=[{g['eps_y_min']}, {g['eps_y_max']}] x {g['n_eps_y']}, "
                f"nu=[{g['nu_min']}, {g['nu_max']}] x {g['n_nu']}, cells={self.data.cells.shape[0]}, "
                f"path={self.path!r})")

    def _scalar(self, q: int, v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]:
        """One point from Python floats: the kernel's compiled entry point (~1 us instead of ~30 us
        through the array machinery); anything unusual (NaN result, outside the validated range,
        which warns) goes the checked array way. Python floats are tested first, inline (a
        function call per argument costs ~10 % of the whole call)."""
        if type(v1_star) is float and type(eps_y) is float and type(nu) is float:
            v, e, n = v1_star, eps_y, nu
        else:
            v, e, n = fast_scalar(v1_star), fast_scalar(eps_y), fast_scalar(nu)
            if v is None or e is None or n is None:
                return self._eval(q, v1_star, eps_y, nu)
        if _EPS_LO <= e <= _EPS_HI and _NU_LO <= n <= _NU_HI:
            entry = self._entry
            if entry is None:
                entry = self._entry = compiled_entry(table_value_kernel, (nb.typeof(self.data), nb.int64,
                                                                          nb.float64, nb.float64, nb.float64))
            r = entry(self.data, q, v, e, n)
            if r == r:
                return r
            return self._eval(q, v, e, n)
        return self._eval(q, v1_star, eps_y, nu)

    def _eval(self, q: int, v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]:
        (v, e, n), shape = broadcast_inputs((v1_star, "v1_star"), (eps_y, "eps_y"), (nu, "nu"))
        out = np.empty(v.size)
        if v.size == 0:
            return shaped(out, shape)
        if v.size >= PARALLEL_MIN_POINTS:
            run_parallel(table_array_parallel, table_array, self.data, q, v, e, n, out)
        else:
            table_array(self.data, q, v, e, n, out)
        bad = np.isnan(out)
        if bad.any():
            self._raise(v[bad], e[bad], n[bad])
        warn_if_outside_validated(e, n)
        return shaped(out, shape)

    def _check_material(self, e: NDArray[np.float64], n: NDArray[np.float64]) -> None:
        check_eps_y(e)
        check_nu(n)
        d = self.data
        for name, x, lo, hi in (("eps_y", e, d.eps_lo, d.eps_hi), ("nu", n, d.nu_lo, d.nu_hi)):
            out = (x < lo) | (x > hi)
            if out.any():
                raise ValueError(f"{name} = {float(x[out][0])!r} is outside this table's range [{lo}, {hi}] "
                                 "(use fastrest.direct, fastrest.curve, or build a wider table)")

    def _raise(self, v: NDArray[np.float64], e: NDArray[np.float64], n: NDArray[np.float64]) -> NoReturn:
        check_velocity(v, "v1_star")
        self._check_material(e, n)
        v0, e0, n0 = float(v[0]), float(e[0]), float(n[0])
        lim = speed_limit(e0, n0)
        if v0 > lim:
            raise_out_of_range(v, e, n, False,
                               hint="fastrest.direct and fastrest.curve accept extrapolate=True")
        raise ValueError(f"v1_star = {v0!r} at eps_y = {e0!r}, nu = {n0!r} lies within the interpolation "
                         f"error of the w_m* = {OMEGA_M_STAR_MAX:g} limit (V1* = {lim:.10g}) or outside "
                         "this table's coverage")

    def _model_code(self, unloading: str) -> int:
        try:  # a name seen before: one dict look-up (the scalar path's cost is mostly such calls)
            return self._codes[unloading]
        except (KeyError, TypeError):
            pass
        code = _unloading.get(unloading).code
        if not 2 + 2 * code < self.data.n_quantities:
            raise ValueError(f"this table holds no values for unloading={unloading!r} (it was built for "
                             f"{_unloading.NAMES[:(self.data.n_quantities - 1) // 2]}); rebuild it with "
                             "`fastrest build` or use fastrest.curve / fastrest.direct")
        if type(unloading) is str:
            self._codes[unloading] = code
        return code

    # a float in gives a float out (fastrest.fastpath.TableOmega, TableQuantity)
    @table_omega
    def omega_m(self, v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]:
        return self._scalar(0, v1_star, eps_y, nu)

    @table_quantity
    def e(self, v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike,
          unloading: str = "jcg") -> float | NDArray[np.float64]:
        return self._scalar(1 + 2 * self._model_code(unloading), v1_star, eps_y, nu)

    @table_quantity
    def loss(self, v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike,
             unloading: str = "jcg") -> float | NDArray[np.float64]:
        return self._scalar(2 + 2 * self._model_code(unloading), v1_star, eps_y, nu)

    omega_m.__doc__ = _quantity_doc("Maximum interference w_m* = omega_m/omega_c (-), JGM eq (29).",
        extra="", returns="w_m* (-)", raises="", notes="w_m* solves F(w_m*) = V1*^2 (JGM eq 29).",
        example="round(t.omega_m(5.0, 0.005, 0.33), 6)\n        3.673079")
    e.__doc__ = _quantity_doc("Coefficient of restitution e = V2/V1 (-), JGM eqs (16), (38).",
        extra=_UNLOADING, returns="e (-)", raises="; an unknown unloading model, or one the table does not hold",
        notes="e from w_m* and the unloading model's residual interference (JGM eq 38).",
        example='round(t.e(5.0, 0.005, 0.33, "etsion"), 6)\n        0.925853')
    loss.__doc__ = _quantity_doc("Dissipated fraction of the impact energy 1 - e^2 (-).",
        extra=_UNLOADING, returns="1 - e^2 (-)", raises="; an unknown unloading model, or one the table does not hold",
        notes="1 - e^2 tabulated as such (accurate where e is close to 1).",
        example="round(t.loss(5.0, 0.005, 0.33), 6)\n        0.193456")

    # The names before Curve's and Scene's were adopted: deprecated, warn, and call the new ones.
    def omega_m_star(self, v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]:
        warn_deprecated("Table.omega_m_star", "Table.omega_m")
        return self.omega_m(v1_star, eps_y, nu)

    def e_star(self, v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike,
               unloading: str = "jcg") -> float | NDArray[np.float64]:
        warn_deprecated("Table.e_star", "Table.e")
        return self.e(v1_star, eps_y, nu, unloading)

    def loss_star(self, v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike,
                  unloading: str = "jcg") -> float | NDArray[np.float64]:
        warn_deprecated("Table.loss_star", "Table.loss")
        return self.loss(v1_star, eps_y, nu, unloading)

    omega_m_star.__doc__ = _DEPRECATED_DOC.format(old="omega_m_star", new="omega_m")
    e_star.__doc__ = _DEPRECATED_DOC.format(old="e_star", new="e")
    loss_star.__doc__ = _DEPRECATED_DOC.format(old="loss_star", new="loss")

    @doc(TABLE_DOC)
    def loading_energy(self, w: ArrayLike, eps_y: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]:
        """Loading energy F(w*) = 1 - (W_ep)*(w*) to interference w* over U_c (-), from the table.

        F(w*) is V1*^2 of the impact whose maximum interference is w* (JGM eqs 19, 25, 29); U_c is
        the critical energy (JGM eq 24). The same quantity as :func:`fastrest.loading_energy`
        (exact quadrature, one material at a time), interpolated from the table's stored W*.

        {params_energy}

        Returns
        -------
        float or ndarray
            F (-), broadcast over the inputs (a float for scalar inputs).

        Raises
        ------
        TypeError
            An input is not a real number.
        ValueError
            w negative, NaN or above 425 (the stored grid's end); eps_y or nu outside the table;
            w past (or, for interpolation, too close to) the end of the law, a/R = 1, which only
            tables past eps_y = 0.0102 reach.

        {warns_table}

        Notes
        -----
        w* <= 1.9: the closed form w*^2.5 (Hertz, JGM eq 19), exact. Above: 10-point Lagrange
        interpolation of ln F in ln w* and across the stored eps_y and nu nodes
        (:mod:`fastrest.tables.w_star`). Against the quadrature, over the shipped table's domain
        (edges included), the relative error is about 1e-10 (tests/test_tables.py measures it).

        Examples
        --------
        >>> import fastrest
        >>> t = fastrest.load_table()
        >>> f = t.loading_energy(100.0, 0.005, 0.33)
        >>> abs(f / fastrest.loading_energy(100.0, 0.005, 0.33) - 1) < 1e-7
        True
        """
        (x, e, n), shape = broadcast_inputs((w, "w"), (eps_y, "eps_y"), (nu, "nu"))
        out = np.empty(x.size)
        loading_energy_array(self.energy, x, e, n, out)
        bad = np.isnan(out)
        if bad.any():
            self._raise_energy(x[bad], e[bad], n[bad])
        warn_if_outside_validated(e, n)
        return shaped(out, shape)

    @doc(TABLE_DOC)
    def W_star(self, w: ArrayLike, eps_y: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]:
        """Normalised elasto-plastic loading energy (W_ep)* = 1 - F(w*) (-), JGM eq (25), from the table.

        (W_ep)* = -(5/2) int_1^w* P* dz: zero at w* = 1, negative above. The same quantity as
        :func:`fastrest.W_star` (exact quadrature), interpolated from the table's stored W*; see
        :meth:`loading_energy` for the parameters, errors and method.

        {params_energy}

        Returns
        -------
        float or ndarray
            (W_ep)* (-), broadcast over the inputs.

        Raises
        ------
        TypeError
            An input is not a real number.
        ValueError
            As :meth:`loading_energy`, naming the parameter.

        {warns_table}

        Notes
        -----
        1 - :meth:`loading_energy` (JGM eq 25 with eq 19 below w* = 1.9).

        Examples
        --------
        >>> import fastrest
        >>> t = fastrest.load_table()
        >>> float(t.W_star(1.0, 0.005, 0.33))
        0.0
        """
        return 1.0 - self.loading_energy(w, eps_y, nu)

    def _raise_energy(self, w: NDArray[np.float64], e: NDArray[np.float64], n: NDArray[np.float64]) -> NoReturn:
        bad = ~((w >= 0.0) & (w <= W_STAR_OMEGA_MAX))
        if bad.any():
            raise ValueError(f"w (normalised interference omega/omega_c) must be in [0, {W_STAR_OMEGA_MAX:g}] "
                             f"(the table's W* grid); got {float(w[bad][0])!r}")
        self._check_material(e, n)
        raise ValueError(f"w = {float(w[0])!r} at eps_y = {float(e[0])!r}, nu = {float(n[0])!r} lies past, or within "
                         "the interpolation stencil of, the end of the JG law (a/R = 1); use fastrest.W_star")

    @keyword_only("tol", "n_check")
    def to_xarray(self, *, tol: float = 1e-3, n_check: int = 20000) -> xarray.Dataset:
        """This table on a rectilinear (v1_star, eps_y, nu) grid as an :class:`xarray.Dataset`.

        Parameters
        ----------
        tol : float
            Error asked of linear interpolation on the grid (relative to the direct solver).
        n_check : int
            Random points the error is measured on.

        Returns
        -------
        xarray.Dataset
            Variables ``omega_m``, ``e_<model>``, ``loss_<model>`` (NaN past w_m* = 425), nodes placed
            so that linear interpolation (``ds.e_jcg.interp(...)``) is within ``tol`` of the direct
            solver where it can be; the measured errors are in the attributes.

        Raises
        ------
        ImportError
            xarray is not installed (``pip install fastrest[xarray]``).
        ValueError
            ``tol`` or ``n_check`` out of range (see :mod:`fastrest.export.grid`).

        Examples
        --------
        >>> import fastrest
        >>> ds = fastrest.load_table().to_xarray(tol=1e-2, n_check=200)  # doctest: +SKIP
        """
        tol = _check_tol(tol)
        return dataset(self, tol=tol, n_check=_check_n_check(n_check, allow_zero=True))

    def measure_error(self, points: tuple[ArrayLike, ArrayLike, ArrayLike] | None = None) -> dict[str, dict[str, Any]]:
        """Worst error of every quantity against the direct solver.

        Parameters
        ----------
        points : (ndarray, ndarray, ndarray), optional
            (v1_star, eps_y, nu); default: the adversarial sample of
            :func:`fastrest.tables.error.adversarial_points` (edges, corners, every cell boundary
            +/- 1 ulp, the last cell before each material's limit).

        Returns
        -------
        dict
            Quantity name -> its worst error and where (:func:`fastrest.tables.error.measure`).

        Examples
        --------
        >>> import numpy as np, fastrest
        >>> pts = (np.array([5.0]), np.array([0.005]), np.array([0.33]))
        >>> fastrest.load_table().measure_error(pts)["e_jcg"]["max_error"] < 1e-9
        True
        """
        return measure(self, points)
