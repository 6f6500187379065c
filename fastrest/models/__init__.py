"""Closed-form comparison models and the paper's empirical fits.

Jackson, Green & Marghitu (2010), "Predicting the coefficient of restitution of impacting
elastic-perfectly plastic spheres", Nonlinear Dyn. 60:217-229, doi:10.1007/s11071-009-9591-z
(JGM below) compare their model with the closed forms of

* Chang & Ling (1992), based on the CEB contact model (Chang, Etsion & Bogy 1987): JGM eq (1);
* Thornton (1997): JGM eq (2);
* Weir & Tallon (2005), which reduces to Johnson's (1985) simplified model for R1 = R: JGM eq (3);
* Wu, Li & Thornton (2003): JGM eqs (39)-(41);

and summarise their own numerical results by the empirical fits (42)-(44) (JCG unloading, eq 35)
and (45) (Etsion unloading, eq 33). This package implements all of them, one module per published
model (:mod:`~fastrest.models.thornton1997`, :mod:`~fastrest.models.weir_tallon2005`,
:mod:`~fastrest.models.chang_ling1992`, :mod:`~fastrest.models.wu2003`,
:mod:`~fastrest.models.jgm_fits`; yield velocities: :mod:`~fastrest.models.yield_velocities`;
:data:`~fastrest.models.MODELS` and :func:`~fastrest.models.evaluate`: :mod:`~fastrest.models.registry`), without depending on the
JGM solver itself.

Conventions
-----------
* Normalised speeds are JGM's ``v1_star = V1 / V_c`` with V_c of JGM eq (28)
  (:attr:`fastrest.Impact.V_c`). Models that were published against their own yield velocity
  V_y (Thornton, Wu et al.) are converted with the ratios V_c / V_y of JGM Table 2
  (:func:`~fastrest.models.yield_velocity_ratio`).
* Every function is vectorised with NumPy broadcasting; a scalar input gives a Python ``float``.
* Invalid input raises :class:`ValueError` naming the parameter and its range: speeds must be
  finite and >= 0, ``0 <= nu < 0.5``, ``eps_y > 0``, dimensional material data finite and > 0.
* :data:`~fastrest.models.MODELS` maps a name to a function of ``(v1_star, eps_y, nu)``, so one can loop over the
  models; :func:`~fastrest.models.evaluate` is the dimensional form, taking an :class:`~fastrest.Impact` and V1 in m/s.
* No model output is clipped to e <= 1 unless the caller asks for it explicitly (only
  :func:`~fastrest.models.weir_tallon` / :func:`~fastrest.models.johnson` offer ``cap=True``). Where a published formula exceeds 1
  (Wu et al. eq 40 near V_c, Weir-Tallon below its unit-e speed) the formula's value is returned.

References
----------
.. [CL] W.R. Chang, F.F. Ling, "Normal impact model of rough surfaces", ASME J. Tribol. 114 (1992)
   439-447.
.. [CEB] W.R. Chang, I. Etsion, D.B. Bogy, "An elastic-plastic model for the contact of rough
   surfaces", ASME J. Tribol. 109 (1987) 257-263.
.. [Th] C. Thornton, "Coefficient of restitution for collinear collisions of elastic-perfectly
   plastic spheres", J. Appl. Mech. 64 (1997) 383-386.
.. [WT] G. Weir, S. Tallon, "The coefficient of restitution for normal incident, low velocity
   particle impacts", Chem. Eng. Sci. 60 (2005) 3637.
.. [J] K.L. Johnson, Contact Mechanics, Cambridge University Press (1985).
.. [Wu] C.Y. Wu, L.Y. Li, C. Thornton, "Rebound behaviour of spheres for plastic impacts",
   Int. J. Impact Eng. 28 (2003) 929-946.
"""
from .chang_ling1992 import ceb_hardness_factor, chang_ling, chang_ling_dimensional
from .jgm_fits import (JGM_FIT_V_MAX, jgm_fit_etsion, jgm_fit_etsion_kernel, jgm_fit_jcg,
                       jgm_fit_jcg_array, jgm_fit_jcg_kernel, jgm_fit_jcg_scalar)
from .registry import MODELS, evaluate
from .thornton1997 import THORNTON_COEFFICIENT, thornton
from .weir_tallon2005 import johnson, weir_tallon, weir_tallon_normalised, weir_tallon_unit_velocity
from .wu2003 import wu, wu_branches, wu_finite_plastic_velocity
from .yield_velocities import yield_velocity, yield_velocity_ratio

__all__ = [
    "MODELS",
    "evaluate",
    "yield_velocity_ratio",
    "yield_velocity",
    "thornton",
    "THORNTON_COEFFICIENT",
    "weir_tallon",
    "weir_tallon_unit_velocity",
    "weir_tallon_normalised",
    "johnson",
    "ceb_hardness_factor",
    "chang_ling",
    "chang_ling_dimensional",
    "wu",
    "wu_finite_plastic_velocity",
    "wu_branches",
    "jgm_fit_jcg",
    "jgm_fit_etsion",
    "jgm_fit_jcg_kernel",
    "jgm_fit_jcg_array",
    "jgm_fit_etsion_kernel",
    "jgm_fit_jcg_scalar",
    "JGM_FIT_V_MAX",
]
