"""The runtime docstrings (help(shellspace.f)) list every parameter of the
signature on a line of its own, in the signature's order, with a
description: python/parameter_docs.inc is the one of this build."""
import re

import pytest

import shellspace

FUNCTIONS = sorted(
    name for name in dir(shellspace)
    if not name.startswith("_") and callable(getattr(shellspace, name))
    and not isinstance(getattr(shellspace, name), type))


def signature_names(doc, name):
    first = doc.split("\n", 1)[0]
    m = re.match(r"^%s\((.*)\) -> .+$" % re.escape(name), first)
    assert m, "no signature in the docstring of " + name
    return re.findall(r"(?:^|, )(\w+): ", m.group(1))


def parameter_block(doc):
    _, found, block = doc.partition("\nParameters:\n")
    assert found, "no Parameters: block"
    return [line.strip() for line in block.strip("\n").split("\n")]


def test_the_module_has_its_functions():
    assert len(FUNCTIONS) >= 20
    assert "geodesic" in FUNCTIONS and "read_mesh" in FUNCTIONS


@pytest.mark.parametrize("name", FUNCTIONS)
def test_one_line_per_parameter_in_signature_order(name):
    doc = getattr(shellspace, name).__doc__
    names = signature_names(doc, name)
    lines = parameter_block(doc)
    assert [line.split(":", 1)[0] for line in lines] == names
    for line in lines:
        assert len(line.split(":", 1)[1].strip()) > 3, line


def test_defaults_shown_as_in_the_signature():
    lines = parameter_block(shellspace.geodesic.__doc__)
    steps = [line for line in lines if line.startswith("steps:")][0]
    assert steps.endswith("(default 8)")
    start = [line for line in lines if line.startswith("start:")][0]
    assert "(default" not in start


def test_a_doc_without_the_block_is_caught():
    doc = "geodesic(start: object, steps: int = 8) -> object\n\nText."
    with pytest.raises(AssertionError):
        parameter_block(doc)
    doc += "\n\nParameters:\n    steps: K (default 8)"
    names = signature_names(doc, "geodesic")
    assert names == ["start", "steps"]
    assert [line.split(":", 1)[0] for line in parameter_block(doc)] != names
