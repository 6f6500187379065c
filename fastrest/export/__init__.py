"""fastrest outside Python: files other tools read.

* :mod:`.grid`: a gridded CF-style NetCDF4/HDF5 file (xarray, any NetCDF reader);
* :mod:`.velocity`: per material pair, tables of e against impact speed V (m/s) for DEM codes;
* :mod:`.c_header`: a self-contained C99 header evaluating a scene's curves.

The command line is ``fastrest export {grid,velocity,c}``; every file is written atomically.
"""
__all__ = ["grid", "velocity", "c_header"]
