"""Writes the type stubs of the module `shellspace` (shellspace/__init__.pyi).

    python3 python/make_stubs.py [--check] OUTPUT.pyi [PARAMETERS.inc]

with the built module on PYTHONPATH (build/python). Every function, its
parameters one per line with their types and defaults (from the signature
pybind11 writes first in each docstring) and a docstring: the function's own
text, then "Parameters:" with one line per parameter. A parameter's line is
the CLI flag's description of the same name (docs/cli.md, the verb's
--help) or, for the arrays the CLI reads from files, the line of ARRAYS
below. --check compares instead of writing and exits 1 if OUTPUT differs
(ctest python_stubs): after changing a function or a flag, run it without
--check and commit the stub. PARAMETERS.inc (python/parameter_docs.inc) gets
the same "Parameters:" blocks as C++ initialisers: the module compiles them
into its runtime docstrings (python/parameter_docs.h), so help() shows what
the stubs show; rebuild the module after writing it.
"""
import argparse
import os
import re
import sys

import shellspace

HERE = os.path.dirname(os.path.abspath(__file__))
CLI_MD = os.path.join(HERE, "..", "docs", "cli.md")

# The CLI verb whose flags a function shares (its section of docs/cli.md).
VERBS = {"branching_construct": "branching construct",
         "branching_simulate": "branching simulate",
         "write_film_strip": "render", "write_gltf": "export"}

# Parameters that are arrays (or paths) in Python and files on the CLI,
# and the function-specific ones the CLI's text does not fit.
ARRAYS = {
    "F": "#F x 3 integer faces (0-based vertex indices)",
    "V": "#V x 3 float64 vertex positions",
    "reference": "#V x 3 positions of the reference shell",
    "deformed": "#V x 3 positions of the deformed shell",
    "start": "#V x 3 positions of the first shape of the path",
    "end": "#V x 3 positions of the last shape of the path",
    "first": "#V x 3 positions of shape 0",
    "second": "#V x 3 positions of shape 1",
    "a": "#V x 3 positions of the first shape",
    "b": "#V x 3 positions of the second shape",
    "variation": "#V x 3 positions of the variation at the path's start",
    "inputs": "the shapes: K x #V x 3, or a list of #V x 3 arrays",
    "keyframes": "the keyframes: K x #V x 3, or a list of #V x 3 arrays",
    "frames": "the frames: K x #V x 3, or a list of #V x 3 arrays",
    "at": "the time step of each shape (integers in [0, steps])",
    "mask": "vertex indices held fixed, or the path of a mask file",
    "num_vertices": "the vertex count of the mesh the mask is for",
    # Python's side of the CLI's exit codes.
    "time_limit": "stop the solves after this many seconds of wall clock "
                  "(None: no limit); the partial result is raised as "
                  "NotConvergedError's .result unless allow_unconverged",
    "allow_unconverged": "return a result whose solve missed its stopping "
                         "criterion (or was cut by time_limit) instead of "
                         "raising NotConvergedError",
}
# Per function, where the name means something else than above.
SPECIFIC = {
    ("transport", "path"): "the path: K x #V x 3, or a list of #V x 3 arrays",
    ("read_mesh", "path"): "a .ply, .obj or .off file",
    ("read_mask", "path"): "a mask file: one 0-based vertex index per line",
    ("write_mesh", "path"): "the file to write (.ply, .obj or .off)",
    ("write_film_strip", "path"): "the PNG file to write",
    ("write_gltf", "path"): "the .glb file to write",
    ("align_rigidly", "source"): "#V x 3 positions to move",
    ("compare", "a"): "the first shell (#V x 3) or path (K x #V x 3, or a "
                      "list of #V x 3 arrays)",
    ("compare", "b"): "the second shell or path, as a (as many frames as "
                      "a)",
    ("align_rigidly", "target"): "#V x 3 positions to fit them to",
    ("solve_modulo_rigid_motions", "rows"): "row indices of the triplets of "
                                            "H (3#V x 3#V): integers in "
                                            "[0, 3#V)",
    ("solve_modulo_rigid_motions", "cols"): "column indices of the "
                                            "triplets: integers in [0, 3#V)",
    ("solve_modulo_rigid_motions", "vals"): "values of the triplets "
                                            "(duplicates summed)",
    ("solve_modulo_rigid_motions", "rhs"): "the right-hand side, #V x 3 "
                                           "(row v, column c: coordinate "
                                           "3 v + c; a flat 3#V vector is "
                                           "refused)",
    ("solve_modulo_rigid_motions", "shape"): "#V x 3 positions whose rigid "
                                             "motions are factored out",
    ("solve_modulo_rigid_motions", "shift"): "added to the diagonal of the "
                                             "reduced Hessian (finite, "
                                             ">= 0)",
    ("elastic_mean_newton", "initial"): "#V x 3 positions of the start",
    ("elastic_mean_newton", "terms"): "terms(s) -> None or (E, G #V x 3, "
                                      "(rows, cols, vals))",
    ("elastic_mean_newton", "tolerance"): "relative gradient tolerance: "
                                          "|G|_inf <= tolerance * max(1, "
                                          "|G(initial)|_inf)",
    ("elastic_mean_newton", "max_iterations"): "accepted Newton steps",
    ("elastic_mean_newton", "on_step"): "None, or on_step(|G|_inf, E, "
                                        "accepted) after every line search",
    ("elastic_mean_newton", "stop"): "None, or stop() -> True to end before "
                                     "the next step",
    ("pca_modes", "mean"): "#V x 3 positions of the mean",
    ("pca_modes", "displacements"): "the displacements v_i: n x #V x 3, or "
                                    "a list of #V x 3 arrays",
    ("pca_modes", "relative_cutoff"): "modes of the eigenvalues above this "
                                      "times the largest",
    ("aligned_vertex_average", "shapes"): "the shapes: N x #V x 3, or a "
                                          "list of #V x 3 arrays",
    ("energy_gradient", "side"): "the side differentiated: 'reference' or "
                                 "'deformed'",
    ("energy_hessian", "rows"): "the side of the rows: 'reference' or "
                                "'deformed'",
    ("energy_hessian", "cols"): "the side of the columns: 'reference' or "
                                "'deformed'",
}
SHAPE_ARGS = {"reference", "deformed", "start", "end", "first", "second",
              "a", "b", "variation", "V", "F", "at", "source", "target",
              "shape", "rhs", "rows", "cols", "vals", "initial", "mean"}
STACK_ARGS = {"inputs", "keyframes", "frames", "path", "displacements",
              "shapes"}


def cli_flags():
    """{verb: {flag: description}} from docs/cli.md."""
    flags, verb = {}, None
    with open(CLI_MD, encoding="utf-8") as f:
        for line in f:
            m = re.match(r"^## (.+)$", line)
            if m:
                verb = m.group(1).strip()
                flags[verb] = {}
                continue
            m = re.match(r"^  --(\w+) \([\w ]+\)  (.*)$", line)
            if m and verb:
                flags[verb][m.group(1)] = m.group(2).strip()
    return flags


def split_parameters(inner):
    """The parameters of a pybind11 signature: [(name, type, default)]."""
    parts, depth, current, quote = [], 0, "", None
    for c in inner:
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "[(":
            depth += 1
        elif c in "])":
            depth -= 1
        if c == "," and depth == 0 and not quote:
            parts.append(current.strip())
            current = ""
        else:
            current += c
    if current.strip():
        parts.append(current.strip())
    out = []
    for p in parts:
        m = re.match(r"^(\w+): ([^=]+?)(?: = (.*))?$", p)
        if not m:
            raise SystemExit("cannot parse parameter " + repr(p))
        out.append(m.groups())
    return out


def python_type(function, name, kind):
    if kind == "object":
        if function == "transport" and name == "path" or name in STACK_ARGS:
            return "Union[ArrayLike, Sequence[ArrayLike]]"
        if name == "mask":
            return "Union[ArrayLike, str, None]"
        if name in SHAPE_ARGS:
            return "ArrayLike"
        return "Any"
    kind = kind.replace("numpy.ndarray[numpy.float64]", "NDArray[np.float64]")
    kind = kind.replace("List[", "list[")
    return {"tuple": "tuple[Any, ...]"}.get(kind, kind)


def return_type(kind):
    if kind == "object":
        return "Any"
    return python_type("", "", kind)


def describe(function, name, flags):
    if (function, name) in SPECIFIC:
        return SPECIFIC[(function, name)]
    verb = VERBS.get(function, function)
    flag = "lambda" if name == "lambda_" else name
    if flag in flags.get(verb, {}) and name not in ARRAYS:
        return flags[verb][flag]
    if name in ARRAYS:
        return ARRAYS[name]
    for verb_flags in flags.values():  # a flag of another verb
        if flag in verb_flags:
            return verb_flags[flag]
    raise SystemExit("no description of parameter %s of %s: add it to "
                     "python/make_stubs.py" % (name, function))


def docstring(text, indent):
    text = text.replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
    lines = text.rstrip().split("\n")
    out = indent + '"""' + lines[0] + "\n"
    for line in lines[1:]:
        out += (indent + line if line else "") + "\n"
    return out + indent + '"""\n'


def signature_and_text(name, function):
    """The parameters, the return type and the function's own text (without
    the "Parameters:" block the module appends from PARAMETERS.inc)."""
    doc = function.__doc__ or ""
    signature, _, text = doc.partition("\n")
    m = re.match(r"^%s\((.*)\) -> (.+)$" % re.escape(name), signature)
    if not m:
        raise SystemExit("no signature in the docstring of " + name)
    text = re.split(r"\n\s*Parameters:\n", "\n" + text)[0]
    body = re.sub(r"\s*\n\s*", " ", text.strip())
    return split_parameters(m.group(1)), m.group(2).strip(), body


def parameter_lines(name, parameters, flags):
    """["Parameters:", "    name: description (default x)", ...]."""
    lines = ["Parameters:"]
    for pname, _, default in parameters:
        shown = "" if default is None else " (default %s)" % default
        lines.append("    %s: %s%s" % (pname, describe(name, pname, flags),
                                        shown))
    return lines


def function_stub(name, function, flags):
    parameters, returned, body = signature_and_text(name, function)
    out = "def %s(\n" % name
    lines = [body, ""] if body else []
    lines += parameter_lines(name, parameters, flags)
    for pname, kind, default in parameters:
        out += "    %s: %s%s,\n" % (pname, python_type(name, pname, kind),
                                    " = ..." if default is not None else "")
    out += ") -> %s:\n" % RETURNS.get(name, return_type(returned))
    return out + docstring("\n".join(lines), "    ") + "\n"


def functions():
    """The module's functions by name."""
    return [(name, getattr(shellspace, name))
            for name in sorted(dir(shellspace))
            if not name.startswith("_") and callable(getattr(shellspace, name))
            and not isinstance(getattr(shellspace, name), type)]


def parameter_docs():
    """python/parameter_docs.inc: {"function", R"doc(Parameters: ...)doc"},
    per function, read by python/parameter_docs.cc."""
    flags = cli_flags()
    out = ("// Generated by python/make_stubs.py from docs/cli.md and its "
           "arrays' lines:\n// the runtime docstrings' \"Parameters:\" "
           "blocks (python/parameter_docs.h).\n")
    for name, function in functions():
        parameters, _, _ = signature_and_text(name, function)
        block = "\n".join(parameter_lines(name, parameters, flags))
        if ")doc\"" in block:
            raise SystemExit("a parameter text of %s ends the raw string" %
                             name)
        out += '{"%s", R"doc(%s)doc"},\n' % (name, block)
    return out


# The solving functions' result classes (python/module_results.h).
RETURNS = {"geodesic": "GeodesicResult", "log": "LogResult",
           "shoot": "ShootResult", "transport": "TransportResult",
           "spline": "SplineResult", "regress": "RegressResult",
           "mean": "MeanResult", "pca": "PcaResult"}
ARRAY_ATTRIBUTES = {"path", "log", "mean"}


def attribute_type(cls, name, kind):
    kind = kind.strip().replace("shellspace.", "")
    if kind == "object":
        if name in ARRAY_ATTRIBUTES:
            return "NDArray[np.float64]"
        if name == "shapes" and cls == "TransportResult":
            return "NDArray[np.float64]"
        if name == "shapes":
            return "dict[str, NDArray[np.float64]]"
        return "Any"
    kind = kind.replace("List[", "list[")
    return {"dict": "dict[str, Any]", "tuple": "tuple[Any, ...]",
            "Iterator": "Iterator[Any]"}.get(kind, kind)


def class_stub(name, cls):
    """The stub of a bound class: its properties with their types (from
    the getters' signatures), to_dict and the pair protocol."""
    out = "class %s:\n" % name + docstring(cls.__doc__.strip(), "    ")
    for attr, value in vars(cls).items():
        if isinstance(value, property):
            first = (value.fget.__doc__ or "").split("\n")[0]
            m = re.match(r"^\(.*\) -> (.+)$", first)
            kind = attribute_type(name, attr, m.group(1) if m else "object")
            out += "    @property\n    def %s(self) -> %s: ...\n" % (attr,
                                                                    kind)
    methods = {"to_dict": "def to_dict(self) -> dict[str, Any]: ...",
               "__len__": "def __len__(self) -> int: ...",
               "__iter__": "def __iter__(self) -> Iterator[Any]: ...",
               "__getitem__": "def __getitem__(self, index: int) -> Any: ..."}
    for attr, line in methods.items():
        if attr in vars(cls):
            out += "    " + line + "\n"
    return out + "\n"


def options_stub(name, cls, flags):
    """The stub of an options class (python/module_options.h): its
    function's keyword arguments as attributes and keyword-only
    constructor parameters, and the mapping methods."""
    function = cls.function
    parameters, _, _ = signature_and_text(function, getattr(shellspace,
                                                           function))
    options = [(p, python_type(function, p, kind))
               for p, kind, default in parameters if default is not None]
    out = "class %s:\n" % name + docstring(cls.__doc__.strip(), "    ")
    out += "    function: str\n"
    for pname, kind in options:
        out += "    %s: %s\n" % (pname, kind)
    out += "    def __init__(\n        self,\n        *,\n"
    for pname, kind in options:
        out += "        %s: %s = ...,\n" % (pname, kind)
    out += "    ) -> None: ...\n"
    for line in ("def keys(self) -> list[str]: ...",
                 "def __getitem__(self, name: str) -> Any: ...",
                 "def __iter__(self) -> Iterator[str]: ...",
                 "def __len__(self) -> int: ...",
                 "def to_dict(self) -> dict[str, Any]: ..."):
        out += "    " + line + "\n"
    return out + "\n"


def stubs():
    flags = cli_flags()
    out = ('"""Type stubs of the extension module shellspace (generated by '
           'python/make_stubs.py).\n\n' + shellspace.__doc__.strip() +
           '\n"""\nfrom typing import Any, Iterator, Optional, Sequence, Union\n\n'
           'import numpy as np\nfrom numpy.typing import ArrayLike, NDArray\n'
           '\nfrom . import collections as collections\n\n')
    names = sorted(n for n in dir(shellspace) if not n.startswith("_"))
    for name in names:
        value = getattr(shellspace, name)
        if isinstance(value, float):
            out += "%s: float\n\n" % name
    for name in names:
        value = getattr(shellspace, name)
        if isinstance(value, type) and issubclass(value, BaseException):
            out += "\nclass %s(%s):\n" % (name, value.__bases__[0].__name__)
            if value.__doc__ and not value.__doc__.startswith(
                    value.__bases__[0].__doc__ or "\0"):
                out += docstring(value.__doc__.strip(), "    ")
            if name == "NotConvergedError":
                for attribute in ("result", "summary", "failures",
                                  "stop_reason"):
                    out += "    %s: Any\n" % attribute
            elif not value.__doc__:
                out += "    ...\n"
            out += "\n"
    for name in names:
        value = getattr(shellspace, name)
        if isinstance(value, type) and not issubclass(value, BaseException):
            if "function" in vars(value) and "__slots__" in vars(value):
                out += "\n" + options_stub(name, value, flags)
            else:
                out += "\n" + class_stub(name, value)
    out += "\n"
    for name, function in functions():
        out += function_stub(name, function, flags) + "\n"
    return out.rstrip("\n") + "\n"


def check_or_write(path, text, check, command):
    """Writes text to path, or with check returns 1 if path differs."""
    if not check:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        return 0
    try:
        with open(path, encoding="utf-8") as f:
            current = f.read()
    except OSError:
        current = None
    if current == text:
        return 0
    sys.stderr.write(path + " is not the one of this build: run " + command +
                     " (and rebuild the module)\n")
    return 1


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("output")
    parser.add_argument("parameters", nargs="?")
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    command = " ".join(["python3 python/make_stubs.py", args.output] +
                       ([args.parameters] if args.parameters else []))
    failed = check_or_write(args.output, stubs(), args.check, command)
    if args.parameters:
        failed |= check_or_write(args.parameters, parameter_docs(),
                                 args.check, command)
    return failed


if __name__ == "__main__":
    sys.exit(main())
