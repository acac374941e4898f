"""The type stubs (siloscope/__init__.pyi) against the package: every public name stubbed, every function's and
method's parameters (names, kinds, defaults) as the code has them, properties as properties, and the stub valid
Python. No type checker is in Debian's stack this suite installs, so the stub is read with `ast`."""
import ast
import inspect
import os

import siloscope

STUB = os.path.join(os.path.dirname(siloscope.__file__), "__init__.pyi")


def _stub():
    with open(STUB) as f:
        return ast.parse(f.read(), STUB)


def _params(fn):
    """(name, kind, default as source text or None) of a stub's def."""
    a = fn.args
    out = []
    positional = a.posonlyargs + a.args
    defaults = [None] * (len(positional) - len(a.defaults)) + [ast.unparse(d) for d in a.defaults]
    for arg, d in zip(positional, defaults):
        out.append((arg.arg, "positional", d))
    if a.vararg:
        out.append((a.vararg.arg, "*", None))
    for arg, d in zip(a.kwonlyargs, a.kw_defaults):
        out.append((arg.arg, "keyword", None if d is None else ast.unparse(d)))
    if a.kwarg:
        out.append((a.kwarg.arg, "**", None))
    return out


def _runtime(fn):
    kinds = {inspect.Parameter.POSITIONAL_ONLY: "positional", inspect.Parameter.POSITIONAL_OR_KEYWORD: "positional",
             inspect.Parameter.VAR_POSITIONAL: "*", inspect.Parameter.KEYWORD_ONLY: "keyword",
             inspect.Parameter.VAR_KEYWORD: "**"}
    out = []
    for p in inspect.signature(fn).parameters.values():
        d = None if p.default is inspect.Parameter.empty else repr(p.default)
        out.append((p.name, kinds[p.kind], d))
    return out


def _same_default(a, b):
    return a == b or (a is not None and b is not None and ast.literal_eval(a) == ast.literal_eval(b))


def _check(stub_fn, real, where):
    got, want = _params(stub_fn), _runtime(real)
    assert [(n, k) for n, k, _ in got] == [(n, k) for n, k, _ in want], f"{where}: stub {got} against {want}"
    for (n, _, a), (_, _, b) in zip(got, want):
        assert _same_default(a, b), f"{where}({n}): stub default {a} against {b}"


def test_every_public_name_is_stubbed_with_its_parameters():
    tree = _stub()
    top = {n.name: n for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    for name in siloscope.__all__:
        assert name in top, f"siloscope.{name} has no stub"
        obj = getattr(siloscope, name)
        node = top[name]
        if isinstance(node, ast.FunctionDef):
            _check(node, obj, name)
            continue
        methods = {n.name: n for n in node.body if isinstance(n, ast.FunctionDef)}
        for attr, value in vars(obj).items():
            if attr.startswith("__") and attr != "__init__" or attr.startswith("_") and not attr.startswith("_repr"):
                continue
            if attr == "__init__" and value is getattr(Exception, "__init__", None):
                continue
            if isinstance(value, property):
                assert attr in methods and any(ast.unparse(d) == "property" for d in methods[attr].decorator_list), \
                    f"{name}.{attr} is a property: stub it with @property"
            elif isinstance(value, classmethod):
                assert attr in methods, f"{name}.{attr} has no stub"
                assert any(ast.unparse(d) == "classmethod" for d in methods[attr].decorator_list)
                _check(methods[attr], value.__func__, f"{name}.{attr}")
            elif inspect.isfunction(value):
                assert attr in methods, f"{name}.{attr} has no stub"
                _check(methods[attr], value, f"{name}.{attr}")


def test_stub_names_nothing_the_package_lacks():
    tree = _stub()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            assert hasattr(siloscope, node.name), f"the stub names siloscope.{node.name}, which does not exist"
        if isinstance(node, ast.ClassDef):
            cls = getattr(siloscope, node.name)
            for m in node.body:
                if isinstance(m, ast.FunctionDef) and not m.name.startswith("__"):
                    assert hasattr(cls, m.name), f"the stub names {node.name}.{m.name}, which does not exist"
    assert os.path.exists(os.path.join(os.path.dirname(STUB), "py.typed"))


def test_every_public_name_has_a_docstring():
    missing = []
    for name in siloscope.__all__:
        obj = getattr(siloscope, name)
        if not inspect.getdoc(obj):
            missing.append(name)
        if inspect.isclass(obj):
            for attr, value in vars(obj).items():
                if attr.startswith("_"):
                    continue
                f = value.fget if isinstance(value, property) else getattr(value, "__func__", value)
                if (callable(f) or isinstance(value, property)) and not (f.__doc__ or "").strip():
                    missing.append(f"{name}.{attr}")
    assert not missing, f"no docstring: {missing}"
