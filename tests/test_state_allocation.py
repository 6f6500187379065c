"""History rows of many contacts are sized before anything is allocated: a ValueError naming n
and the bytes, not a MemoryError (host: ContactLaw.new_state; GPU: fastrest.cuda.new_state)."""
import importlib.util
import os
import subprocess
import sys
import textwrap

import pytest

import fastrest
from fastrest.force_law import MAX_CONTACTS, STATE_SIZE, check_state_count

LAW = fastrest.contact_law(0.005, 0.33, w_max=30.0)


def test_host_rows_past_the_cap_name_n_and_bytes():
    with pytest.raises(ValueError) as err:
        LAW.new_state(10**12)
    assert "n = 1000000000000" in str(err.value) and str(10**12 * STATE_SIZE * 8) + " bytes" in str(err.value)
    assert check_state_count(MAX_CONTACTS) == MAX_CONTACTS  # the cap itself is allowed (not allocated here)
    assert LAW.new_state(3.0).shape == (3, STATE_SIZE)


def test_device_check_uses_the_free_bytes():
    """The check fastrest.cuda.new_state runs with the GPU's free memory (importable without numba-cuda)."""
    assert check_state_count(2 * MAX_CONTACTS, 2**40, "on the GPU") == 2 * MAX_CONTACTS  # no host cap there
    with pytest.raises(ValueError, match=r"^n = 1000 contacts need 32000 bytes .* more than the 31999 bytes free on the GPU"):
        check_state_count(1000, 31999, "on the GPU")


@pytest.mark.parametrize("n, kind", [(-1, ValueError), (2.5, ValueError), (float("nan"), ValueError),
                                     (None, TypeError), ("3", TypeError)])
def test_bad_counts(n, kind):
    with pytest.raises(kind, match="n"):
        check_state_count(n)


@pytest.mark.cuda
@pytest.mark.skipif(importlib.util.find_spec("numba_cuda") is None,
                    reason='numba-cuda is not installed (pip install "fastrest[gpu]")')
def test_cuda_new_state_refuses_before_allocating():
    """Under the CUDA simulator (a child process): a ValueError naming n and the bytes."""
    code = textwrap.dedent("""
        import fastrest.cuda as fc
        try:
            fc.new_state(10**12)
        except ValueError as exc:
            assert "n = 1000000000000" in str(exc) and "32000000000000 bytes" in str(exc), exc
        else:
            raise SystemExit("no ValueError")
        assert fc.new_state(3).shape == (3, 4)
        print("OK")
    """)
    env = dict(os.environ, NUMBA_ENABLE_CUDASIM="1")
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0 and r.stdout.strip().endswith("OK"), r.stderr[-3000:]
