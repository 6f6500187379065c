"""The cell-polynomial evaluators of fastrest.interpolation with indices outside their rows: NaN,
never a read outside the array (which returned garbage or killed the interpreter)."""
import numba
import numpy as np
import pytest

from fastrest.interpolation import (ROW, cell_polynomial, data_pointer, pointer_cell_polynomial,
                                    row_in_range, row_polynomial)

ROWS = np.random.default_rng(3).uniform(-1.0, 1.0, (4, ROW))
BAD = [4, 5, 1000, 2**40, 2**62, -1, -(2**40), np.int32(-5), np.uint64(2**63), np.int8(4)]


def reference(rows, i, v):
    """The row's polynomial by NumPy (sum c_k u^k), independent of estrin5."""
    u = (v - rows[i, 0]) * rows[i, 1]
    return np.polynomial.polynomial.polyval(u, rows[i, 2:])


@pytest.mark.parametrize("i", range(4))
def test_rows_in_range_evaluate_their_polynomial(i):
    v = 0.3
    np.testing.assert_allclose(cell_polynomial(ROWS, i, v), reference(ROWS, i, v), rtol=1e-13, atol=1e-14)
    u = (v - ROWS[i, 0]) * ROWS[i, 1]
    assert row_polynomial(ROWS, i, u) == cell_polynomial(ROWS, i, v)
    assert pointer_cell_polynomial(ROWS.ravel(), i, v) == cell_polynomial(ROWS, i, v)


@pytest.mark.parametrize("i", BAD, ids=repr)
def test_index_outside_the_rows_is_nan(i):
    assert np.isnan(row_polynomial(ROWS, i, 0.5))
    assert np.isnan(cell_polynomial(ROWS, i, 0.5))
    assert np.isnan(pointer_cell_polynomial(ROWS.ravel(), i, 0.5))


def test_rows_with_too_few_columns_are_nan():
    short = np.ones((4, ROW - 1))
    assert np.isnan(row_polynomial(short, 0, 0.5)) and np.isnan(cell_polynomial(short, 0, 0.5))
    assert np.isnan(pointer_cell_polynomial(np.ones(ROW - 1), 0, 0.5))
    assert np.isnan(cell_polynomial(np.empty((0, ROW)), 0, 0.5))


def test_checked_inside_user_jit_code():
    @numba.njit
    def both(rows, i, v):
        p = data_pointer(rows)  # a pointer has no length: the caller owns the bounds
        return cell_polynomial(rows, i, v), row_in_range(rows, i), row_in_range(p, i)

    value, inside, _ = both(ROWS, 2, 0.3)
    assert inside and value == cell_polynomial(ROWS, 2, 0.3)
    value, inside, pointer_check = both(ROWS, 2**40, 0.3)
    assert np.isnan(value) and not inside and pointer_check
