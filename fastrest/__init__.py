"""fastrest: the Jackson-Green-Marghitu (2010) coefficient of restitution, fast.

Jackson, Green & Marghitu (2010), Nonlinear Dyn. 60:217-229 (JGM): the coefficient of
restitution of an elastic-perfectly plastic sphere on a flat. docs/model.md maps every equation to
the function that implements it.

Data flow: :mod:`~fastrest.materials` (a material, C(nu) of eq 5) -> :mod:`~fastrest.critical`
(effective properties and critical values, eqs 4-7, 11, 23-28, in Numba code) ->
:mod:`~fastrest.contact` (normalised JG law, eqs 8-15) -> :mod:`~fastrest.energy` (W*, w_m*, eqs
22-31) -> :mod:`~fastrest.unloading` (one unit per unloading model, eqs 32-38) ->
:mod:`~fastrest.limits` (where the model ends) -> :mod:`~fastrest.direct` (exact solver) ->
:mod:`~fastrest.impact` (:class:`Impact`: two bodies in SI units on top of the solver) and
:mod:`~fastrest.curve`, :mod:`~fastrest.tables` (fast paths) -> :mod:`~fastrest.jit` (inside your
own Numba code); :mod:`~fastrest.forward` (interference -> energies, for multi-asperity codes) and
:mod:`~fastrest.force_law` (the contact law in the time domain, with history, for DEM and
transient codes). Comparison models: :mod:`~fastrest.models`; rough surfaces:
:mod:`~fastrest.rough`; the paper's figures: :mod:`~fastrest.figures`.

Examples
--------
JGM Table 1 (steel sphere, R = 10 mm, m = 32.7 g, on a rigid flat) at 1 m/s, then the same in
normalised form (V1* = V1/V_c, eps_y = Sy/E'):

>>> import fastrest
>>> steel = fastrest.Material(E=200e9, nu=0.33, Sy=1.12e9)
>>> impact = fastrest.Impact(steel, R=0.01, mass=0.0327)
>>> round(impact.e(1.0), 4)
0.7501
>>> round(fastrest.direct.e_exact(10.0, 0.005, 0.33), 6)
0.828733
"""
import importlib

from ._version import __version__
from ._deprecation import alias as _alias, module_getattr as _module_getattr
from ._validation import ValidityWarning, ExtrapolationWarning
from .materials import Material, poisson_factor, critical_velocity_ratios
from .impact import Impact
from .repeated import RepeatedImpacts
from .contact import P_star, A_star, omega_star_limit
from .energy import W_star, loading_energy
from .limits import Limit, limit
from . import direct
from .curve import Curve, curve
from .scene import Scene, scene
from .tables import Table, load_table, omega_m_star, e_star, loss_star
from .tables import TableFileError
from . import tables
from .force_law import ContactLaw, contact_law

__all__ = ["__version__", "ValidityWarning", "ExtrapolationWarning", "Material", "Impact", "RepeatedImpacts",
           "poisson_factor", "critical_velocity_ratios", "P_star", "A_star", "W_star",
           "loading_energy", "omega_star_limit", "Limit", "limit", "direct", "Curve", "curve", "Scene", "scene", "Table", "load_table",
           "omega_m_star", "e_star", "loss_star", "TableFileError", "ContactLaw", "contact_law"]

# Submodules the imports above do not load come on first attribute access (fastrest.models, ...),
# keeping `import fastrest` fast.
_LAZY = ("models", "rough", "figures", "forward", "jit", "cli")


# Deprecated names (DeprecationWarning naming the replacement): fastrest.table_error, the module
# that became fastrest.tables.error.
_alias(__name__, "table_error", "fastrest.tables.error", lambda: tables.error)
_deprecated = _module_getattr(__name__)


def __getattr__(name):
    if name in _LAZY:
        return importlib.import_module(f".{name}", __name__)
    return _deprecated(name)


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
