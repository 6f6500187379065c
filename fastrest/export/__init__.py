"""fastrest outside Python: files other tools read.

* :mod:`.grid`: a gridded CF-style NetCDF4/HDF5 file (xarray, any NetCDF reader);
* :mod:`.velocity`: per material pair, tables of e against impact speed V (m/s) for DEM codes;
* :mod:`.c_header`: a self-contained C99 header evaluating a scene's curves.

The command line is ``fastrest export {grid,velocity,c}``; every file is written atomically.
"""
__all__ = ["grid", "velocity", "c_header"]


def __getattr__(name: str) -> object:
    """The submodules of ``__all__`` on first use (``fastrest.export.grid`` after a plain
    ``import fastrest.export``), without importing the others."""
    if name in __all__:
        import importlib
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
