"""fastrest: the Jackson-Green-Marghitu (2010) coefficient of restitution, fast."""
from ._version import __version__
from ._validation import ValidityWarning, ExtrapolationWarning
from .materials import Material, Impact, poisson_factor, critical_velocity_ratios
