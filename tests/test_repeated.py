"""Successive impacts on one spot (fastrest.repeated) against an independent time-stepping of the
contact law that keeps the contact's history from one impact to the next; and Impact.e's choice
of NaN past the model's end (past_end), the other side of a sweep that runs past it."""
import math

import numpy as np
import pytest

import fastrest
from fastrest.force_law import hertz_contact_time
from fastrest.jit import contact_force

STEEL = fastrest.Material(200e9, 0.3, 1e9, rho=7850.0)
IMP = fastrest.Impact(STEEL, 0.01)


def stepped(law, speeds, steps=3000):
    """e and w_max* of each impact at the normalised speeds, velocity Verlet on
    d^2w/dtau^2 = -(5/4) P*(w) (tau = t V_c/omega_c), one history row throughout; each impact starts
    where the last left the contact (w = w_res*, force 0) at its speed."""
    state = law.new_state()
    out = []
    for v1 in speeds:
        w, v = max(state[2], 0.0), v1
        dt = hertz_contact_time(v1) / steps
        a = -1.25 * contact_force(law.data, state, w)
        top = w
        for _ in range(100 * steps):
            v += 0.5 * dt * a
            w += dt * v
            p = contact_force(law.data, state, w)
            a = -1.25 * p
            v += 0.5 * dt * a
            top = max(top, w)
            if v < 0.0 and p == 0.0:
                break
        else:
            raise AssertionError("the contact did not end")
        out.append((-v / v1, top))
    return np.array(out)


@pytest.mark.parametrize("unloading", ["jcg", "brake"])
def test_repeated_impacts_match_time_stepping_with_history(unloading):
    V = np.array([0.5, 0.5, 0.5, 0.2, 0.8, 0.5])
    r = IMP.repeated_impacts(V, unloading=unloading)
    law = fastrest.contact_law(IMP.eps_y, IMP.nu, unloading)
    ref = stepped(law, IMP.v1_star(V))
    # the scheme's O(dt^2) error at 3000 steps per Hertz time: ~1e-6 in e
    np.testing.assert_allclose(r.e, ref[:, 0], rtol=0, atol=2e-5)
    np.testing.assert_allclose(r.max_interference / IMP.omega_c, ref[:, 1], rtol=2e-5)
    assert list(r.plastic) == [True, True, True, False, True, False]
    assert r.e[3] == 1.0 and r.e[5] == 1.0  # on the reloading curve
    assert r.residual_interference[3] == r.residual_interference[2]


def test_the_first_impact_is_the_single_one_and_e_rises_to_shakedown():
    r = IMP.repeated_impacts(0.5, 40)
    assert r.e[0] == IMP.e(0.5)
    assert r.max_interference[0] == IMP.max_interference(0.5)
    assert r.residual_interference[0] == IMP.residual(0.5)[0]
    assert np.all(np.diff(r.e) > 0) and np.all(np.diff(r.residual_interference) > 0)
    k = r.shakedown(0.995)
    assert k is not None and r.e[k - 1] >= 0.995 > r.e[k - 2]


def test_energy_balance_of_each_impact():
    """Independent of the solver: the virgin work up to each new maximum is the sum of what the
    impacts put in beyond what each reloading curve gave back (m/2 units: speeds squared)."""
    V = np.array([0.3, 0.6, 0.45, 1.0])
    r = IMP.repeated_impacts(V)
    given_back = 0.0
    total_in = 0.0
    for k, v in enumerate(V):
        total_in += v * v - given_back if r.plastic[k] else 0.0
        given_back = (r.e[k] * v) ** 2 if r.plastic[k] else given_back
        if r.plastic[k]:
            # a single impact reaching this maximum took total_in
            assert IMP.max_interference(math.sqrt(total_in)) == pytest.approx(r.max_interference[k], rel=1e-12)


@pytest.mark.parametrize("args,kwargs,match", [
    ((0.5,), {}, "n .* is required"),
    ((0.5, 0), {}, r"n must be a whole number in \[1, 1000000\]"),
    ((0.5, 2.5), {}, "whole number"),
    (([0.5, 0.6], 3), {}, "n is for one speed"),
    (([0.5, -1.0],), {}, "impact 2 has -1.0"),
    (([[0.5]],), {}, "1-D"),
    ((1e4, 2), {}, "impact 1 at V1 = 10000.0 m/s"),
])
def test_bad_input_is_named(args, kwargs, match):
    with pytest.raises(ValueError, match=match):
        IMP.repeated_impacts(*args, **kwargs)
    with pytest.raises(TypeError):
        IMP.repeated_impacts("fast", 2)
    with pytest.raises(ValueError, match="e_min"):
        IMP.repeated_impacts(0.5, 2).shakedown(1.5)


def test_past_end_nan_keeps_the_valid_speeds():
    """Impact.e(..., past_end="nan"): NaN past V_max, the others as alone, one warning naming the
    first refused speed and the end; the default still refuses; bad input is still an error."""
    top = IMP.V_max()
    V = [0.5, top * 1.5, 2.0, top * 3.0]
    with pytest.warns(RuntimeWarning, match=r"2 of 4 speeds are past the model's end .*the first, V1 = "
                      + repr(top * 1.5).replace(".", r"\.")) as caught:
        e = IMP.e(V, past_end="nan")
    assert len(caught) == 1
    assert np.isnan(e[[1, 3]]).all() and list(e[[0, 2]]) == list(IMP.e([0.5, 2.0]))
    with pytest.raises(ValueError, match="425"):
        IMP.e(V)
    with pytest.raises(ValueError, match="V1"):
        IMP.e([0.5, -1.0], past_end="nan")
    with pytest.raises(ValueError, match="past_end must be 'raise' or 'nan'"):
        IMP.e(0.5, past_end="clip")
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert IMP.e(0.5, past_end="nan") == IMP.e(0.5)  # no warning when every speed is covered
