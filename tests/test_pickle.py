"""Objects users build pickle: Curve, Scene, Table, ContactLaw, and on a Dask
cluster with process workers."""
import pickle

import numpy as np
import pytest

import fastrest


def _objects():
    return [fastrest.curve(0.005, 0.33, v_max=50.0), fastrest.scene([(0.005, 0.33), (0.003, 0.3)], v_max=50.0),
            fastrest.load_table(), fastrest.contact_law(0.005, 0.33)]


def _evaluate(obj):
    if isinstance(obj, fastrest.Curve):
        return np.array([obj.e(5.0), obj.loss(np.float64(7.0)), obj.omega_m(30.0)])
    if isinstance(obj, fastrest.Scene):
        return obj.e(np.array([5.0, 6.0]), np.array([0, 1]))
    if isinstance(obj, fastrest.Table):
        return np.array([obj.e(5.0, 0.005, 0.33), obj.loss(9.0, 0.004, 0.3)])
    return obj.force([0.5, 3.0, 1.0])


def test_round_trip_gives_identical_numbers():
    for obj in _objects():
        copy = pickle.loads(pickle.dumps(obj))
        assert type(copy) is type(obj)
        assert np.array_equal(_evaluate(copy), _evaluate(obj)), obj


@pytest.mark.slow
def test_dask_process_workers():
    distributed = pytest.importorskip("distributed")
    objs = _objects()
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        got = client.gather([client.submit(_evaluate, o, pure=False) for o in objs])
    for o, g in zip(objs, got):
        assert np.array_equal(g, _evaluate(o))
