"""The docstrings of the core modules: their Examples run (doctest), and every public name has them.

A failing example prints the doctest report (captured stdout) with the expected and actual output.
"""
import doctest
import importlib
import inspect

import pytest

#: Modules whose docstring examples are tested; the other modules keep their own doctest list.
MODULES = ["fastrest", "fastrest._validation", "fastrest.contact", "fastrest.energy", "fastrest.direct",
           "fastrest.critical", "fastrest.limits", "fastrest.forward", "fastrest.force_law", "fastrest.jit",
           "fastrest.materials", "fastrest.impact", "fastrest.unloading", "fastrest.unloading.elastic"]

FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


#: Their examples compile user loops inlining the table kernel (~10 s each, cold): `slow`.
SLOW_MODULES = {"fastrest.jit"}


@pytest.mark.parametrize("name", [pytest.param(m, marks=pytest.mark.slow) if m in SLOW_MODULES else m
                                  for m in MODULES])
def test_examples_run(name):
    mod = importlib.import_module(name)
    result = doctest.testmod(mod, optionflags=FLAGS, report=True)
    assert result.attempted > 0, f"{name} has no examples"
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples of {name} failed (see stdout)"


def _public_objects():
    """(label, object) for each callable in ``__all__`` of MODULES defined in one of them, and the
    public methods of those classes."""
    for name in MODULES:
        if name == "fastrest._validation":
            continue  # internal helpers; its two warnings are checked as fastrest's
        mod = importlib.import_module(name)
        for n in getattr(mod, "__all__", []):
            obj = getattr(mod, n)
            if inspect.ismodule(obj) or not callable(obj) or getattr(obj, "__module__", None) not in MODULES:
                continue  # constants (documented by #: comments), and re-exports of other modules
            yield f"{name}.{n}", obj
            if inspect.isclass(obj) and not issubclass(obj, tuple):
                for k, v in vars(obj).items():
                    if not k.startswith("_") and callable(getattr(v, "__func__", v)):
                        yield f"{name}.{n}.{k}", getattr(v, "__func__", v)


def test_public_names_have_numpydoc_sections():
    missing = []
    for label, obj in _public_objects():
        doc = inspect.getdoc(getattr(obj, "py_func", obj)) or ""
        need = ["Parameters", "Examples"] if inspect.isclass(obj) else ["Parameters", "Returns", "Examples"]
        if not inspect.isclass(obj) and list(inspect.signature(getattr(obj, "py_func", obj)).parameters) == ["self"]:
            need.remove("Parameters")  # a method without arguments
        gaps = [s for s in need if f"{s}\n" + "-" * len(s) not in doc]
        if gaps:
            missing.append(f"{label}: {', '.join(gaps)}")
    assert not missing, "numpydoc sections missing:\n" + "\n".join(missing)
