#!/usr/bin/env python3
"""Checks the source layout rules of docs/architecture.md and exits 1 on a breach.

  scripts/check_layout.py              (run by ctest as `layout`)
  scripts/check_layout.py --self-test  (the checker finds planted breaches)

- every library source file (ccma/, cost_functions/, formats/, problems/,
  analyses/, execution/, viewer/, apps/, python/src/) has at most 500 lines;
- every function body in them has at most 60 lines;
- no #include points from a lower layer to a higher one;
- Eigen's dense decompositions of dynamic matrices (JacobiSVD, BDCSVD,
  SelfAdjointEigenSolver, CompleteOrthogonalDecomposition of MatrixXd, by
  name or through the methods jacobiSvd(), bdcSvd(),
  completeOrthogonalDecomposition()) are instantiated only in
  ccma/internal/dense_factorizations.cc: elsewhere the wrappers of
  dense_factorizations.h (each instantiation costs 9-13 s of compile time per
  translation unit).
- a test file tests/<stem>_test.cc keeps its helpers in `namespace <stem>`,
  not in an anonymous namespace: the files of one test executable are
  compiled together (unity batches), where two files' anonymous namespaces
  are one.
- no call's or constructor's parentheses hold two draws from a random engine
  (`d(rng)`, `RandomUnit(rng)`: any call passed `rng`, `rng_` or `random`)
  outside braces: the order in which a call's arguments (or an operator's
  operands) are evaluated is unspecified, so the same seed gave g++ and
  clang different samples. A braced list (`Eigen::Vector3d{d(rng), d(rng),
  d(rng)}`) or one statement per draw is evaluated in order.
Functions are found by braces: a `{` at namespace or class level whose text
since the previous `;`, `{` or `}` has a `)` and is not a namespace, class,
struct, enum or initialiser. Comments and string literals are blanked first.
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MAX_FILE_LINES = 500
MAX_FUNCTION_LINES = 60
SOURCE_DIRS = ["ccma", "cost_functions", "formats", "collision", "problems", "analyses",
               "execution", "viewer", "documents", "apps", "python/src"]
# Layer of each top folder, lowest first. A file may include its own layer
# and lower ones. ccma/ccma.h (the umbrella header) may include everything.
LAYERS = {"ccma": 0, "cost_functions": 0, "formats": 1, "collision": 1, "problems": 2,
          "analyses": 3, "execution": 4, "viewer": 5, "documents": 6, "apps": 7, "python": 7}
# The two faces of the top layer: neither includes the other (what both need
# is in documents/, below them).
FACES = {"apps", "python"}
UMBRELLA = "ccma/ccma.h"
DENSE_FACTORIZATIONS = "ccma/internal/dense_factorizations.cc"
HEAVY_DECOMPOSITION = re.compile(
    r"Eigen::(JacobiSVD|BDCSVD|SelfAdjointEigenSolver|CompleteOrthogonalDecomposition)\s*<\s*Eigen::MatrixXd\b")
# The same through MatrixBase's methods (a fixed-size matrix's decomposition
# is named with its type instead: Eigen::JacobiSVD<Eigen::Matrix3d>).
HEAVY_DECOMPOSITION_METHOD = re.compile(r"\.(jacobiSvd|bdcSvd|completeOrthogonalDecomposition)\s*\(")


def blank(text):
    """Comments, string and char literals replaced by spaces (newlines kept)."""
    pattern = re.compile(r'//[^\n]*|/\*.*?\*/|R"(\w*)\(.*?\)\1"|"(?:\\.|[^"\\\n])*"'
                         r"|'(?:\\.|[^'\\\n])*'", re.S)
    return pattern.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


def functions(text):
    """(name, first line, line count) of each function body at namespace or class level."""
    code = blank(text)
    found, stack, start = [], [], 0  # stack: 'scope', 'init' or ('function', name, line)
    for i, c in enumerate(code):
        if c in ";{}":
            head = code[start:i]
            in_function = any(isinstance(s, tuple) for s in stack)
            if c == "{" and not in_function and re.search(r"[\w>]$", head) and ")" in head:
                # x_{...} in a constructor's initialiser list: part of the head.
                stack.append("init")
                continue
            if c == "}" and stack and stack[-1] == "init":
                stack.pop()
                continue
            if c == "{":
                if (not in_function and ")" in head and not re.search(
                        r"\b(namespace|class|struct|enum|union)\b[^()]*$", head)
                        and not re.search(r"=\s*$", head)):
                    name = re.findall(r"([~\w:]+)\s*\(", head)
                    stack.append(("function", name[0] if name else "?",
                                  code.count("\n", 0, i) + 1))
                else:
                    stack.append("scope")
            elif c == "}" and stack:
                top = stack.pop()
                if isinstance(top, tuple):
                    end = code.count("\n", 0, i) + 1
                    found.append((top[1], top[2], end - top[2] + 1))
            start = i + 1
    return found


def layer_of(path):
    top = path.split("/")[0]
    return LAYERS.get(top)


def check_text(path, text):
    """The breaches of one file (path relative to the repository)."""
    breaches = []
    lines = text.count("\n")
    if lines > MAX_FILE_LINES:
        breaches.append(f"{path}: {lines} lines (at most {MAX_FILE_LINES})")
    for name, line, count in functions(text):
        if count > MAX_FUNCTION_LINES:
            breaches.append(f"{path}:{line}: {name} has {count} lines (at most {MAX_FUNCTION_LINES})")
    own = layer_of(path)
    if path != UMBRELLA and own is not None:
        for m in re.finditer(r'^#include "([^"]+)"', text, re.M):
            other = layer_of(m.group(1))
            if other is not None and other > own:
                breaches.append(f"{path}: includes {m.group(1)} (a higher layer)")
            faces = {path.split("/")[0], m.group(1).split("/")[0]}
            if faces == FACES:
                breaches.append(f"{path}: includes {m.group(1)} (the other face: share it through documents/)")
    if path != DENSE_FACTORIZATIONS:
        for m in HEAVY_DECOMPOSITION.finditer(blank(text)):
            line = text.count("\n", 0, m.start()) + 1
            breaches.append(f"{path}:{line}: Eigen::{m.group(1)}<Eigen::MatrixXd> (use ccma/internal/dense_factorizations.h)")
        for m in HEAVY_DECOMPOSITION_METHOD.finditer(blank(text)):
            line = text.count("\n", 0, m.start()) + 1
            breaches.append(f"{path}:{line}: .{m.group(1)}() (use ccma/internal/dense_factorizations.h)")
    return breaches


DRAW = re.compile(r"\((?:rng_?|random)\s*[,)]")
NOT_CALLS = {"if", "for", "while", "switch", "return", "sizeof", "catch"}


def unsequenced_draws(path, text):
    """Calls whose parentheses hold two or more random draws outside braces."""
    code = blank(text)
    breaches, stack = [], []  # stack of [kind, start, draws]: kind '(' call, '(' other, '{'
    for m in re.finditer(r"[(){}]", code):
        c, i = m.group(0), m.start()
        if c == "{":
            stack.append(["{", i, 0])
        elif c == "(":
            before = re.search(r"([A-Za-z_]\w*|>|\))\s*$", code[max(0, i - 80):i])
            call = bool(before) and before.group(1) not in NOT_CALLS
            if DRAW.match(code, i):  # the draw itself: count it in the enclosing call
                for frame in reversed(stack):
                    if frame[0] == "{":
                        break
                    frame[2] += 1
            stack.append(["call" if call else "(", i, 0])
        elif stack:
            kind, start, draws = stack.pop()
            if kind == "call" and draws >= 2:
                line = text.count("\n", 0, start) + 1
                breaches.append(f"{path}:{line}: {draws} random draws in one call's arguments (their order is "
                                f"unspecified: draw them in separate statements or in a braced list)")
    return breaches


def check_test_file(path, text):
    """The breaches of one test file tests/<stem>_test.cc: an anonymous namespace."""
    m = re.fullmatch(r"tests/(\w+_test)\.cc", path)
    if not m:
        return []
    breaches = []
    for a in re.finditer(r"\bnamespace\s*\{", blank(text)):
        line = text.count("\n", 0, a.start()) + 1
        breaches.append(f"{path}:{line}: an anonymous namespace (this file is compiled together with others of "
                        f"its area: use namespace {m.group(1)})")
    return breaches


def self_test():
    """Planted breaches are found; their clean twins are not."""
    body = "".join(f"  x += {i};\n" for i in range(58))
    ok = "int F(int x) {\n" + body + "  return x;\n}\n"  # 61 lines with braces: 60 + 1
    ok = ok.replace("  x += 0;\n", "")  # 60 lines
    long = ok.replace("  return x;", "  x += 99;\n  return x;")  # 61 lines
    lambda_inside = "void G() {\n  auto f = [] { return 1; };\n  (void)f;\n}\n"
    assert functions(ok) == [("F", 1, 60)], functions(ok)
    assert functions(long) == [("F", 1, 61)], functions(long)
    assert functions(lambda_inside) == [("G", 1, 4)], functions(lambda_inside)
    assert functions('const char* s = "}{";\nvoid H() {\n}\n') == [("H", 2, 2)]
    assert functions("namespace a {\nstruct S {\n  int f() const {\n    return 1;\n  }\n};\n}\n") == [("f", 3, 3)]
    ctor = "A::A(int x) : a_{x}, b_(x) {\n" + body + "}\n"  # 60 lines of body + 2
    assert functions(ctor) == [("A::A", 1, 60)], functions(ctor)
    assert not check_text("problems/a.cc", ok)
    assert len(check_text("problems/a.cc", long)) == 1
    assert len(check_text("problems/a.cc", "x\n" * 501)) == 1
    assert not check_text("problems/a.cc", "x\n" * 500)
    assert len(check_text("ccma/a.cc", '#include "problems/forward_problem.h"\n')) == 1
    assert not check_text("problems/a.cc", '#include "ccma/model.h"\n')
    assert not check_text("ccma/ccma.h", '#include "analyses/design.h"\n')
    assert len(check_text("python/src/a.cc", '#include "apps/json_output.h"\n')) == 1
    assert len(check_text("apps/a.cc", '#include "python/src/documents.h"\n')) == 1
    assert not check_text("python/src/a.cc", '#include "documents/json_values.h"\n')
    assert len(check_text("documents/a.cc", '#include "apps/cli.h"\n')) == 1
    assert len(check_text("problems/a.cc", "Eigen::JacobiSVD<Eigen::MatrixXd> svd(A);\n")) == 1
    assert not check_text("problems/a.cc", "JacobiSvd svd(A);  // not Eigen::JacobiSVD<Eigen::MatrixXd>\n")
    assert not check_text(DENSE_FACTORIZATIONS, "Eigen::BDCSVD<Eigen::MatrixXd> svd;\n")
    assert len(check_text("ccma/a.cc", "P = A.completeOrthogonalDecomposition().pseudoInverse();\n")) == 1
    assert len(check_text("ccma/a.cc", "s = A.jacobiSvd().singularValues();\n")) == 1
    assert not check_text("ccma/a.cc", "MinimumNormSolver cod(A);  // not A.completeOrthogonalDecomposition()\n")
    assert len(check_test_file("tests/a_test.cc", "namespace ccma {\nnamespace {\nint x;\n}\n}\n")) == 1
    assert not check_test_file("tests/a_test.cc", "namespace ccma {\nnamespace a_test {\nint x;\n}\n}\n")
    assert not check_test_file("tests/a_test.cc", "// namespace {\nconst char* s = \"namespace {\";\n")
    assert len(unsequenced_draws("tests/a_test.cc", "v = Eigen::Vector3d(d(rng), d(rng), d(rng));\n")) == 1
    assert len(unsequenced_draws("tests/a_test.cc", "f(a(rng) * RandomUnit(rng));\n")) == 1
    assert len(unsequenced_draws("execution/a.cc", "g(Pose(RandomRotation(rng_), RandomVector(rng_, 2.0)));\n")) >= 1
    assert not unsequenced_draws("tests/a_test.cc", "v = Eigen::Vector3d{d(rng), d(rng), d(rng)};\n")
    assert not unsequenced_draws("tests/a_test.cc", "const double a = d(rng), b = d(rng);\nu << d(rng), d(rng);\n")
    assert not unsequenced_draws("tests/a_test.cc", "push_back(Vector3d{d(rng), d(rng)});\nif (d(rng) > d(rng)) x();\n")
    assert not unsequenced_draws("ccma/a.cc", "M = NullaryExpr(n, m, [&]() { return d(random); });\nf(d(rng));\n")
    print("layout self-test: ok")
    return 0


def main():
    if "--self-test" in sys.argv:
        return self_test()
    breaches = []
    for d in SOURCE_DIRS:
        for dirpath, _, names in os.walk(os.path.join(ROOT, d)):
            if "node_modules" in dirpath:
                continue
            for n in sorted(names):
                if not n.endswith((".h", ".cc")):
                    continue
                path = os.path.relpath(os.path.join(dirpath, n), ROOT)
                text = open(os.path.join(ROOT, path), encoding="utf-8").read()
                breaches += check_text(path, text) + unsequenced_draws(path, text)
    tests = os.path.join(ROOT, "tests")
    for n in sorted(os.listdir(tests)):
        if n.endswith("_test.cc"):
            text = open(os.path.join(tests, n), encoding="utf-8").read()
            breaches += check_test_file("tests/" + n, text) + unsequenced_draws("tests/" + n, text)
    for d in ["benchmarks", "examples", "fuzz"]:
        for dirpath, _, names in os.walk(os.path.join(ROOT, d)):
            for n in sorted(names):
                if n.endswith((".h", ".cc")):
                    path = os.path.relpath(os.path.join(dirpath, n), ROOT)
                    breaches += unsequenced_draws(path, open(os.path.join(ROOT, path), encoding="utf-8").read())
    for b in breaches:
        print(b)
    print(f"layout: {len(breaches)} breaches")
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
