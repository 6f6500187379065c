"""Moved to :mod:`fastrest._placement` (below the tables, which place grid nodes with it too)."""
from .._placement import JUMP, JUMP_GAP, interior, place_rows, scaled_error

__all__ = ["JUMP_GAP", "JUMP", "scaled_error", "interior", "place_rows"]
