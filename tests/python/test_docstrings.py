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


# ---- One default per option: the Python keyword's is the CLI flag's ----

import os

CLI_MD = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                      "docs", "cli.md")
VERBS = {"branching_construct": "branching construct",
         "branching_simulate": "branching simulate",
         "write_film_strip": "render", "write_gltf": "export"}
# Where the front ends differ on purpose: Python's arrays and outputs are
# arguments (no file to name), eta's default is a rule in both.
DIFFERENT_ON_PURPOSE = {"eta", "output", "png", "gltf", "mask", "time_limit"}


def cli_defaults():
    """{verb: {flag: default text}} from docs/cli.md (generated from the
    flag tables by scripts/cli_reference.sh; ctest docs_cli_reference)."""
    defaults, verb, flag = {}, None, None
    with open(CLI_MD, encoding="utf-8") as f:
        for line in f:
            m = re.match(r"^## (.+)$", line)
            if m:
                verb = m.group(1).strip()
                defaults[verb] = {}
                continue
            m = re.match(r"^  --(\w+) \(", line)
            if m:
                flag = m.group(1)
                continue
            m = re.match(r"^      default: (.*?)(?:; valid: .*)?$", line)
            if m and verb and flag:
                defaults[verb][flag] = m.group(1)
    return defaults


def python_defaults(name):
    first = getattr(shellspace, name).__doc__.split("\n", 1)[0]
    inner = re.match(r"^%s\((.*)\) -> .+$" % re.escape(name), first).group(1)
    return dict(re.findall(r"(\w+): [^=,\[]+(?:\[[^\]]*\])? = ('[^']*'|[^,]+)",
                           inner))


def same_default(python, cli):
    python = python.strip()
    if python.startswith("'"):
        return python.strip("'") == cli.strip('"')
    if python in ("True", "False"):
        return python.lower() == cli
    try:
        return float(python) == float(cli)
    except ValueError:
        return False


COMPARED = []
for _name in FUNCTIONS:
    _verb = VERBS.get(_name, _name)
    for _param, _default in python_defaults(_name).items():
        _flag = "lambda" if _param == "lambda_" else _param
        if _param not in DIFFERENT_ON_PURPOSE and _flag in cli_defaults().get(
                _verb, {}):
            COMPARED.append((_name, _param))


def test_defaults_are_compared_for_the_solving_functions():
    assert ("geodesic", "steps") in COMPARED
    assert ("geodesic", "multires") in COMPARED
    assert ("pca", "modes") in COMPARED
    assert len(COMPARED) >= 60, len(COMPARED)


@pytest.mark.parametrize("name,param", COMPARED)
def test_the_python_default_is_the_cli_default(name, param):
    flag = "lambda" if param == "lambda_" else param
    python = python_defaults(name)[param]
    cli = cli_defaults()[VERBS.get(name, name)][flag]
    assert same_default(python, cli), (python, cli)


def test_a_changed_default_is_caught():
    assert same_default("8", "8") and same_default("'auto'", "auto")
    assert same_default("1e-08", "1e-08") and same_default("False", "false")
    assert not same_default("9", "8")
    assert not same_default("'off'", "auto")
    assert not same_default("True", "false")
