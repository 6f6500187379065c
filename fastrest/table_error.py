"""Deprecated: the former home of :mod:`fastrest.tables.error`; use that module.

Importing this module, or any name from it, warns (DeprecationWarning); the names are the objects
of :mod:`fastrest.tables.error`. Nothing in fastrest imports it.
"""
from ._deprecation import alias, module_getattr, warn_deprecated
from .tables import error as _error

__all__ = []

warn_deprecated("the module fastrest.table_error", "fastrest.tables.error")

__getattr__ = module_getattr(__name__)
for _name in ("AccuracyWarning", "DEFAULT_TOL", "SAFETY", "SIGN_CHANGE_FLOOR", "adversarial_points", "sample_points",
              "measure", "meets", "worst", "build_to_tolerance", "warn_if_inaccurate"):
    alias(__name__, _name, f"fastrest.tables.error.{_name}", (lambda n: lambda: getattr(_error, n))(_name))
del _name
