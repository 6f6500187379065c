"""The warning of a damaged cached table points at the user's line, not at fastrest's internals
(cached_table is wrapped by the keyword-only decorator, which added a frame)."""
import warnings

from fastrest import tables
from fastrest.tables import store
from fastrest.tables.file import TableFileError

GRID = dict(eps_y_min=0.004, eps_y_max=0.006, n_eps_y=6, nu_min=0.3, nu_max=0.35, n_nu=6,
            bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6)


def test_damaged_cache_warning_names_the_callers_line(tmp_path, monkeypatch):
    monkeypatch.setenv("FASTREST_CACHE_DIR", str(tmp_path))
    path = tmp_path / f"{tables.grid_key(tables.normalise_grid(GRID))}.h5"
    path.write_bytes(b"damaged")
    calls = []

    def load(p, tol=None):  # the first read finds the damage; the rebuilt file loads
        calls.append(p)
        if len(calls) == 1:
            raise TableFileError(f"{p}: damaged")
        return "rebuilt"

    monkeypatch.setattr(store, "load_table", load)
    monkeypatch.setattr(store, "build", lambda *a, **k: None)  # the rebuild itself is tested elsewhere
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        assert tables.cached_table(GRID, progress=False) == "rebuilt"
    [w] = [w for w in rec if "rebuilding the cached table" in str(w.message)]
    assert w.category is RuntimeWarning and w.filename == __file__
