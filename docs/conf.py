"""Sphinx configuration of fastrest's documentation (``.ci/docs`` builds it with ``-W``).

The user guide is Markdown (myst-parser). The API reference (``api/index.rst``) has one page per
group of public names (``api/<group>.rst``), each with autosummary tables; autosummary writes one
page per name under ``api/generated/`` (not committed) from the templates in
``_templates/autosummary``, and this file writes one page per public module
(``api/generated/modules``). The public modules are listed once, in
``stability.md`` (between its ``public-modules`` markers); the build fails unless the reference
lists every name of their ``__all__`` exactly once and nothing else, except the names of
:data:`INTERNAL` (exported for fastrest's own modules, command line and tests, documented in the
source, given no page).
"""
import ast
import importlib
import inspect
import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))

import fastrest  # noqa: E402

project = "fastrest"
author = "the fastrest authors"
copyright = "the fastrest authors"
version = release = fastrest.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "examples", "figures/*.md", "Thumbs.db", ".DS_Store"]
templates_path = ["_templates"]
html_static_path = []

# Broken cross-references are errors (with -W): references to fastrest objects must resolve;
# types from other libraries, written in docstrings as text, are not looked up.
nitpicky = True
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|np|numba|nb|scipy|h5py|xarray|xr|dask|distributed|matplotlib|typing|collections|"
               r"os|pathlib|argparse|concurrent|threading|builtins)(\..*)?"),
]
suppress_warnings = ["ref.citation"]   # a module's reference list may hold citations no docstring cites

# MyST: Markdown pages with GitHub-style anchors (``[x](model.md#2-equations-and-...)``).
myst_heading_anchors = 4
myst_enable_extensions = ["dollarmath"]

# autodoc + numpydoc
autodoc_typehints = "none"            # types are in the numpydoc Parameters/Returns sections
autodoc_member_order = "bysource"
autodoc_default_options = {}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks = set()

html_theme = "pydata_sphinx_theme"
html_title = f"fastrest {release}"
html_theme_options = {
    "navbar_align": "left",
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version", "theme-version"],
}
html_show_sourcelink = False

# ---------------------------------------------------------------------------------------------
# fastrest.cuda needs numba-cuda (the `gpu` extra). The reference must not depend on the machine
# that builds it: without numba-cuda the module is imported with numba-cuda mocked (its kernels
# are then never compiled; its docstrings and signatures are plain Python).

try:
    import fastrest.cuda  # noqa: E402,F401
except ImportError:
    from sphinx.ext.autodoc.mock import mock
    with mock(["numba_cuda", "numba.cuda"]):
        import fastrest.cuda  # noqa: E402,F401
    print("fastrest docs: fastrest.cuda imported with numba-cuda mocked (not installed)")

# ---------------------------------------------------------------------------------------------
# The API reference: the public modules (stability.md), their names (api/<group>.rst), checked
# against each other.

API = DOCS / "api"
GENERATED = API / "generated"


def public_modules():
    """Dotted names of the public modules, in the order docs/stability.md lists them."""
    text = (DOCS / "stability.md").read_text(encoding="utf-8")
    m = re.search(r"<!-- public-modules:start -->(.*?)<!-- public-modules:end -->", text, re.S)
    if m is None:
        raise RuntimeError("docs/stability.md: no public-modules markers")
    return list(dict.fromkeys(re.findall(r"`(fastrest(?:\.\w+)*)`", m.group(1))))


PUBLIC = public_modules()

#: Names in the ``__all__`` of a public module that the reference gives no page, with why: helpers
#: that fastrest's own modules, command line and tests share, and the bounds the code checks its
#: inputs against (an input past one is refused with a message giving the bound), which users do
#: not set. They are internal (stability.md); a reference to one renders as plain code.
INTERNAL = {
    "fastrest.forward.forward_values_excess": "documented internal (the rough solvers' onset path)",
    "fastrest.force_law.check_state_count": "the allocation check of ContactLaw.new_state and cuda.new_state",
    "fastrest.force_law.MAX_CONTACTS": "bound of ContactLaw.new_state",
    "fastrest.export.grid.TOL_MIN": "bound of --tol",
    "fastrest.export.grid.MAX_NODES": "bound of the grid's size",
    "fastrest.export.grid.MIN_CHECK_POINTS": "bound of --check-points",
    "fastrest.export.grid.MAX_CHECK_POINTS": "bound of --check-points",
    "fastrest.export.velocity.TOL_MIN": "bound of --tol",
    "fastrest.export.velocity.MAX_ROWS": "bound of a table's rows",
    "fastrest.export.velocity.MAX_PAIRS": "bound of a pairs file",
    "fastrest.export.velocity.MAX_PAIRS_BYTES": "bound of a pairs file",
    "fastrest.export.velocity.pair_from_options": "the command line's options as a Pair",
    "fastrest.export.c_header.MAX_MATERIALS": "bound of --materials",
    "fastrest.figures.MAX_DPI": "bound of --dpi",
    "fastrest.tables.GRID_COUNTS": "bounds of a grid's node counts",
    "fastrest.tables.EPS_Y_AR_BINDS": "where the kernels check a/R = 1 per point",
    "fastrest.tables.PARALLEL_MIN_POINTS": "where the batch kernels start threads",
    "fastrest.tables.error.SAFETY": "the build's margin below tol (docs/tables.md)",
    "fastrest.tables.error.SIGN_CHANGE_FLOOR": "the error metric's floor (docs/tables.md)",
    "fastrest.cuda.THREADS_PER_BLOCK": "launch configuration of the batch kernels",
    "fastrest.cuda.ROUGH_BLOCKS": "launch configuration of rough_impact",
}


def _attr(mod, name):
    """``mod.name``, importing a submodule of that name if it is not an attribute yet."""
    try:
        return getattr(mod, name)
    except AttributeError:
        return importlib.import_module(f"{mod.__name__}.{name}")


def _is_data(obj):
    return not (inspect.ismodule(obj) or inspect.isclass(obj) or callable(obj))


def data_home(modname, name, depth=0):
    """(module, name) where the constant ``modname.name`` is assigned, following ``from x import``."""
    mod = importlib.import_module(modname)
    try:
        tree = ast.parse(inspect.getsource(mod))
    except (OSError, TypeError):
        return modname, name
    for node in tree.body:
        targets = []
        if isinstance(node, ast.Assign):
            for t in node.targets:
                targets += t.elts if isinstance(t, ast.Tuple) else [t]
        elif isinstance(node, ast.AnnAssign):
            targets = [node.target]
        if any(isinstance(t, ast.Name) and t.id == name for t in targets):
            return modname, name
    for node in tree.body:
        if isinstance(node, ast.ImportFrom) and depth < 10:
            for alias in node.names:
                if (alias.asname or alias.name) == name:
                    base = modname if hasattr(mod, "__path__") else modname.rpartition(".")[0]
                    for _ in range(max(node.level - 1, 0)):
                        base = base.rpartition(".")[0]
                    src = ".".join(p for p in (base if node.level else "", node.module or "") if p)
                    return data_home(src, alias.name, depth + 1)
    return modname, name


def _key(modname, name, obj):
    """One key per documented thing: the object for classes and functions, where it is assigned
    for a constant (the same constant re-exported elsewhere is one entry)."""
    return ("data",) + data_home(modname, name) if _is_data(obj) else ("obj", id(obj))


def _split(fullname):
    """(public module, name) of a dotted name, the module the longest public prefix."""
    for mod in sorted(PUBLIC, key=len, reverse=True):
        if fullname.startswith(mod + ".") and "." not in fullname[len(mod) + 1:]:
            return mod, fullname[len(mod) + 1:]
    return None, fullname


def listed_names():
    """Full names of the entries of the autosummary tables of the reference's group pages
    (``api/*.rst``), in order."""
    out = []
    for page in sorted(API.glob("*.rst")):
        out += _listed_in(page)
    return out


def _listed_in(page):
    out, current, in_table = [], None, False
    for line in page.read_text(encoding="utf-8").splitlines():
        m = re.match(r"\.\. currentmodule:: (\S+)", line)
        if m:
            current = m.group(1)
            continue
        if line.startswith(".. autosummary::"):
            in_table = True
            continue
        if in_table:
            if not line.strip() or line.strip().startswith(":"):
                continue
            if not line.startswith(" "):
                in_table = False
                continue
            name = line.strip()
            full = name if name.startswith("fastrest.") else f"{current}.{name}"
            out.append(full)
    return out


def _internal_keys():
    """{key: full name} of the names of :data:`INTERNAL` (each must be in its module's ``__all__``)."""
    keys, problems = {}, []
    for full in INTERNAL:
        modname, name = _split(full)
        if modname is None or name not in importlib.import_module(modname).__all__:
            problems.append(f"{full}: in conf.py's INTERNAL but not in the __all__ of a public module")
            continue
        keys[_key(modname, name, _attr(importlib.import_module(modname), name))] = full
    return keys, problems


def check_reference():
    """Every name of every public ``__all__`` listed once in the tables of api/*.rst, nothing else,
    except the names of :data:`INTERNAL` (listed nowhere); returns {key: listed full name}."""
    internal, problems = _internal_keys()
    homes = {}
    for full in listed_names():
        modname, name = _split(full)
        if modname is None or name not in importlib.import_module(modname).__all__:
            problems.append(f"{full}: listed but not in the __all__ of a public module")
            continue
        obj = _attr(importlib.import_module(modname), name)
        key = _key(modname, name, obj)
        if key in internal:
            problems.append(f"{full}: listed but internal (conf.py's INTERNAL: {internal[key]})")
        if key in homes:
            problems.append(f"{full}: listed twice (also as {homes[key]})")
        homes[key] = full
    for modname in PUBLIC:
        mod = importlib.import_module(modname)
        for name in mod.__all__:
            obj = _attr(mod, name)
            if inspect.ismodule(obj):
                if obj.__name__ not in PUBLIC:
                    problems.append(f"{modname}.{name}: exports module {obj.__name__}, not public (stability.md)")
            elif _key(modname, name, obj) not in homes and _key(modname, name, obj) not in internal:
                problems.append(f"{modname}.{name}: public (stability.md) but in no table of docs/api/*.rst")
    pages = re.findall(r"^   generated/modules/(\S+)$", (API / "index.rst").read_text(encoding="utf-8"), re.M)
    if pages != PUBLIC:
        problems.append(f"api/index.rst's module pages {pages} differ from stability.md's {PUBLIC}")
    if problems:
        raise RuntimeError("the API reference disagrees with the public API:\n  " + "\n  ".join(problems))
    return homes


HOMES = check_reference()

# Templates: plain classes (namedtuples, exceptions) without a members list; numba-compiled
# functions, which autosummary takes for data, documented as functions.
_OBJECTS = {full: _attr(importlib.import_module(_split(full)[0]), _split(full)[1]) for full in HOMES.values()}
autosummary_generate = True
autosummary_context = {
    "plain_classes": sorted(f for f, o in _OBJECTS.items()
                            if inspect.isclass(o) and issubclass(o, (tuple, BaseException))),
    "function_like": sorted(f for f, o in _OBJECTS.items() if not inspect.isclass(o) and callable(o)),
}


def _summary_name(modname, name, obj):
    """Where the reference documents ``modname.name``."""
    return HOMES[_key(modname, name, obj)]


def write_module_pages(app=None):
    """``api/generated/modules/<module>.rst``: the module's docstring and a table of its names."""
    out = GENERATED / "modules"
    out.mkdir(parents=True, exist_ok=True)
    written = set()
    for modname in PUBLIC:
        mod = importlib.import_module(modname)
        lines = [modname, "=" * len(modname), "", f".. automodule:: {modname}", "   :no-members:", ""]
        subs = [_attr(mod, n).__name__ for n in mod.__all__ if inspect.ismodule(_attr(mod, n))]
        names = [(n, _attr(mod, n)) for n in mod.__all__ if not inspect.ismodule(_attr(mod, n))]
        names = [(n, o) for n, o in names if _key(modname, n, o) in HOMES]   # not the INTERNAL ones
        if subs:
            lines += ["Modules: " + ", ".join(f":mod:`{s}`" for s in subs), ""]
        if names:
            lines += [f"Names ``{modname}`` exports for users (each is documented once; a name exported by",
                      "several modules links to its page):", "", ".. autosummary::", "   :nosignatures:", ""]
            for n, o in names:
                full = _summary_name(modname, n, o)
                lines += [f"   {full[len(modname) + 1:]}" if _split(full)[0] == modname else f"   ~{full}"]
            lines += [""]
        text = "\n".join(lines)
        path = out / f"{modname}.rst"
        if not path.exists() or path.read_text() != text:
            path.write_text(text)
        written.add(path.name)
    for stale in out.glob("*.rst"):
        if stale.name not in written:
            stale.unlink()


def constant_docs(app, what, name, obj, options, lines):
    """A constant documented where it is re-exported takes the ``#:`` comment of the module
    that assigns it."""
    if what not in ("data", "attribute") or any(ln.strip() for ln in lines):
        return
    modname, short = _split(name)
    if modname is None:
        return
    from sphinx.pycode import ModuleAnalyzer
    home, home_name = data_home(modname, short)
    try:
        docs = ModuleAnalyzer.for_module(home).find_attr_docs()
    except Exception:
        return
    lines[:] = list(docs.get(("", home_name), []))


def setup(app):
    app.connect("builder-inited", write_module_pages)


# ---------------------------------------------------------------------------------------------
# Cross-references written against the path a user imports (``fastrest.Impact``, ``Table``,
# ``JCG`` inside its own module) resolve to where the object is documented.

def _lookup(path):
    """The object at dotted ``path`` (module attributes, then class attributes), or raise."""
    parts = path.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for p in parts[i:]:
            obj = inspect.getattr_static(obj, p) if inspect.isclass(obj) else getattr(obj, p)
        return obj
    raise LookupError(path)


_DOCUMENTED = {}


def _documented(env):
    """id(object) -> documented full name, for every documented Python object (cached per build)."""
    py = env.get_domain("py")
    key = len(py.objects)
    if _DOCUMENTED.get("key") != key:
        by_id, by_last = {}, {}
        for name, entry in py.objects.items():
            if entry.objtype == "module" or getattr(entry, "aliased", False):
                continue
            try:
                obj = _lookup(name)
            except Exception:
                continue
            if entry.objtype not in ("data", "attribute"):
                by_id.setdefault(id(obj), name)
            by_last.setdefault(name.rsplit(".", 1)[-1], []).append((name, obj))
        _DOCUMENTED.update(key=key, by_id=by_id, by_last=by_last)
    return _DOCUMENTED["by_id"], _DOCUMENTED["by_last"]


def _candidates(target, module, cls):
    out = [target]
    if cls:
        out.append(f"{module}.{cls}.{target}" if module else f"{cls}.{target}")
    if module:
        parts = module.split(".")
        out += [".".join(parts[:i] + [target]) for i in range(len(parts), 0, -1)]
    return out


def resolve_alias(app, env, node, contnode):
    if node.get("refdomain") != "py":
        return None
    from sphinx.util.nodes import make_refnode
    target = node["reftarget"].lstrip("~.")
    by_id, by_last = _documented(env)
    py = env.get_domain("py")
    found_internal = False
    candidates = _candidates(target, node.get("py:module"), node.get("py:class"))
    page = node.get("refdoc", "")
    if page.startswith("api/generated/") and "." not in target:   # a bare name in an object's
        try:                                                        # docstring: its own module's
            home = getattr(_lookup(page.rsplit("/", 1)[-1]), "__module__", None)
        except Exception:
            home = None
        if isinstance(home, str):
            candidates.append(f"{home}.{target}")
    for path in candidates:
        try:
            obj = _lookup(path)
        except Exception:
            continue
        name = by_id.get(id(obj)) if not isinstance(obj, (int, float, str, tuple)) else None
        if name is None:   # a constant: the documented name of that spelling holding that value
            last = path.rsplit(".", 1)[-1]
            for cand, value in by_last.get(last, []):
                try:
                    same = value is obj or bool(value == obj)
                except Exception:
                    same = False
                if same:
                    name = cand
                    break
        if name is None:
            if path.startswith("fastrest."):
                found_internal = True
            continue
        entry = py.objects[name]
        return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id, contnode, name)
    if "." not in target:   # a bare name documented in exactly one place
        named = [n for n, _ in by_last.get(target, [])]
        if len(named) == 1:
            entry = py.objects[named[0]]
            return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id, contnode, named[0])
    if found_internal:      # an internal name of fastrest (not in any __all__): plain text, no link
        return contnode
    return None


def drop_type_docstrings(app, what, name, obj, options, lines):
    """A constant without a ``#:`` comment would show its value's docstring (ndarray's, int's, a
    namedtuple's class): a value's own ``__doc__`` never documents the constant, so drop it."""
    doc = getattr(obj, "__doc__", None)
    if what in ("data", "attribute") and lines and isinstance(doc, str) and doc == getattr(type(obj), "__doc__", None):
        from sphinx.util.docstrings import prepare_docstring
        own = [ln for ln in prepare_docstring(doc) if ln.strip()]
        if own and [ln for ln in lines if ln.strip()][:len(own)] == own:
            lines[:] = []


def module_citations(app, what, name, obj, options, lines):
    """A function citing ``[Wu]_`` defined in a module's docstring: numpydoc renamed the module's
    citations (prefix from the module's name); point the reference at the module page that
    defines it (the module the reference lists the function under, else where it is defined)."""
    if what == "module":
        return
    import hashlib
    from numpydoc.numpydoc import HASH_LEN
    text = "\n".join(lines)
    cited = set(re.findall(r"\[([A-Za-z0-9_.-]+)\]_", text)) - set(re.findall(r"^\s*\.\. \[([^\]]+)\]", text, re.M))
    if not cited:
        return
    homes = [m for m in (_split(name)[0], getattr(obj, "__module__", None)) if m in PUBLIC]
    for c in cited:
        for mod_name in homes:
            mod_doc = sys.modules[mod_name].__doc__ or ""
            if re.search(rf"^\s*\.\. \[{re.escape(c)}\]", mod_doc, re.M):
                prefix = "R" + hashlib.sha256(mod_name.encode("utf8")).hexdigest()[:HASH_LEN]
                lines[:] = [ln.replace(f"[{c}]_", f"[{prefix}-{c}]_") for ln in lines]
                break


_setup_api = setup


def setup(app):  # noqa: F811
    _setup_api(app)
    app.connect("missing-reference", resolve_alias)
    app.connect("autodoc-process-docstring", drop_type_docstrings, priority=400)
    app.connect("autodoc-process-docstring", constant_docs, priority=450)
    app.connect("autodoc-process-docstring", module_citations, priority=600)   # after numpydoc
