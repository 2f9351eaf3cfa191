"""The library's field tables (topple/core/field.hpp: one table per result type, the JSON keys of the CLI) against
the Python side: every field is an attribute of the class built from its table, an entry of that class's docstring
(Attributes) and an annotation of its stub (topple/__init__.pyi); a dict built from a table (topple.intensity,
GroundMotion.metadata) has exactly the table's keys, each named in its docstring and stub. So neither the docstrings
nor the stubs can drift from the tables."""
import ast
import pathlib
import re

import pytest

import topple
from topple import _core

from test_docstrings import doc_of, sections

TABLES = _core._field_tables()
CLASS_TABLES = sorted(name for name in TABLES if name[0].isupper() and "." not in name)
# A bare fit (topple.fragility_fit) has no unit: theta_unit is the im_unit of topple.fragility's dict instead.
NOT_ATTRIBUTES = {("FragilityFit", "theta_unit")}
STUB = ast.parse(pathlib.Path(topple.__file__).with_name("__init__.pyi").read_text())


def stub_class(name):
    for node in STUB.body:
        if isinstance(node, ast.ClassDef) and node.name == name:
            return node
    raise AssertionError(f"no stub class {name}")


def stub_members(name):
    """The members a stub class declares, with those of the stub classes it derives from (_SlidingSummary: the fields
    the two sliding results share, written once)."""
    node = stub_class(name)
    members = set()
    for base in node.bases:
        if isinstance(base, ast.Name):
            members |= stub_members(base.id)
    for item in node.body:
        if isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
            members.add(item.target.id)
        elif isinstance(item, ast.FunctionDef):
            members.add(item.name)
    return members


def named_in(name, text):
    return re.search(r"(?<![\w])" + re.escape(name) + r"(?![\w])", text) is not None


def test_the_tables_are_there():
    assert set(TABLES) >= {"SlidingResult", "Sliding2dResult", "RockingResult", "SlideRockResult", "FragilityFit",
                           "intensity", "GroundMotion.metadata"}
    assert all(TABLES.values())


@pytest.mark.parametrize("cls_name", CLASS_TABLES)
def test_class_fields_are_attributes_documented_and_stubbed(cls_name):
    cls = getattr(topple, cls_name)
    attributes = sections(doc_of(cls)).get("Attributes", {})
    stubbed = stub_members(cls_name)
    problems = []
    for field in TABLES[cls_name]:
        if (cls_name, field) in NOT_ATTRIBUTES:
            continue
        if not hasattr(cls, field):
            problems.append(f"{cls_name}.{field}: not an attribute")
        if field not in attributes:
            problems.append(f"{cls_name}.{field}: not in the docstring's Attributes")
        if field not in stubbed:
            problems.append(f"{cls_name}.{field}: not in the stub")
    assert not problems, "\n".join(problems)


def test_intensity_keys_are_the_table():
    motion = topple.GroundMotion([0.0, 0.1, -0.2, 0.05, 0.0] * 40, 0.01)
    assert list(topple.intensity(motion)) == TABLES["intensity"]
    returns = " ".join(sections(doc_of(topple.intensity)).get("Returns", {}).values())
    missing = [k for k in TABLES["intensity"] if not named_in(k, returns)]
    assert not missing, f"topple.intensity's docstring does not name {missing}"


def test_metadata_keys_are_the_table():
    motion = topple.GroundMotion([0.0, 0.1, -0.2, 0.05, 0.0], 0.01)
    assert list(motion.metadata) == TABLES["GroundMotion.metadata"]
    doc = sections(doc_of(topple.GroundMotion))["Attributes"]["metadata"]
    stub = next(ast.get_docstring(n) for n in stub_class("GroundMotion").body
                if isinstance(n, ast.FunctionDef) and n.name == "metadata")
    for where, text in (("docstring", doc), ("stub", stub)):
        missing = [k for k in TABLES["GroundMotion.metadata"] if not named_in(k, text)]
        assert not missing, f"GroundMotion.metadata's {where} does not name {missing}"
