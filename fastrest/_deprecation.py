"""Deprecations, written once: old names and old call forms keep working for one release and warn.

Every deprecation warns :class:`DeprecationWarning` naming the replacement, attributed to the
caller's line. Four forms:

* :func:`alias` + :func:`module_getattr`: an old module attribute (``fastrest.materials.Impact``,
  ``fastrest.direct.e_star``) resolved by the module's ``__getattr__``. The object is registered by
  whichever module defines it, so a low module that once held a name now defined above it never
  imports upward: the higher module registers the alias (``fastrest.impact`` registers
  ``fastrest.materials.Impact``), and a package's modules are all imported with the package;
* :func:`keyword_only`: options that became keyword-only, still accepted positionally;
* :func:`renamed`: a parameter with a new name, still accepted by its old keyword;
* :func:`warn_deprecated`: anything else (a deprecated method, a compiled function's old
  argument order, warned when it is compiled).

Nothing here imports from fastrest: every module may use it.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar, cast
import functools
import inspect
import warnings

__all__ = ["warn_deprecated", "alias", "module_getattr", "keyword_only", "renamed"]

_F = TypeVar("_F", bound=Callable[..., Any])

#: The release after which deprecated names and forms may go.
REMOVED_IN = "0.4"

# (module, name) -> (function returning the object, the replacement as users should write it)
_ALIASES: dict[tuple[str, str], tuple[Callable[[], Any], str]] = {}


def warn_deprecated(old: str, new: str, stacklevel: int = 3, category: type[Warning] = DeprecationWarning) -> None:
    """Warn that ``old`` is deprecated in favour of ``new`` (both as a user writes them).

    ``stacklevel`` counts from the caller of this function (default 3: the user's call of the
    function that calls this one). ``category``: FutureWarning where no user line can be blamed
    (a warning raised while Numba compiles the user's function is attributed to fastrest's code,
    and Python's default filters show a DeprecationWarning only when it is attributed to __main__).
    """
    warnings.warn(f"{old} is deprecated and will be removed in fastrest {REMOVED_IN}; use {new}",
                  category, stacklevel=stacklevel)


def alias(module: str, name: str, new: str, get: Callable[[], Any]) -> None:
    """Register ``module.name`` (``module`` a dotted module name) as a deprecated alias.

    ``get()`` returns the object (called on each access, so it may be defined later or above);
    ``new`` is the replacement as users should write it (``"fastrest.Impact"``). The module must
    define ``__getattr__ = module_getattr(__name__)``.
    """
    _ALIASES[(module, name)] = (get, new)


def aliases(module: str) -> dict[str, str]:
    """The deprecated names registered for ``module``: {name: replacement}."""
    return {n: new for (m, n), (_, new) in _ALIASES.items() if m == module}


def module_getattr(module: str) -> Callable[[str], Any]:
    """A module ``__getattr__`` resolving the deprecated aliases registered for ``module`` with a
    DeprecationWarning (on attribute access and on ``from module import name``)."""

    def __getattr__(name: str) -> Any:
        entry = _ALIASES.get((module, name))
        if entry is None:
            raise AttributeError(f"module {module!r} has no attribute {name!r}")
        get, new = entry
        warn_deprecated(f"{module}.{name}", new)
        return get()

    __getattr__.__qualname__ = f"{module}.__getattr__"
    return __getattr__


def keyword_only(*names: str, old: Callable[[tuple[Any, ...]], bool] | None = None) -> Callable[[_F], _F]:
    """Decorator: options ``names`` are keyword-only in the decorated function's signature, and a
    call that still passes them positionally (in that order, after the positional parameters) works
    and warns, naming the keyword.

    ``old(args)`` (optional) decides from the positional arguments whether a call is in the old form
    where a positional slot of the new signature held an option before: e.g. ``forward_data(eps_y,
    nu, w_max, unloading)`` became ``forward_data(eps_y, nu, unloading, *, w_max)``; then every
    positional argument from the first of the moved slots on is mapped to ``names`` in order (not
    when one of ``names`` is passed by keyword: that call is in the new form).
    """

    def wrap(f: _F) -> _F:
        params = list(inspect.signature(f).parameters.values())
        pos = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
        n_pos = len(pos)
        missing = [n for n in names if n not in {p.name for p in params if p.kind == p.KEYWORD_ONLY}]
        if missing:
            raise TypeError(f"{f.__qualname__}: {missing} are not keyword-only parameters")
        # where the moved options started in the old signature: after the positional parameters,
        # or (with ``old``) at the first positional parameter that has a default
        first = n_pos if old is None else next(i for i, p in enumerate(pos) if p.default is not p.empty)

        @functools.wraps(f)
        def checked(*args: Any, **kwargs: Any) -> Any:
            if (len(args) > n_pos) if old is None else (
                    len(args) > first and not any(n in kwargs for n in names) and old(args)):
                extra = args[first:]
                order = names if old is None else names + tuple(p.name for p in pos[first:])
                if len(extra) > len(order):
                    raise TypeError(f"{f.__qualname__}() takes at most {first + len(order)} positional "
                                    f"arguments ({len(args)} given)")
                moved = dict(zip(order, extra))
                for k in moved:
                    if k in kwargs:
                        raise TypeError(f"{f.__qualname__}() got multiple values for argument {k!r}")
                opts = [k for k in moved if k in names]
                warn_deprecated(f"passing {', '.join(opts)} of {f.__qualname__}() positionally",
                                " and ".join(f"{k}=..." for k in opts) + " (keyword-only)")
                kwargs.update(moved)
                args = args[:first]
            return f(*args, **kwargs)

        return cast(_F, checked)

    return wrap


def renamed(**names: str) -> Callable[[_F], _F]:
    """Decorator: parameters renamed, given as ``old="new"``; a call that passes one by its old
    keyword works and warns, naming the new keyword (positional calls are not affected)."""

    def wrap(f: _F) -> _F:
        @functools.wraps(f)
        def checked(*args: Any, **kwargs: Any) -> Any:
            for old, new in names.items():
                if old in kwargs:
                    if new in kwargs:
                        raise TypeError(f"{f.__qualname__}() got values for both {old!r} and {new!r}")
                    warn_deprecated(f"the keyword {old}= of {f.__qualname__}()", f"{new}=")
                    kwargs[new] = kwargs.pop(old)
            return f(*args, **kwargs)

        return cast(_F, checked)

    return wrap
