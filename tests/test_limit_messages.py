"""A speed past a curve's or a scene's end is refused with a message that says where the end is
and whether it is the model's limit (w_m* = 425), not only "build it with a larger v_max"."""
import re
import warnings

import pytest

import fastrest


def _limit_in(msg):
    m = re.search(r"V1\* = ([0-9.e+]+)", msg)
    assert m, msg
    return float(m[1])


def test_default_curve_says_its_end_is_the_model_limit():
    c = fastrest.curve(0.005, 0.33)
    with pytest.raises(ValueError) as exc:
        c.e(2000.0)
    msg = str(exc.value)
    assert "larger v_max" not in msg
    assert "the model's limit (w_m* = 425)" in msg and "eps_y = 0.005, nu = 0.33" in msg
    assert f"v_max = {c.v_max!r}" in msg and "extrapolate=True" in msg
    # and indeed no curve goes further without extrapolate
    with pytest.raises(ValueError):
        fastrest.curve(0.005, 0.33, v_max=c.v_max * (1 + 1e-9))


def test_short_curve_names_how_far_it_may_go():
    c = fastrest.curve(0.005, 0.33, v_max=50.0)
    with pytest.raises(ValueError, match="larger v_max, up to V1\\* = ") as exc:
        c.e(60.0)
    top = _limit_in(str(exc.value))
    assert top == pytest.approx(fastrest.limit(0.005, 0.33).v1_star, rel=1e-9)
    assert fastrest.curve(0.005, 0.33, v_max=top * (1 - 1e-9)).e(60.0) > 0  # that far is allowed


def test_extrapolated_curve_at_the_model_end():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        c = fastrest.curve(0.005, 0.33, extrapolate=True)
    with pytest.raises(ValueError, match="the end of the model extrapolated past the model's limit") as exc:
        c.e(1e5)
    assert _limit_in(str(exc.value)) == pytest.approx(fastrest.limit(0.005, 0.33).v1_star, rel=1e-9)


def test_scene_names_the_material_and_its_limit():
    s = fastrest.scene([(0.005, 0.33), (0.003, 0.3)], v_max=40.0)
    with pytest.raises(ValueError, match="of material 1: build the scene with a larger v_max, up to V1\\* = ") as exc:
        s.e(45.0, 1)
    assert _limit_in(str(exc.value)) == pytest.approx(fastrest.limit(0.003, 0.3).v1_star, rel=1e-9)
    full = fastrest.scene([(0.005, 0.33)])
    with pytest.raises(ValueError, match="that is the model's limit \\(w_m\\* = 425\\)"):
        full.e(1e5, 0)
