"""fastrest: the Jackson-Green-Marghitu (2010) coefficient of restitution, fast.

Data flow: :mod:`~fastrest.materials` (material -> critical values, eqs 4-7, 23-28) ->
:mod:`~fastrest.critical` (the same in Numba code) -> :mod:`~fastrest.contact` (normalised JG law,
eqs 8-15) -> :mod:`~fastrest.energy` (W*, w_m*, eqs 22-31) -> :mod:`~fastrest.unloading` (one unit
per unloading model, eqs 32-38) -> :mod:`~fastrest.limits` (where the model ends) -> :mod:`~fastrest.direct` (exact solver) ->
:mod:`~fastrest.curve` and :mod:`~fastrest.tables` (fast paths) -> :mod:`~fastrest.jit` (inside
your own Numba code); :mod:`~fastrest.force_law` (the contact law in the time domain, with
history, for DEM and transient codes). Comparison models: :mod:`~fastrest.models`; rough surfaces:
:mod:`~fastrest.rough`; the paper's figures: :mod:`~fastrest.figures`.
"""
import importlib

from ._version import __version__
from ._validation import ValidityWarning, ExtrapolationWarning
from .materials import Material, Impact, poisson_factor, critical_velocity_ratios
from .contact import P_star, A_star, omega_star_limit
from .energy import W_star, loading_energy
from . import direct
from .curve import Curve, curve, Scene, scene
from .tables import Table, load_table, omega_m_star, e_star, loss_star
from .tables import TableFileError
from .force_law import ContactLaw, contact_law

__all__ = ["__version__", "ValidityWarning", "ExtrapolationWarning", "Material", "Impact",
           "poisson_factor", "critical_velocity_ratios", "P_star", "A_star", "W_star",
           "loading_energy", "omega_star_limit", "direct", "Curve", "curve", "Scene", "scene", "Table", "load_table",
           "omega_m_star", "e_star", "loss_star", "TableFileError", "ContactLaw", "contact_law"]

# Submodules the imports above do not load come on first attribute access (fastrest.models, ...),
# keeping `import fastrest` fast.
_LAZY = ("models", "rough", "figures", "forward", "jit", "cli")


def __getattr__(name):
    if name in _LAZY:
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'fastrest' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
