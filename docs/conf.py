"""Sphinx configuration of fastrest's documentation (``.ci/docs`` builds it with ``-W``).

The user guide is Markdown (myst-parser); the API reference is generated at build time from the
``__all__`` of every public module (no leading underscore in its dotted name): one page per module
under ``api/generated/`` (not committed), each name documented once, where it is defined, and
listed with a link wherever else it is exported.
"""
import importlib
import inspect
import os
import pkgutil
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
# The API reference, generated from ``__all__``.

#: Modules left out of the reference: compatibility aliases of names documented elsewhere.
# Not public although not underscored (docs/stability.md): a deprecated alias, the command line's
# implementation (its public interface is the commands), and plumbing.
SKIP_MODULES = {"fastrest.table_error", "fastrest.cli", "fastrest.export.cli", "fastrest.fastpath",
                "fastrest.tables.probe", "fastrest.tables.hdf5_read"}

# Modules that need an optional extra (fastrest.cuda: numba-cuda, the `gpu` extra): in the
# reference only where the extra is installed; docs/gpu.md describes them either way.
OPTIONAL_MODULES = {"fastrest.cuda"}

GENERATED = DOCS / "api" / "generated"


def public_modules():
    """Dotted names of the public modules of fastrest that define ``__all__``, sorted."""
    names = ["fastrest"] + [m.name for m in pkgutil.walk_packages(fastrest.__path__, "fastrest.")]
    out = []
    for name in sorted(set(names)):
        if name in SKIP_MODULES or any(part.startswith("_") for part in name.split(".")):
            continue
        try:
            mod = importlib.import_module(name)
        except ImportError as exc:
            if name in OPTIONAL_MODULES:   # its extra is not installed: documented without it
                print(f"fastrest docs: {name} left out of the API reference ({exc})")
                continue
            raise
        if getattr(mod, "__all__", None) is not None:
            out.append(name)
    return out


def _defines(mod, name):
    """Whether module ``mod`` itself defines ``name`` (def, class or assignment in its source)."""
    try:
        src = inspect.getsource(mod)
    except (OSError, TypeError):
        return False
    return re.search(rf"^(def|class)\s+{re.escape(name)}\b|^{re.escape(name)}\b[^=\n]*=", src, re.M) is not None


def _kind(obj):
    if inspect.ismodule(obj):
        return "module"
    if inspect.isclass(obj):
        return "class"
    if callable(obj):
        return "function"
    return "data"


def _key(n, obj):
    """Objects are one entry whatever they are called; constants are one entry per name and value."""
    return id(obj) if _kind(obj) != "data" else (n, repr(obj)[:200])


def canonical_homes(modules):
    """For each exported object, the one (module, name) documenting it: where it is defined (its
    ``__module__`` and ``__name__``, or an assignment in the module's source for a constant), else
    the first, most specific, module exporting it."""
    homes = {}        # _key -> (module, name, defined_here)
    exports = {}      # module -> [(name, obj)]
    for m in modules:
        mod = importlib.import_module(m)
        exports[m] = [(n, getattr(mod, n)) for n in mod.__all__]
    for m in sorted(modules, key=lambda m: (-m.count("."), m)):
        mod = importlib.import_module(m)
        for n, obj in exports[m]:
            kind = _kind(obj)
            if kind == "module":
                continue
            if kind == "data":
                defined_here = _defines(mod, n)
            else:
                defined_here = getattr(obj, "__module__", None) == m and getattr(obj, "__name__", n) == n
            key = _key(n, obj)
            if key not in homes or (defined_here and not homes[key][2]):
                homes[key] = (m, n, defined_here)
    return exports, {k: v[:2] for k, v in homes.items()}


def _summary(obj):
    doc = inspect.getdoc(getattr(obj, "py_func", obj)) or ""
    first = doc.strip().split("\n\n")[0].replace("\n", " ").strip()
    return first


def write_api(app=None):
    """Write ``api/generated/<module>.rst`` for each public module and ``api/generated/modules.rst``."""
    modules = public_modules()
    exports, homes = canonical_homes(modules)
    GENERATED.mkdir(parents=True, exist_ok=True)
    written = set()
    for m in modules:
        lines = [m, "=" * len(m), "", f".. automodule:: {m}", "   :no-members:", ""]
        here, elsewhere, submods = [], [], []
        for n, obj in exports[m]:
            kind = _kind(obj)
            if kind == "module":
                submods.append(obj.__name__)
            elif homes[_key(n, obj)] == (m, n):
                here.append((n, obj, kind))
            else:
                elsewhere.append((n, ".".join(homes[_key(n, obj)])))
        if submods:
            lines += ["Modules exported here: " + ", ".join(f":mod:`{s}`" for s in submods), ""]
        if elsewhere:
            lines += ["Also exported here (documented where they are defined):", ""]
            lines += [f"* :py:obj:`{m}.{n} <{home}>`" for n, home in elsewhere]
            lines += [""]
        for n, obj, kind in here:
            directive = {"class": "autoclass", "function": "autofunction", "data": "autodata"}[kind]
            if kind == "function" and not inspect.isroutine(obj) and not hasattr(obj, "py_func"):
                directive = "autodata"   # a callable instance (a registry entry, ...)
            lines += [f".. {directive}:: {m}.{n}"]
            if kind == "class":
                if not issubclass(obj, (tuple, BaseException)):
                    lines += ["   :members:"]
            lines += [""]
        text = "\n".join(lines)
        path = GENERATED / f"{m}.rst"
        if not path.exists() or path.read_text() != text:
            path.write_text(text)
        written.add(path.name)
    index = ["Modules", "=======", "", ".. toctree::", "   :maxdepth: 1", ""]
    index += [f"   {m}" for m in modules]
    text = "\n".join(index) + "\n"
    path = GENERATED / "modules.rst"
    if not path.exists() or path.read_text() != text:
        path.write_text(text)
    written.add(path.name)
    for stale in GENERATED.glob("*.rst"):
        if stale.name not in written:
            stale.unlink()


def setup(app):
    app.connect("builder-inited", write_api)


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
    for path in _candidates(target, node.get("py:module"), node.get("py:class")):
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
    if what in ("data", "attribute") and lines and isinstance(getattr(obj, "__doc__", None), str):
        from sphinx.util.docstrings import prepare_docstring
        own = [ln for ln in prepare_docstring(obj.__doc__) if ln.strip()]
        if own and [ln for ln in lines if ln.strip()][:len(own)] == own:
            lines[:] = []


def module_citations(app, what, name, obj, options, lines):
    """A function citing ``[Wu]_`` defined in its module's docstring: numpydoc renamed the
    module's citations (prefix from the module's name); point the reference there."""
    if what == "module":
        return
    import hashlib
    from numpydoc.numpydoc import HASH_LEN
    text = "\n".join(lines)
    cited = set(re.findall(r"\[([A-Za-z0-9_.-]+)\]_", text)) - set(re.findall(r"^\s*\.\. \[([^\]]+)\]", text, re.M))
    if not cited:
        return
    mod_name = getattr(obj, "__module__", None) or name.rsplit(".", 1)[0]
    mod = sys.modules.get(mod_name)
    mod_doc = (mod.__doc__ or "") if mod else ""
    prefix = "R" + hashlib.sha256(mod_name.encode("utf8")).hexdigest()[:HASH_LEN]
    for c in cited:
        if re.search(rf"^\s*\.\. \[{re.escape(c)}\]", mod_doc, re.M):
            lines[:] = [ln.replace(f"[{c}]_", f"[{prefix}-{c}]_") for ln in lines]


_setup_api = setup


def setup(app):  # noqa: F811
    _setup_api(app)
    app.connect("missing-reference", resolve_alias)
    app.connect("autodoc-process-docstring", drop_type_docstrings, priority=400)
    app.connect("autodoc-process-docstring", module_citations, priority=600)   # after numpydoc
