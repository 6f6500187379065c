"""The tables package documents what it exports: every name of its modules'
``__all__`` has a numpydoc docstring (or, for a constant, a ``#:`` comment), and the Examples in
those docstrings run and give what they show."""
import doctest
import importlib
import inspect
import pkgutil
import re

import pytest

import fastrest.tables

MODULES = sorted(m.name for m in pkgutil.iter_modules(fastrest.tables.__path__, "fastrest.tables.")
                 if not m.name.rsplit(".", 1)[1].startswith("_"))


def _sections(doc):
    return set(re.findall(r"^\s*(Parameters|Returns|Raises|Warns|Notes|Examples)\n\s*-{3,}", doc or "", re.M))


@pytest.mark.parametrize("module", ["fastrest.tables"] + MODULES)
def test_exported_names_are_documented(module):
    mod = importlib.import_module(module)
    assert mod.__doc__, module
    source = inspect.getsource(mod)
    for name in mod.__all__:
        obj = getattr(mod, name)
        if inspect.isfunction(obj) or inspect.isclass(obj) or hasattr(obj, "py_func"):
            doc = obj.__doc__
            sections = _sections(doc)
            assert "Examples" in sections, (module, name, "no Examples")
            fn = getattr(obj, "py_func", obj)
            if inspect.isfunction(fn) and [p for p in inspect.signature(fn).parameters]:
                assert "Parameters" in sections, (module, name, "no Parameters")
        elif inspect.ismodule(obj):
            continue
        else:   # a constant: a #: comment where it is defined (in this module or where it comes from)
            home = source if re.search(rf"^{name}\b.* = ", source, re.M) else "".join(
                inspect.getsource(importlib.import_module(m)) for m in MODULES)
            assert re.search(rf"^#:.*\n(#:.*\n)*{name}\b.* = ", home, re.M), (module, name, "no #: comment")


@pytest.mark.parametrize("module", ["fastrest.tables"] + MODULES)
def test_examples_run(module):
    mod = importlib.import_module(module)
    finder = doctest.DocTestFinder()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    for test in finder.find(mod, module, globs=vars(mod).copy()):
        runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{result.failed} failing examples in {module}"
