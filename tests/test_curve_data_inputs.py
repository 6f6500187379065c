"""build_curve_data validates its inputs as fastrest.curve does: the same exception and message."""
import numpy as np
import pytest

import fastrest
from fastrest.curve_data import build_curve_data

BAD = [
    ((0.0, 0.3), {}),
    ((-0.005, 0.3), {}),
    ((float("nan"), 0.3), {}),
    ((float("inf"), 0.3), {}),
    ((None, 0.3), {}),
    (("0.005", 0.3), {}),
    ((np.array([0.005, 0.006]), 0.3), {}),
    ((0.005, -2**63), {}),
    ((0.005, 0.5), {}),
    ((0.005, None), {}),
    ((0.005, 0.3), {"v_max": -1.0}),
    ((0.005, 0.3), {"v_max": float("nan")}),
    ((0.005, 0.3), {"v_max": "20"}),
    ((0.005, 0.3), {"extrapolate": 1}),
    ((0.005, 0.3), {"et_ratio": None}),
    ((0.005, 0.3), {"et_ratio": 1.5}),
    ((0.005, 0.3, "no-such-model"), {}),
]


@pytest.mark.parametrize("args, kwargs", BAD, ids=repr)
def test_refuses_what_curve_refuses_with_the_same_message(args, kwargs):
    with pytest.raises((TypeError, ValueError)) as via_curve:
        fastrest.curve(*args, **kwargs)
    with pytest.raises(via_curve.type) as direct:
        build_curve_data(*args, **kwargs)
    assert str(direct.value) == str(via_curve.value)


@pytest.mark.parametrize("bits, kind", [(0, ValueError), (13, ValueError), (2.5, ValueError), (None, TypeError),
                                        (True, TypeError)])
def test_bits_per_octave_checked(bits, kind):
    with pytest.raises(kind, match="bits_per_octave"):
        build_curve_data(0.005, 0.3, v_max=20.0, bits_per_octave=bits)


def test_valid_inputs_still_build_the_curve_of_fastrest_curve():
    d = build_curve_data(0.005, 0.33, "jcg", v_max=20.0)
    c = fastrest.curve(0.005, 0.33, v_max=20.0).data
    assert d.v_max == c.v_max and d.base == c.base
    np.testing.assert_array_equal(d.e_rows, c.e_rows)
