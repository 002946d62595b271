"""The type stub python/ccma/_ccma.pyi against the built extension ccma._ccma.

Every public name of the module and of each class must be in the stub and
every name in the stub must exist in the module, with the same kind (class,
exception, function, method, read-only or writable property), the same
constructors, __repr__s and overload counts, and the same parameter names and
defaults as the pybind11 signatures. A binding added without its stub entry
(or a stub entry left behind) fails here.
"""
import ast
import inspect
import re

import pytest

import ccma
from ccma import _ccma
from conftest import ROOT

STUB_PATH = ROOT / "python" / "ccma" / "_ccma.pyi"


def public(name):
    return not name.startswith("_")


# ------------------------------------------------------------------ stub side

class StubFunction:
    """One name defined by `def` in the stub (all its @overload variants)."""

    def __init__(self):
        self.variants = []  # ast.FunctionDef, in order
        self.overloaded = False
        self.is_property = False
        self.has_setter = False


def decorator_names(node):
    names = []
    for d in node.decorator_list:
        if isinstance(d, ast.Name):
            names.append(d.id)
        elif isinstance(d, ast.Attribute):
            names.append(d.attr)  # x.setter -> "setter"
    return names


def collect_functions(body):
    functions = {}
    for node in body:
        if not isinstance(node, ast.FunctionDef):
            continue
        f = functions.setdefault(node.name, StubFunction())
        decorators = decorator_names(node)
        if "setter" in decorators:
            f.has_setter = True
            continue
        if "property" in decorators:
            f.is_property = True
        if "overload" in decorators:
            f.overloaded = True
        f.variants.append(node)
    return functions


def base_names(node):
    return [b.id if isinstance(b, ast.Name) else ast.unparse(b) for b in node.bases]


@pytest.fixture(scope="module")
def stub():
    tree = ast.parse(STUB_PATH.read_text(encoding="utf-8"), filename=str(STUB_PATH))
    classes, variables = {}, set()
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            classes[node.name] = node
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            variables.add(node.target.id)
        elif isinstance(node, ast.Assign):
            variables.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return {"tree": tree, "classes": classes, "functions": collect_functions(tree.body), "variables": variables}


def stub_params(fn):
    """[(name, has_default, kind)] of a stub def, without self."""
    a = fn.args
    positional = a.posonlyargs + a.args
    defaults = [None] * (len(positional) - len(a.defaults)) + list(a.defaults)
    params = [(p.arg, d is not None, "positional_only" if p in a.posonlyargs else "positional")
              for p, d in zip(positional, defaults)]
    params += [(p.arg, d is not None, "keyword_only") for p, d in zip(a.kwonlyargs, a.kw_defaults)]
    if a.vararg:
        params.append(("*" + a.vararg.arg, False, "var"))
    if a.kwarg:
        params.append(("**" + a.kwarg.arg, False, "var"))
    if params and params[0][0] == "self":
        params = params[1:]
    return params


# --------------------------------------------------------------- runtime side

def split_top_level(text):
    """Splits a pybind11 argument list at the commas outside brackets."""
    parts, depth, current = [], 0, ""
    for ch in text:
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append(current.strip())
            current = ""
        else:
            current += ch
    if current.strip():
        parts.append(current.strip())
    return parts


def runtime_signatures(obj, name):
    """[[(param name, has_default)]] of each pybind11 overload of `obj`, without self."""
    signatures = []
    pattern = re.compile(r"^(?:\d+\. )?" + re.escape(name) + r"\((.*)\) -> ")
    for line in (obj.__doc__ or "").splitlines():
        m = pattern.match(line.strip())
        if not m:
            continue
        params = []
        for part in split_top_level(m.group(1)):
            if part.startswith("**") or part.startswith("*"):
                params.append((part.split(":")[0].strip(), False))
                continue
            params.append((part.split(":")[0].strip(), " = " in part))
        if params and params[0][0] == "self":
            params = params[1:]
        signatures.append(params)
    return signatures


def runtime_module_names():
    return {n for n in dir(_ccma) if public(n)} | {"__version__"}


def runtime_classes():
    return {n: getattr(_ccma, n) for n in dir(_ccma) if public(n) and inspect.isclass(getattr(_ccma, n))}


def runtime_members(cls):
    """{name: "property" | "rw_property" | "method"} defined by the class itself."""
    members = {}
    for n, v in vars(cls).items():
        if not public(n):
            continue
        if isinstance(v, property):
            members[n] = "rw_property" if v.fset is not None else "property"
        elif callable(v):
            members[n] = "method"
        else:
            members[n] = "attribute"
    return members


def has_binding(cls, dunder):
    """Whether pybind11 bound `dunder` (e.g. __init__) for the class itself."""
    v = vars(cls).get(dunder)
    return v is not None and (getattr(v, "__doc__", "") or "").lstrip().startswith(dunder + "(")


def is_exception(cls):
    return issubclass(cls, BaseException)


# ---------------------------------------------------------------------- tests

def test_stub_parses_and_package_reexports_module(stub):
    assert stub["classes"] and stub["functions"]
    for name in runtime_module_names():
        assert getattr(ccma, name) is getattr(_ccma, name), name


def test_module_names_match(stub):
    stubbed = {n for n in stub["classes"] if public(n)} | {n for n in stub["functions"] if public(n)}
    stubbed |= {n for n in stub["variables"] if public(n) or n == "__version__"}
    runtime = runtime_module_names()
    assert sorted(runtime - stubbed) == [], "in ccma._ccma but not in the stub"
    assert sorted(stubbed - runtime) == [], "in the stub but not in ccma._ccma"


def test_module_name_kinds_match(stub):
    for name in runtime_module_names():
        obj = getattr(_ccma, name)
        if inspect.isclass(obj):
            assert name in stub["classes"], "%s is a class" % name
        elif callable(obj):
            assert name in stub["functions"], "%s is a function" % name
        else:
            assert name in stub["variables"], "%s is a variable" % name
    assert isinstance(_ccma.__version__, str)


@pytest.mark.parametrize("name", sorted(runtime_classes()))
def test_class_bases_match(stub, name):
    cls = runtime_classes()[name]
    runtime_bases = [b.__name__ for b in cls.__bases__ if b.__name__ != "pybind11_object"]
    assert base_names(stub["classes"][name]) == runtime_bases
    if is_exception(cls):
        assert issubclass(cls, ValueError), "ccma's exceptions are ValueErrors"


@pytest.mark.parametrize("name", sorted(n for n, c in runtime_classes().items() if not is_exception(c)))
def test_class_members_match(stub, name):
    cls = runtime_classes()[name]
    node = stub["classes"][name]
    functions = collect_functions(node.body)
    fields = {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
    stubbed = {}
    for n, f in functions.items():
        if public(n):
            stubbed[n] = ("rw_property" if f.has_setter else "property") if f.is_property else "method"
    for n in fields:
        if public(n):
            stubbed[n] = "attribute"
    runtime = runtime_members(cls)
    assert sorted(set(runtime) - set(stubbed)) == [], "%s: in the module but not in the stub" % name
    assert sorted(set(stubbed) - set(runtime)) == [], "%s: in the stub but not in the module" % name
    for n, kind in runtime.items():
        assert stubbed[n] == kind, "%s.%s is a %s, the stub says %s" % (name, n, kind, stubbed[n])
    for dunder in ("__init__", "__repr__"):
        assert has_binding(cls, dunder) == (dunder in functions), \
            "%s.%s: bound %s, stubbed %s" % (name, dunder, has_binding(cls, dunder), dunder in functions)


def callables_to_check(stub):
    """(qualified name, runtime object, stub function) of every function, method and constructor."""
    out = []
    for name in sorted(runtime_module_names()):
        obj = getattr(_ccma, name)
        if inspect.isclass(obj):
            if is_exception(obj):
                continue
            functions = collect_functions(stub["classes"][name].body)
            for member, kind in sorted(runtime_members(obj).items()):
                if kind == "method":
                    out.append(("%s.%s" % (name, member), member, getattr(obj, member), functions[member]))
            if has_binding(obj, "__init__"):
                out.append(("%s.__init__" % name, "__init__", vars(obj)["__init__"], functions["__init__"]))
        elif callable(obj):
            out.append((name, name, obj, stub["functions"][name]))
    return out


def test_signatures_match(stub):
    problems = []
    for qualified, name, obj, f in callables_to_check(stub):
        runtime = runtime_signatures(obj, name)
        if not runtime:
            problems.append("%s: no pybind11 signature in its docstring" % qualified)
            continue
        if len(runtime) > 1 and not f.overloaded:
            problems.append("%s: %d overloads, the stub has no @overload" % (qualified, len(runtime)))
        if len(runtime) != len(f.variants):
            problems.append("%s: %d overloads, the stub has %d" % (qualified, len(runtime), len(f.variants)))
            continue
        for params, variant in zip(runtime, f.variants):
            stubbed = stub_params(variant)
            if params == [("**kwargs", False)]:
                # Options built from keywords: each keyword is a writable field.
                owner = getattr(_ccma, qualified.split(".")[0])
                fields = sorted(n for n, k in runtime_members(owner).items() if k == "rw_property")
                if sorted(p[0] for p in stubbed) != fields or any(
                        kind != "keyword_only" or not default for _, default, kind in stubbed):
                    problems.append("%s: the stub's keyword-only arguments %s are not the fields %s"
                                    % (qualified, [p[0] for p in stubbed], fields))
                continue
            if [(n, d) for n, d, _ in stubbed] != params or any(k != "positional" for _, _, k in stubbed):
                problems.append("%s: runtime %s, stub %s" % (qualified, params, stubbed))
    assert problems == []


def test_every_stub_item_has_a_docstring(stub):
    missing = []

    def check(body, prefix):
        for node in body:
            if isinstance(node, ast.ClassDef):
                if ast.get_docstring(node) is None:
                    missing.append(prefix + node.name)
                check(node.body, prefix + node.name + ".")
            elif isinstance(node, ast.FunctionDef):
                if "setter" not in decorator_names(node) and ast.get_docstring(node) is None:
                    missing.append(prefix + node.name)

    check(stub["tree"].body, "")
    assert missing == []
