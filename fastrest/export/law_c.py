"""The contact law with its history as C, C++ and CUDA: ``fastrest export c --law``.

The C functions are not written by hand: :func:`law_source` translates the Python source of the jit
law (:mod:`fastrest.law_cells`: ``law_row``, ``virgin``, ``elastic_back``, ``outside``,
``law_step``, and :func:`fastrest.interpolation.estrin5`) statement by statement, through Python's
``ast``. The translator knows exactly the subset those functions use (assignments, a tuple
returned and unpacked, ``if``/``else``, arithmetic and comparisons, ``math.sqrt``, ``math.nan``,
``math.inf``, ``np.uint64``, 2-d row indexing and fastrest's ``select``, ``fdiv``, ``fma`` and
``float_bits`` intrinsics) and refuses anything else with :class:`LawTranslationError`, so an edit
of the law it cannot follow fails loudly rather than writing other arithmetic. ``select(c, a, b)``
becomes ``c ? a : b``, ``fdiv`` a division, ``fma`` C99's ``fma``: compiled without contraction
(``-ffp-contract=off``; nvcc ``--fmad=false``) the C law gives fastrest.jit's numbers bit for bit
(tests/test_export_law.py steps histories through both).

``fastrest_law_step(rows, first, last, w_end, state, w)``: the normal force P* at interference w*,
updating the contact's history ``state`` [w_max, P*(w_max), w_res*, delta] (zeros: a virgin
contact), exactly as :func:`fastrest.jit.contact_force`. The rows are a law's
``ContactLaw.data.law_rows``; :func:`law_header_text` writes those of one or several materials
into the header with the function, for a DEM code that has no Python at run time.
"""
from __future__ import annotations

import ast
import inspect
import math
import numbers
import os
import textwrap
from collections.abc import Sequence
from typing import Any

import numpy as np

from .. import interpolation, law_cells
from ..force_law import STATE_SIZE
from .._provenance import provenance
from .c_header import _PORTABLE, _lit, _rows_literal, _table
from ._io import check_target, write_files

__all__ = ["LawTranslationError", "translate", "law_source", "law_header_text", "write_law_header"]


class LawTranslationError(ValueError):
    """The source of the jit law holds a construct the C translator does not know.

    Examples
    --------
    >>> from fastrest.export.law_c import LawTranslationError
    >>> issubclass(LawTranslationError, ValueError)
    True
    """


D, I, U, B, P = "double", "FASTREST_INT64", "fastrest_law_uint64", "bool", "fastrest_law_pair"
# (function, C name, parameter types, return type), in the order they are emitted
_FUNCTIONS = [
    (interpolation.estrin5, "fastrest_law_estrin5", [D] * 7, D),
    (law_cells.law_row, "fastrest_law_row", [D, I, I], I),
    (law_cells.virgin, "fastrest_law_virgin", ["const double *", I, I, D], P),
    (law_cells.elastic_back, "fastrest_law_elastic_back", [D, D, D, D], D),
    (law_cells.outside, "fastrest_law_outside", [D, D, D, D], D),
    (law_cells.law_step, "fastrest_law_step", ["const double *", I, I, D, "double *", D], D),
]
_OPS = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.RShift: ">>"}  # no "/": Numba's raises on 0 (fdiv)
_NUM = (D, I, U)
# C/C++ words a local may not be named (and the temporaries' prefix, fastrest...)
_RESERVED = set("""auto bool break case catch char class const continue default delete do double else enum
extern float for goto if inline int long new operator private protected public register restrict return short
signed sizeof static struct switch template this throw try typedef union unsigned void volatile while fma sqrt
memcpy NAN INFINITY""".split())
_CMP = {ast.Lt: "<", ast.LtE: "<=", ast.Gt: ">", ast.GtE: ">=", ast.Eq: "==", ast.NotEq: "!="}


class _Function:
    """One function's translation: its locals' C types and its statements."""

    def __init__(self, fn, params, ret):
        self.fn = fn
        self.glob = fn.__globals__
        self.types = dict(params)
        self.ret = ret
        self.tmp = 0

    def fail(self, node, what):
        raise LawTranslationError(f"{self.fn.__module__}.{self.fn.__name__}, line "
                                  f"{getattr(node, 'lineno', '?')}: {what} is not translated to C")

    def need(self, node, got, allowed, what):
        if got not in allowed:
            self.fail(node, f"{what} of C type {got!r}")

    # --- expressions: (C text, C type) ---
    def expr(self, node):
        if isinstance(node, ast.Constant) and not isinstance(node.value, bool):
            return self.number(node, node.value)
        if isinstance(node, ast.Name):
            if node.id in self.types:
                return node.id, self.types[node.id]
            if node.id in self.glob and isinstance(self.glob[node.id], numbers.Number):
                return self.number(node, self.glob[node.id])
            self.fail(node, f"the name {node.id!r}")
        if isinstance(node, ast.Attribute) and self.resolve(node.value) is math and node.attr in ("nan", "inf"):
            return ("FASTREST_NAN" if node.attr == "nan" else "FASTREST_INFINITY"), D
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            text, ty = self.expr(node.operand)
            self.need(node, ty, (D, I), "a negation")
            return f"(-{text})", ty
        if isinstance(node, ast.BinOp) and type(node.op) in _OPS:
            (a, ta), (b, tb) = self.expr(node.left), self.expr(node.right)
            return f"({a} {_OPS[type(node.op)]} {b})", self.promote(node, ta, tb, "an operand")
        if isinstance(node, ast.Compare) and len(node.ops) == 1 and type(node.ops[0]) in _CMP:
            (a, ta), (b, tb) = self.expr(node.left), self.expr(node.comparators[0])
            self.promote(node, ta, tb, "a compared value")
            return f"({a} {_CMP[type(node.ops[0])]} {b})", B
        if isinstance(node, ast.Subscript):
            return self.subscript(node), D
        if isinstance(node, ast.Call):
            return self.call(node)
        self.fail(node, f"the expression {ast.unparse(node)!r}")

    def resolve(self, node):
        """The object a name or dotted name is bound to in the function's module (None: unbound)."""
        if isinstance(node, ast.Attribute):
            return getattr(self.resolve(node.value), node.attr, None)
        return self.glob.get(node.id) if isinstance(node, ast.Name) and node.id not in self.types else None

    def promote(self, node, ta, tb, what):
        """The C type of arithmetic on ta and tb, where C's and Numba's agree (uint64 with int64:
        float64 in Numba, uint64 in C; a shift: int64 only)."""
        self.need(node, ta, _NUM, what)
        self.need(node, tb, _NUM, what)
        if isinstance(getattr(node, "op", None), ast.RShift) and (ta, tb) != (I, I):
            self.fail(node, "a shift of other than two int64")
        if U in (ta, tb) and D not in (ta, tb) and ta != tb:
            self.fail(node, "arithmetic mixing uint64 and int64")
        return D if D in (ta, tb) else ta

    def number(self, node, v):
        if isinstance(v, (bool, np.bool_, np.unsignedinteger)) or not isinstance(v, numbers.Real):
            self.fail(node, f"the constant {v!r}")
        if isinstance(v, numbers.Integral):
            if not -2**63 <= int(v) < 2**63:
                self.fail(node, f"the constant {v!r} (not an int64)")
            return f"FASTREST_INT64_C({int(v)})", I
        return _lit(v), D

    def subscript(self, node):
        """rows[i, k] (a const double * parameter, LAW_ROW wide) or state[k] (a double * one)."""
        base, idx = node.value, node.slice
        kind = self.types.get(base.id) if isinstance(base, ast.Name) else None
        elts = idx.elts if isinstance(idx, ast.Tuple) else [idx]
        if (kind, len(elts)) not in (("const double *", 2), ("double *", 1)):
            self.fail(node, f"the subscript {ast.unparse(node)!r}")
        text = []
        for e in elts:
            t, ty = self.expr(e)
            self.need(e, ty, (I, U), "an index")
            text.append(t)
        return f"{base.id}[{text[0]} * FASTREST_LAW_ROW + {text[1]}]" if len(text) == 2 else f"{base.id}[{text[0]}]"

    def call(self, node):
        f = node.func
        if node.keywords:
            self.fail(node, "a keyword argument")
        args = [self.expr(a) for a in node.args]
        text, types = [a for a, _ in args], [t for _, t in args]
        name, obj = ast.unparse(f), self.resolve(f)
        if obj is interpolation.select and len(args) == 3:
            if types[0] != B or types[1] != types[2] or types[1] not in (D, I):
                self.fail(node, "a select of other than a comparison and two float64 or two int64")
            return f"({text[0]} ? {text[1]} : {text[2]})", types[1]
        # the callee (the object the name is bound to): argument types as Numba types them, C, result
        known = [(math.sqrt, [D], "sqrt({})", D), (np.uint64, [I], "((" + U + ")({}))", U),
                 (interpolation.fdiv, [D, D], "({} / {})", D), (interpolation.fma, [D, D, D], "fma({}, {}, {})", D),
                 (interpolation.float_bits, [D], "fastrest_law__bits({})", I)]
        known += [(fn, params, c_name + "(" + ", ".join(["{}"] * len(params)) + ")", ret)
                  for fn, c_name, params, ret in _FUNCTIONS]
        match = [k for k in known if k[0] is obj]
        if not match:
            self.fail(node, f"the call {name}")
        _, want, template, ret = match[0]
        types = [("const double *" if t == "double *" and w == "const double *" else t) for t, w in zip(types, want)]
        if types != want:
            self.fail(node, f"the call {name} with arguments of C types {types} (not {want})")
        return template.format(*text), ret

    # --- statements ---
    def scoped(self, body, indent):
        """A block whose new locals end with it (C's scope): a later use fails here, not in C."""
        outer = dict(self.types)
        out = self.block(body, indent)
        self.types = outer
        return out

    def block(self, body, indent):
        out = []
        for st in body:
            out += self.statement(st, indent)
        return out

    def statement(self, st, pad):
        if isinstance(st, ast.Expr) and isinstance(st.value, ast.Constant) and isinstance(st.value.value, str):
            return []  # a docstring
        if isinstance(st, ast.Return) and st.value is not None:
            if isinstance(st.value, ast.Tuple):
                both = [self.expr(e) for e in st.value.elts]
                if self.ret != P or [t for _, t in both] != [D, D]:
                    self.fail(st, f"a tuple return other than two float64 as a {P}")
                return [f"{pad}return fastrest_law_make_pair({both[0][0]}, {both[1][0]});"]
            text, ty = self.expr(st.value)
            self.need(st, ty, (self.ret,), f"a return as {self.ret}")
            return [f"{pad}return {text};"]
        if isinstance(st, ast.If):
            test, ty = self.expr(st.test)
            if ty != B:
                self.fail(st, "an if on a non-comparison")
            out = [f"{pad}if {test} {{", *self.scoped(st.body, pad + "    ")]
            if st.orelse:
                out += [f"{pad}}} else {{", *self.scoped(st.orelse, pad + "    ")]
            return out + [f"{pad}}}"]
        if isinstance(st, ast.Assign):
            return self.assign(st, pad)
        self.fail(st, f"the statement {type(st).__name__}")

    def assign(self, st, pad):
        if len(st.targets) == 1 and isinstance(st.targets[0], ast.Tuple):
            names = st.targets[0].elts
            text, ty = self.expr(st.value)
            if ty != P or len(names) != 2 or not all(isinstance(n, ast.Name) for n in names):
                self.fail(st, "a tuple assignment other than two names from a pair")
            self.tmp += 1
            out = [f"{pad}{P} fastrest_tmp_{self.tmp} = {text};"]
            for n, field in zip(names, "ab"):
                out += self.store(n, f"fastrest_tmp_{self.tmp}.{field}", D, pad)
            return out
        text, ty = self.expr(st.value)
        if len(st.targets) == 1:
            return self.store(st.targets[0], text, ty, pad)
        self.need(st, ty, _NUM, "a chained assignment")
        self.tmp += 1  # a = b = x: the value once, then the targets from left to right, as Python
        out = [f"{pad}{ty} fastrest_tmp_{self.tmp} = {text};"]
        for target in st.targets:
            out += self.store(target, f"fastrest_tmp_{self.tmp}", ty, pad)
        return out

    def store(self, target, text, ty, pad):
        if isinstance(target, ast.Subscript):
            if not (isinstance(target.value, ast.Name) and self.types.get(target.value.id) == "double *"):
                self.fail(target, f"storing into {ast.unparse(target.value)!r}")
            self.need(target, ty, (D,), "storing a value")
            return [f"{pad}{self.subscript(target)} = {text};"]
        if not isinstance(target, ast.Name):
            self.fail(target, "this assignment")
        self.need(target, ty, _NUM, f"assigning {target.id!r}")
        if target.id in _RESERVED or target.id.startswith("fastrest"):
            self.fail(target, f"the local name {target.id!r} (a C/C++ word or the translator's)")
        if target.id in self.types:
            if self.types[target.id] != ty:
                self.fail(target, f"{target.id!r} changing type")
            return [f"{pad}{target.id} = {text};"]
        self.types[target.id] = ty
        return [f"{pad}{ty} {target.id} = {text};"]


def translate(fn: Any, c_name: str, param_types: Sequence[str], ret: str) -> str:
    """The C definition of the jit function ``fn`` (a Numba dispatcher or a Python function).

    Parameters
    ----------
    fn : callable
        The function; its source is read with :func:`inspect.getsource`.
    c_name : str
        Its name in C.
    param_types : sequence of str
        The C type of each parameter (``"double"``, ``"FASTREST_INT64"``, ``"const double *"``,
        ``"double *"``).
    ret : str
        The C return type.

    Returns
    -------
    str
        The definition, ``static inline``.

    Raises
    ------
    LawTranslationError
        A construct outside the translated subset (naming the function, line and construct).

    Examples
    --------
    >>> from fastrest.export.law_c import translate
    >>> def twice(w):
    ...     return w + w
    >>> print(translate(twice, "twice", ["double"], "double").splitlines()[-2])
        return (w + w);
    """
    py = getattr(fn, "py_func", fn)
    tree = ast.parse(textwrap.dedent(inspect.getsource(py)))
    node = tree.body[0]
    if not isinstance(node, ast.FunctionDef):
        raise LawTranslationError(f"{py.__name__}: not a function definition")
    args = node.args
    if args.vararg or args.kwarg or args.kwonlyargs or args.defaults or len(args.args) != len(param_types):
        raise LawTranslationError(f"{py.__module__}.{py.__name__}: its parameters are not {len(param_types)} "
                                  "plain positional ones")
    names = [a.arg for a in args.args]
    if any(n in _RESERVED or n.startswith("fastrest") for n in names):
        raise LawTranslationError(f"{py.__module__}.{py.__name__}: a parameter named as a C/C++ word or the "
                                  "translator's temporaries")
    body = _Function(py, zip(names, param_types), ret).block(node.body, "    ")
    params = ", ".join(f"{t}{'' if t.endswith('*') else ' '}{n}" for t, n in zip(param_types, names))
    return "\n".join([f"/* {py.__module__}.{py.__name__} */",
                      f"static inline FASTREST_LAW_FN {ret} {c_name}({params})", "{", *body, "}"])


_PRELUDE = r"""
#ifndef FASTREST_LAW_FN
#define FASTREST_LAW_FN FASTREST_FN
#endif
#define FASTREST_LAW_ROW @LAW_ROW@
#define FASTREST_STATE_SIZE @STATE_SIZE@
#if defined(__CUDACC_RTC__)
typedef unsigned long long fastrest_law_uint64;
#else
typedef uint64_t fastrest_law_uint64;
#endif
typedef struct { double a, b; } fastrest_law_pair;
static inline FASTREST_LAW_FN fastrest_law_pair fastrest_law_make_pair(double a, double b)
{
    fastrest_law_pair p;
    p.a = a;
    p.b = b;
    return p;
}
/* The bits of a double as a signed 64-bit integer (fastrest.interpolation.float_bits). */
static inline FASTREST_LAW_FN FASTREST_INT64 fastrest_law__bits(double v)
{
#if defined(__CUDA_ARCH__)
    return __double_as_longlong(v);
#else
    FASTREST_INT64 b;
    memcpy(&b, &v, sizeof b);
    return b;
#endif
}
"""


def _prelude():
    """The header's fixed part, with the row width and history size of the Python definitions."""
    return _PRELUDE.replace("@LAW_ROW@", str(law_cells.LAW_ROW)).replace("@STATE_SIZE@", str(STATE_SIZE))


def law_source() -> str:
    """The contact law as C99/C++/CUDA source: ``fastrest_law_step`` and its helpers, no tables.

    Returns
    -------
    str
        Text of a header (its own include guard ``FASTREST_LAW_H``).

    Raises
    ------
    LawTranslationError
        The jit law's source left the translated subset.

    Examples
    --------
    >>> from fastrest.export.law_c import law_source
    >>> "double fastrest_law_step(const double *rows" in law_source()
    True
    """
    prov = provenance()
    head = [f"/* fastrest_law.h: the contact law of fastrest {prov['fastrest_version']}, translated from the",
            " * source of fastrest.law_cells (fastrest.jit.contact_force). Do not edit.",
            " *",
            " * double fastrest_law_step(rows, first, last, w_end, state, w): the normal force P* = P/P_c at",
            " * interference w* = omega/omega_c, updating the contact's history state[FASTREST_STATE_SIZE] =",
            " * [w_max, P*(w_max), w_res*, delta] (zeros: a virgin contact; Jackson-Green loading, elastic",
            " * unloading and reloading along JGM eq 32, 0 at or below w_res*). rows: a law's cells, row-major,",
            " * FASTREST_LAW_ROW doubles each (ContactLaw.data.law_rows), this law's rows first .. first + last;",
            " * w_end: its end (ContactLaw.data.w_max). NaN, with the state set to NaN, for w NaN, -inf or past",
            " * w_end, and for a state that is no history of a law.",
            " * Compile without contraction of a * b + c (gcc/clang -ffp-contract=off, nvcc --fmad=false) for",
            " * fastrest.jit's numbers bit for bit; C99 or C++, libm only; compiles unedited as CUDA. */",
            "#ifndef FASTREST_LAW_H", "#define FASTREST_LAW_H", _PORTABLE,
            "#if defined(__CUDACC__)", "#pragma nv_diagnostic pop", "#endif", _prelude()]
    body = [translate(f, c, p, r) for f, c, p, r in _FUNCTIONS]
    return "\n".join(head + body + ["#endif /* FASTREST_LAW_H */"]) + "\n"


def law_header_text(laws: Sequence[Any], names: Sequence[str] | None = None, command: str | None = None) -> str:
    """:func:`law_source` with the rows of ``laws`` (:class:`fastrest.ContactLaw`) as tables.

    Parameters
    ----------
    laws : sequence of ContactLaw
        One or more laws (:func:`fastrest.contact_law`); law k's rows are
        ``fastrest_law_rows[fastrest_law_first[k] .. fastrest_law_first[k] + fastrest_law_last[k]]``.
    names : sequence of str, optional
        A label per law, for the comments.
    command : str, optional
        The command that wrote the header, for its first comment.

    Returns
    -------
    str
        The header.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.export.law_c import law_header_text
    >>> text = law_header_text([fastrest.contact_law(0.005, 0.33, w_max=30.0)])
    >>> "#define FASTREST_N_LAWS 1" in text
    True
    """
    if not laws:
        raise ValueError("laws: give at least one contact law")
    rows = [np.ascontiguousarray(law.data.law_rows) for law in laws]
    first = np.concatenate([[0], np.cumsum([r.shape[0] for r in rows])[:-1]])
    lines = [law_source().replace("#endif /* FASTREST_LAW_H */\n", ""),
             f"/* Laws ({command or 'fastrest export c --law'}): k, eps_y, nu, et_ratio, unloading, end w* */"]
    for k, law in enumerate(laws):
        label = f" ({names[k]})" if names and names[k] else ""
        lines.append(f"/*   {k}{label}: eps_y = {law.eps_y!r}, nu = {law.nu!r}, et_ratio = {law.data.et_ratio!r}, "
                     f"{law.unloading}, w_end = {law.data.w_max!r} */")
    lines += [f"#define FASTREST_N_LAWS {len(laws)}",
              _table("FASTREST_INT64", "fastrest_law_first", "[FASTREST_N_LAWS]",
                     ", ".join(f"FASTREST_INT64_C({int(f)})" for f in first)),
              _table("FASTREST_INT64", "fastrest_law_last", "[FASTREST_N_LAWS]",
                     ", ".join(f"FASTREST_INT64_C({r.shape[0] - 1})" for r in rows)),
              _table("double", "fastrest_law_w_end", "[FASTREST_N_LAWS]", ", ".join(_lit(law.data.w_max) for law in laws)),
              f"FASTREST_TABLE(double, fastrest_law_rows, [{int(sum(r.shape[0] for r in rows))}][FASTREST_LAW_ROW], {{",
              _rows_literal(np.concatenate(rows)), "});", "#endif /* FASTREST_LAW_H */"]
    return "\n".join(lines) + "\n"


def write_law_header(path: str | os.PathLike[str], laws: Sequence[Any], names: Sequence[str] | None = None,
                     command: str | None = None) -> str:
    """Write :func:`law_header_text` to ``path`` atomically; return the path.

    Parameters
    ----------
    path : str or path-like
        The header (a regular file or a new path).
    laws, names, command
        As :func:`law_header_text`.

    Returns
    -------
    str
        The path written.

    Examples
    --------
    >>> import fastrest, tempfile, os
    >>> from fastrest.export.law_c import write_law_header
    >>> out = os.path.join(tempfile.mkdtemp(), "law.h")
    >>> write_law_header(out, [fastrest.contact_law(0.005, 0.33, w_max=30.0)]) == out
    True
    """
    check_target(path, "--out", "the header")
    text = law_header_text(laws, names, command)
    return str(write_files({path: text}, "--out", "the header")[0])
