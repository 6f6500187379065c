"""Former home of :mod:`fastrest.tables.error` (kept so that ``fastrest.table_error`` imports keep
working): the same objects."""
from .tables.error import (DEFAULT_TOL, SAFETY, SIGN_CHANGE_FLOOR, AccuracyWarning, adversarial_points,
                           build_to_tolerance, measure, meets, sample_points, warn_if_inaccurate, worst)

__all__ = ["AccuracyWarning", "DEFAULT_TOL", "SAFETY", "SIGN_CHANGE_FLOOR", "adversarial_points", "sample_points",
           "measure", "meets", "worst", "build_to_tolerance", "warn_if_inaccurate"]
