"""ContactLaw.force and ContactLaw.dissipated_energy with a given contact state: one rule for what
is a history of the law, messages that name the state, read-only states without a recompile."""
import math

import numpy as np
import pytest

import fastrest
from fastrest import force_law
from fastrest.force_law import contact_force, dissipated_energy

LAW = fastrest.contact_law(0.005, 0.33, w_max=100.0)

NOT_A_HISTORY = {
    "nan": [math.nan] * 4,
    "past the law's w_max": [150.0, 1.0, 1.0, 1.0],
    "negative w_max": [-1.0, 0.0, 0.0, 0.0],
    "infinite w_max": [math.inf, 1.0, 1.0, 1.0],
    "nan P*(w_max)": [10.0, math.nan, 0.0, 0.0],
}


@pytest.mark.parametrize("row", NOT_A_HISTORY.values(), ids=NOT_A_HISTORY.keys())
def test_force_and_dissipated_energy_refuse_the_same_states(row):
    """The message names the state and the law's w_max (100), not the interference (5.0) or 425."""
    for call in (lambda st: LAW.force(5.0, st), LAW.dissipated_energy):
        state = np.array(row)
        with pytest.raises(ValueError) as err:
            call(state)
        msg = str(err.value)
        assert msg.startswith("state = [") and "w_max = 100.0" in msg
        assert "interference" not in msg and "425" not in msg
        np.testing.assert_array_equal(state, np.array(row))  # not changed by a refused call


def test_kernel_takes_a_negative_w_max_as_no_history():
    """contact_force gives NaN (and loses the state) where ContactLaw refuses; it was a new contact."""
    state = np.array([-1.0, 0.0, 0.0, 0.0])
    assert math.isnan(contact_force(LAW.data, state, 5.0))
    assert np.isnan(state).all()
    assert math.isnan(dissipated_energy(LAW.data, np.array([-1.0, 0.0, 0.0, 0.0])))


def test_valid_history_continues():
    state = LAW.new_state()
    first = LAW.force([10.0, 5.0], state)
    again = LAW.force(10.0, state)  # reloading to the maximum: the same force
    assert again == first[0] and state[0] == 10.0


def test_read_only_state_refused_by_force_before_running():
    state = LAW.new_state()
    state.flags.writeable = False
    before = len(force_law._force_path.signatures)
    with pytest.raises(ValueError, match=r"^state is updated in place .* writeable"):
        LAW.force(5.0, state)
    assert len(force_law._force_path.signatures) == before  # no compile of a read-only signature


def test_read_only_state_dissipated_energy_without_a_new_signature():
    state = LAW.new_state(3)
    for row, w in zip(state, (2.0, 10.0, 50.0)):
        LAW.force([w, 0.0], row)
    expected = LAW.dissipated_energy(state)
    before = len(force_law._dissipated_rows.signatures)
    ro = state.copy()
    ro.flags.writeable = False
    np.testing.assert_array_equal(LAW.dissipated_energy(ro), expected)
    strided = np.repeat(state, 2, axis=0)[::2]  # not contiguous
    np.testing.assert_array_equal(LAW.dissipated_energy(strided), expected)
    assert len(force_law._dissipated_rows.signatures) == before
