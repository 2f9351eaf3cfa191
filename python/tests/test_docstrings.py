"""Docstring coverage of the public API: every public function and class of `topple` and `topple.plot` has a
numpy-style docstring, with a Parameters section naming every parameter, a Returns section when it returns
something, an Attributes section naming every public attribute of a class, and the unit of every physical quantity
(names ending in _m, _s, _g, _hz, _deg, _rad, ... and the plain lengths width, height ...). The stubs
(topple/__init__.pyi) are checked to be in step: the same parameter names and the same summary line."""
import ast
import inspect
import pathlib
import pydoc
import re

import pytest

import topple

plot = pytest.importorskip("topple.plot")

# Name suffix -> what the description must contain (longest suffixes first: _m_s2 before _m_s before _s).
UNIT_SUFFIXES = [
    ("_j_per_kg", r"J/kg"),
    ("_m_s2", r"m/s(\^2|²|2)"),
    ("_rad_s", r"rad/s"),
    ("_m_s", r"m/s"),
    ("_m2", r"m(\^2|²)"),
    ("_hz", r"\bHz\b"),
    ("_deg", r"\bdeg"),
    ("_rad", r"\brad\b"),
    ("_g", r"\bg\b"),
    ("_s", r"\bs\b"),
    ("_m", r"\bm\b"),
]
# Physical parameters without a suffix (the constructors' and readers' historical names).
PLAIN_UNITS = {"width": r"\bm\b", "height": r"\bm\b", "diameter": r"\bm\b", "a": r"\bm\b", "h": r"\bm\b",
               "D": r"m(\^2|²)", "g": r"m/s(\^2|²|2)", "dt": r"\bs\b"}
# Names whose suffix is not a unit: zeta_g is the damping ratio of the *ground* filter (dimensionless).
NOT_UNITS = {"zeta_g"}


def unit_pattern(name):
    if name in NOT_UNITS:
        return None
    if name in PLAIN_UNITS:
        return PLAIN_UNITS[name]
    for suffix, pattern in UNIT_SUFFIXES:
        if name.endswith(suffix):
            return pattern
    return None


def doc_of(obj):
    """The docstring without nanobind's leading signature line."""
    doc = inspect.getdoc(obj) or ""
    name = getattr(obj, "__name__", "")
    lines = doc.splitlines()
    if lines and name and lines[0].startswith(name + "(") and not inspect.isclass(obj):
        lines = lines[1:]
    return "\n".join(lines).strip()


def sections(doc):
    """{section title: {entry name: description}} of a numpy-style docstring."""
    out = {}
    lines = doc.splitlines()
    i = 0
    while i < len(lines):
        if i + 1 < len(lines) and re.fullmatch(r"-{3,}", lines[i + 1].strip()) and lines[i].strip():
            title = lines[i].strip()
            entries = {}
            i += 2
            current = None
            while i < len(lines) and not (i + 1 < len(lines) and re.fullmatch(r"-{3,}", lines[i + 1].strip())):
                line = lines[i]
                if line.strip() and not line.startswith(" "):
                    head = line.split(" : ")[0].strip()
                    current = [n.strip() for n in head.split(",")]
                    for n in current:
                        entries[n] = line.split(" : ", 1)[1] if " : " in line else ""
                elif current is not None:
                    for n in current:
                        entries[n] += " " + line.strip()
                i += 1
            out[title] = entries
        else:
            i += 1
    return out


def signature_line_params(obj):
    """Parameter names from nanobind's signature line `name(a: T, *, b: T = 1) -> R`, and whether it returns."""
    first = (obj.__doc__ or "").splitlines()[0]
    body = first[first.index("(") + 1:]
    depth, names, piece, returns = 0, [], "", True
    for k, ch in enumerate(body):
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            if depth == 0:
                returns = not body[k + 1:].strip().startswith("-> None")
                break
            depth -= 1
        if ch == "," and depth == 0:
            names.append(piece)
            piece = ""
        else:
            piece += ch
    names.append(piece)
    names = [re.split(r"[:=]", n)[0].strip() for n in names]
    return [n for n in names if n and n not in ("*", "/", "self") and not n.startswith("*")], returns


def params_and_returns(obj):
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return signature_line_params(obj)
    names = [p.name for p in sig.parameters.values()
             if p.name != "self" and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    ret = sig.return_annotation
    returns = ret not in (None, "None", inspect.Signature.empty) or obj.__name__ == "__getattr__"
    return names, returns


def public(module):
    return [(f"{module.__name__}.{n}", getattr(module, n)) for n in module.__all__]


FUNCTIONS = [(n, o) for m in (topple, plot) for n, o in public(m) if callable(o) and not inspect.isclass(o)]
CLASSES = [(n, o) for m in (topple, plot) for n, o in public(m) if inspect.isclass(o)]
METHODS = [(f"{cn}.{n}", getattr(c, n)) for cn, c in CLASSES for n, v in vars(c).items()
           if not n.startswith("_") and callable(getattr(c, n)) and not isinstance(v, property)
           and not issubclass(c, BaseException)]


def check_units(where, entries):
    for name, text in entries.items():
        pattern = unit_pattern(name)
        if pattern is not None:
            assert re.search(pattern, text), f"{where}: {name} does not name its unit ({pattern}): {text!r}"


@pytest.mark.parametrize("name,obj", FUNCTIONS + METHODS, ids=[n for n, _ in FUNCTIONS + METHODS])
def test_function_docstring(name, obj):
    doc = doc_of(obj)
    assert doc and doc.splitlines()[0].strip(), f"{name} has no docstring"
    secs = sections(doc)
    params, returns = params_and_returns(obj)
    if params:
        assert "Parameters" in secs, f"{name}: no Parameters section"
        missing = [p for p in params if p not in secs["Parameters"]]
        assert not missing, f"{name}: parameters not documented: {missing}"
        check_units(name, secs["Parameters"])
    if returns:
        assert "Returns" in secs, f"{name}: no Returns section"
        assert all(v.strip() for v in secs["Returns"].values()) or secs["Returns"], f"{name}: empty Returns"


@pytest.mark.parametrize("name,cls", CLASSES, ids=[n for n, _ in CLASSES])
def test_class_docstring(name, cls):
    doc = doc_of(cls)
    assert doc and doc.splitlines()[0].strip(), f"{name} has no docstring"
    secs = sections(doc)
    attributes = [n for n, v in vars(cls).items()
                  if not n.startswith("_") and (isinstance(v, property) or not callable(v))]
    if issubclass(cls, BaseException):
        attributes = ["file", "line", "field", "problem"]
    if attributes:
        assert "Attributes" in secs, f"{name}: no Attributes section"
        missing = [a for a in attributes if a not in secs["Attributes"]]
        assert not missing, f"{name}: attributes not documented: {missing}"
        check_units(name, secs["Attributes"])
    if "__init__" in vars(cls) and cls is topple.GroundMotion:
        params, _ = signature_line_params(cls.__init__)
        missing = [p for p in params if p not in secs.get("Parameters", {})]
        assert not missing, f"{name}: constructor parameters not documented: {missing}"
        check_units(name, secs["Parameters"])


def test_help_shows_a_real_docstring():
    text = pydoc.render_doc(topple.Block, renderer=pydoc.plaintext)
    assert "Parameters" in text and "Full base width across the rocking direction" in text
    assert "Returns" in text and "RockingBody" in text
    text = pydoc.render_doc(topple.GroundMotion, renderer=pydoc.plaintext)
    assert "Sample interval, s" in text


def test_the_unit_check_can_fail():
    # The checker itself: a parameter ending in _m documented without a unit is caught, one with it passes.
    with pytest.raises(AssertionError, match="height_m does not name its unit"):
        check_units("f", {"height_m": "Height of the thing."})
    check_units("f", {"height_m": "Height, m.", "zeta_g": "Damping ratio (dimensionless)."})
    assert sections("Parameters\n----------\na, b : float\n    Lengths, m.\n") == {
        "Parameters": {"a": "float Lengths, m.", "b": "float Lengths, m."}}


STUB = pathlib.Path(topple.__file__).with_name("__init__.pyi")


def stub_functions():
    tree = ast.parse(STUB.read_text())
    out = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out[node.name] = node
        elif isinstance(node, ast.ClassDef):
            out[node.name] = node
            for sub in node.body:
                # Overloads: the first one carries the docstring.
                if isinstance(sub, ast.FunctionDef) and f"{node.name}.{sub.name}" not in out:
                    out[f"{node.name}.{sub.name}"] = sub
    return out


def test_stubs_are_in_step_with_the_runtime():
    stubs = stub_functions()
    problems = []
    for name, obj in FUNCTIONS + METHODS:
        if not name.startswith("topple.") or name.startswith("topple.plot."):
            continue
        short = name[len("topple."):]
        node = stubs.get(short)
        if node is None:
            problems.append(f"{short}: no stub")
            continue
        a = node.args
        stub_params = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs if x.arg != "self"]
        params, _ = params_and_returns(obj)
        if stub_params != params:
            problems.append(f"{short}: stub parameters {stub_params} != runtime {params}")
        stub_doc = ast.get_docstring(node)
        summary = doc_of(obj).splitlines()[0].strip()
        if not stub_doc or stub_doc.splitlines()[0].strip() != summary:
            problems.append(f"{short}: stub summary {stub_doc and stub_doc.splitlines()[0]!r} != {summary!r}")
    for name, cls in CLASSES:
        if name.startswith("topple.") and not name.startswith("topple.plot.") and name[7:] not in stubs:
            problems.append(f"{name}: no stub class")
    assert not problems, "\n".join(problems)
