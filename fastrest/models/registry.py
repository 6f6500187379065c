"""The comparison models under one calling convention: :data:`MODELS` and :func:`evaluate`."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any
from numpy.typing import ArrayLike, NDArray
if TYPE_CHECKING:
    from ..impact import Impact
import math

import numpy as np

from .._validation import broadcast_named, check_eps_y, check_nu, check_velocity
from .._doc import doc
from ._common import MODEL_DOC, check_impact, check_v_star, finite_out
from .chang_ling1992 import chang_ling, chang_ling_dimensional
from .jgm_fits import jgm_fit_etsion, jgm_fit_jcg
from .thornton1997 import thornton
from .weir_tallon2005 import weir_tallon, weir_tallon_normalised
from .wu2003 import wu

__all__ = ["MODELS", "evaluate"]


def _registry(fn, args):
    """Wrap ``fn`` as ``(v1_star, eps_y, nu) -> e``; ``args`` names the arguments ``fn`` takes."""
    def model(v1_star, eps_y, nu):
        given = {"v1_star": check_v_star(v1_star), "eps_y": check_eps_y(eps_y), "nu": check_nu(nu)}
        shape = broadcast_named(*((a, n) for n, a in given.items()))
        e = fn(*(given[a] for a in args))
        return finite_out(np.broadcast_to(e, shape).copy() if shape else e)

    model.__name__ = model.__qualname__ = fn.__name__
    model.__doc__ = (f"Registry form ``(v1_star, eps_y, nu) -> e`` of :func:`{fn.__name__}`: all three "
                     f"arguments are validated and broadcast, {fn.__name__} receives {', '.join(args)}."
                     "\n\n" + (fn.__doc__ or ""))
    return model


#: Comparison models and fits under one convention: ``MODELS[name](v1_star, eps_y, nu) -> e``,
#: v1_star = V1/V_c with V_c of JGM eq (28), eps_y = Sy/E', nu = Poisson's ratio (all
#: dimensionless). "wu" uses JGM's V_c in eqs (39)-(41) (``scale="jgm"``), "chang_ling" CEB's
#: own critical interference, "weir_tallon" is eq (3) with R1 = R (= Johnson) normalised with
#: m = (4/3) pi rho R^3. The JGM model itself is not included here.
MODELS = {
    "thornton": _registry(thornton, ("v1_star", "nu")),
    "weir_tallon": _registry(weir_tallon_normalised, ("v1_star", "eps_y", "nu")),
    "chang_ling": _registry(chang_ling, ("v1_star", "eps_y", "nu")),
    "wu": _registry(wu, ("v1_star", "eps_y")),
    "jgm_fit_jcg": _registry(jgm_fit_jcg, ("v1_star", "eps_y")),
    "jgm_fit_etsion": _registry(jgm_fit_etsion, ("v1_star", "eps_y")),
}


@doc(MODEL_DOC)
def evaluate(model_name: str, impact: Impact, V1: ArrayLike, *, rho: float | None = None) -> float | NDArray[np.float64]:
    """Coefficient of restitution of a comparison model for an impact at speed V1 (m/s).

    For every model except Weir-Tallon and Chang-Ling this is
    ``MODELS[model_name](V1 / impact.V_c, impact.eps_y, impact.nu)``.

    * ``"chang_ling"``: :func:`~fastrest.models.chang_ling_dimensional` (eq 1 in SI units; equal to the normalised
      form).
    * ``"weir_tallon"``: :func:`~fastrest.models.weir_tallon` with Sy = ``impact.Sy``, E' = ``impact.E_eff``,
      R1 = R = ``impact.R_eff`` and the density of the sphere taken as the mass-equivalent
      rho = 3 m / (4 pi R_eff^3), m = ``impact.mass``. For a sphere on a flat with the mass computed
      from ``sphere.rho`` this is exactly the sphere's density (for JGM Figs 7-8 the alumina
      sphere's, not the flat's density that Tables 3-4 list); for two spheres it keeps eq (3)
      consistent with the reduced mass, and it equals ``MODELS["weir_tallon"]`` at V1/V_c.
      ``rho`` (kg/m^3) overrides it (then R1 = R = R_eff with the given density).

    Parameters
    ----------
    model_name : str
        A key of :data:`MODELS`.
    impact : fastrest.Impact
        The impact (uses V_c (m/s), eps_y (-), nu (-); Weir-Tallon also Sy (Pa), E_eff (Pa), R_eff (m),
        mass (kg)).
    V1 : float or array_like
        Impact speed (m/s), finite and >= 0.
    rho : float, optional
        Density (kg/m^3) for Weir-Tallon only; default mass-equivalent (see above).

    {returns_e_impact}
    ValueError
        An unknown ``model_name``, ``rho`` given for another model than Weir-Tallon, V1 negative or
        not finite, or what the model itself refuses (e.g. V1 = 0 for Weir-Tallon).

    Warns
    -----
    ValidityWarning
        For the fits, the impact's eps_y or V1* outside their fitted range.

    Notes
    -----
    JGM eqs (1), (2), (3), (39)-(41), (42)-(45) through :data:`MODELS`; V_c of JGM eq (28).

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.models import evaluate
    >>> imp = fastrest.Impact(fastrest.Material(E=200e9, nu=0.33, Sy=1.12e9, rho=7800.0), R=0.01)
    >>> evaluate("thornton", imp, 0.001), round(evaluate("thornton", imp, 1.0), 4)
    (1.0, 0.4121)
    """
    if not (isinstance(model_name, str) and model_name in MODELS):
        raise ValueError(f"model_name must be one of {sorted(MODELS)}; got {model_name!r}")
    check_impact(impact)
    if rho is not None and model_name != "weir_tallon":
        raise ValueError("rho (kg/m^3) applies only to model_name='weir_tallon'")
    V1 = check_velocity(V1, "V1", "(m/s)")
    if model_name == "chang_ling":
        return chang_ling_dimensional(impact, V1)
    if model_name == "weir_tallon":
        if rho is None:
            rho = 3.0 * impact.mass / (4.0 * math.pi * impact.R_eff**3)
        return weir_tallon(V1, impact.Sy, impact.E_eff, rho, R=impact.R_eff)
    return MODELS[model_name](V1 / impact.V_c, impact.eps_y, impact.nu)
