"""A sweep on Dask runs Numba's kernels on each worker's threads (threads_per_worker), not on
every core of the machine in every worker; the calling thread's setting is left as it was."""
import numba
import pytest

import fastrest
from fastrest import rough
from fastrest.rough import sweeps

STEEL = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
SEEN = []  # Numba's thread count where factory ran (module-level: the in-process worker sees it)


def factory(**spec):
    SEEN.append(numba.get_num_threads())
    return rough.surface_from_params(**spec)


def test_worker_threads_is_none_outside_a_worker():
    assert sweeps.worker_threads() is None


def test_a_task_runs_on_its_workers_threads():
    distributed = pytest.importorskip("distributed")
    SEEN.clear()
    specs = [dict(material=STEEL, R_a=1e-4, gw=dict(eta=1e10, sigma=s, A_n=1e-4)) for s in (20e-9, 50e-9)]
    before = numba.get_num_threads()
    with distributed.LocalCluster(n_workers=1, processes=False, threads_per_worker=1,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        out = rough.sweep(specs, [0.01, 0.1], 0.01, factory=factory, client=client)
        # after a task, the worker's thread has its own setting back
        after_task = client.submit(numba.get_num_threads, pure=False).result()
    local = rough.sweep(specs, [0.01, 0.1], 0.01)
    assert SEEN == [1, 1]
    assert after_task == numba.config.NUMBA_NUM_THREADS
    assert numba.get_num_threads() == before
    assert all(list(a.e) == list(b.e) for a, b in zip(out, local))


def _long_failure(**spec):
    raise ValueError("a very long reason " * 100 + "\nand a second line")


def test_the_sweeps_warning_is_two_short_lines():
    """A failed surface's warning names the first error's first line, cut, and points to .errors
    (which keeps each whole error)."""
    specs = [dict(material=STEEL, R_a=1e-4, gw=dict(eta=1e10, sigma=20e-9, A_n=1e-4))] * 2
    with pytest.warns(RuntimeWarning) as caught:
        out = rough.sweep(specs, 0.1, 0.01, factory=_long_failure)
    text = str(caught[0].message)
    assert len(text.splitlines()) <= 2 and len(text) < 400, text
    assert "2 of 2 surfaces failed" in text and ".errors" in text and "..." in text
    assert str(out.errors[0][1]).endswith("and a second line")
