"""The default-table fast API: :func:`omega_m_star`, :func:`e_star`, :func:`loss_star` (also
``fastrest.omega_m_star`` etc.), each point with its own material, from the shipped table."""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray
from .._doc import fill
from ..fastpath import table_omega, table_quantity
from .store import _load_table, load_table  # noqa: F401 (load_table: the docstrings)
from .table import TABLE_DOC

__all__ = ["omega_m_star", "e_star", "loss_star"]

_TOP_DOC = """{what}, from the shipped default table.

    Each point may have its own material. Interpolates the table of :func:`load_table` (accuracy:
    ``load_table().attrs["measured_error"]``, or ``fastrest info``; for the shipped table <= 1e-9 relative,
    except the Etsion 1 - e^2 near its zero crossing, see docs/domain.md). For one material
    :func:`fastrest.curve` is faster and more accurate; :mod:`fastrest.direct` is the exact solver.

    Parameters
    ----------
    v1_star : float or array_like
        Normalised impact speed V1* = V1/V_c (-), JGM eq (30); >= 0. V1* <= 1 is elastic (e = 1).
    eps_y : float or array_like
        Sy/E' (-), JGM eq (11); within the table's range (shipped: 0.0005-0.01).
    nu : float or array_like
        Poisson's ratio of the yielding material (-); within the table's range (shipped: 0.2-0.45).{extra}

    Returns
    -------
    float or ndarray
        {returns}, broadcast over the three inputs (a float for scalar inputs).

    Raises
    ------
    TypeError
        An input is not a real number (string, bool, None, complex).
    ValueError
        v1_star negative or NaN; eps_y or nu outside the table; V1* past the model's limit
        w_m* = 425 (JGM section 3.3; the message gives that V1* for the material). No
        ``extrapolate`` here: use :mod:`fastrest.direct` or :func:`fastrest.curve`.

    {{warns_table}}

    Notes
    -----
    The table holds the exact model: {notes}

    Examples
    --------
    >>> import fastrest
    >>> {example}
    """

_UNLOADING_DOC = """
    unloading : {"jcg", "etsion", "brake"}
        Unloading model: Jackson-Chusoipin-Green, JGM eq (35) (default), Etsion et al., eq (33), or Brake (2015)."""


def _top_doc(**fields):
    """:data:`_TOP_DOC` formatted with ``fields``, its shared paragraphs (``{{name}}`` there) filled
    from :data:`~fastrest.tables.table.TABLE_DOC`."""
    return fill(_TOP_DOC.format(**fields), TABLE_DOC)


# a float in gives a float out (fastrest.fastpath.TableOmega, TableQuantity)
@table_omega
def omega_m_star(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]:
    return _load_table().omega_m(v1_star, eps_y, nu)


@table_quantity
def e_star(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, unloading: str = "jcg") -> float | NDArray[np.float64]:
    return _load_table().e(v1_star, eps_y, nu, unloading)


@table_quantity
def loss_star(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, unloading: str = "jcg") -> float | NDArray[np.float64]:
    return _load_table().loss(v1_star, eps_y, nu, unloading)


omega_m_star.__doc__ = _top_doc(
    what="Normalised maximum interference w_m* = omega_m/omega_c (JGM eq 29)", extra="", returns="w_m* (-)",
    notes="w_m* solves the energy balance F(w_m*) = V1*^2, JGM eq (29) (eq 31 in closed form below 1.9^1.25).",
    example="round(fastrest.omega_m_star(5.0, 0.005, 0.33), 6)\n    3.673079")
e_star.__doc__ = _top_doc(
    what="Coefficient of restitution e = V2/V1 (JGM eqs 16, 38)", extra=_UNLOADING_DOC, returns="e (-)",
    notes="e = V2/V1 from w_m* and the unloading model's residual interference, JGM eq (38).",
    example="round(fastrest.e_star(5.0, 0.005, 0.33), 6)\n    0.898078")
loss_star.__doc__ = _top_doc(
    what="Dissipated fraction of the impact energy 1 - e^2", extra=_UNLOADING_DOC, returns="1 - e^2 (-)",
    notes="1 - e^2 (JGM eq 38), tabulated as such: accurate where e is close to 1.",
    example="round(fastrest.loss_star(5.0, 0.005, 0.33), 6)\n    0.193456")
