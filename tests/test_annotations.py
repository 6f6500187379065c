"""The public API is annotated: every Python-layer function, method and property named in a
public module's ``__all__`` has a type for each parameter and for its return (mypy checks the
types themselves: ``.ci/types``). Numba kernels are exempt: their types are Numba's, inferred per
call, and mypy sees them as ``Any`` (fastrest._jit.jit).
"""
import importlib
import inspect
import pkgutil

import fastrest

SKIP_MODULES = {"fastrest.table_error"}  # a deprecated alias of fastrest.tables.error


def _public_modules():
    names = ["fastrest"] + [m.name for m in pkgutil.walk_packages(fastrest.__path__, "fastrest.")]
    for name in names:
        if name in SKIP_MODULES or any(part.startswith("_") for part in name.split(".")):
            continue
        if name == "fastrest.cuda":
            continue  # optional GPU module: needs numba-cuda
        yield importlib.import_module(name)


def _is_kernel(obj):
    return hasattr(obj, "py_func") and hasattr(obj, "signatures")  # a Numba dispatcher


def _functions():
    """(label, function) for each Python-layer callable users call."""
    seen = set()
    for mod in _public_modules():
        for name in getattr(mod, "__all__", []):
            obj = getattr(mod, name, None)
            if getattr(obj, "__module__", None) != mod.__name__ or _is_kernel(obj):
                continue  # re-exports (checked where defined), constants, kernels
            items = []
            if inspect.isfunction(obj):
                items.append((f"{mod.__name__}.{name}", obj))
            elif inspect.isclass(obj) and not issubclass(obj, (tuple, BaseException)):
                for k, v in vars(obj).items():
                    if k.startswith("_") and k != "__init__":
                        continue
                    if isinstance(v, property):
                        v = v.fget
                    v = getattr(v, "__func__", v)
                    if inspect.isfunction(v) and not _is_kernel(v):
                        items.append((f"{mod.__name__}.{name}.{k}", v))
            for label, f in items:
                f = inspect.unwrap(f)
                if f not in seen:
                    seen.add(f)
                    yield label, f


def test_public_api_is_annotated():
    missing = []
    for label, f in _functions():
        ann = f.__annotations__
        params = [p for p in inspect.signature(f).parameters.values()
                  if p.name not in ("self", "cls")]
        gaps = [p.name for p in params if p.name not in ann]
        if "return" not in ann:
            gaps.append("return")
        if gaps:
            missing.append(f"{label}: {', '.join(gaps)}")
    assert not missing, "not annotated:\n" + "\n".join(missing)


def test_the_package_is_marked_typed():
    import pathlib
    assert (pathlib.Path(fastrest.__file__).parent / "py.typed").is_file()
