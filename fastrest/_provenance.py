"""What every file fastrest exports records about its origin (the exporters, the tables' grids)."""
from ._version import __version__

__all__ = ["REFERENCE", "provenance"]

REFERENCE = ("Jackson R.L., Green I., Marghitu D.B. (2010) Nonlinear Dyn. 60:217-229, "
             "doi:10.1007/s11071-009-9591-z")


def provenance():
    """What every exported file records about its origin."""
    return {"fastrest_version": __version__, "references": REFERENCE,
            "source": "fastrest, Python package: the JGM model by its direct solver (fastrest.direct)"}
