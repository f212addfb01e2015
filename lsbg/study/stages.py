"""The lsbg code a piece of work runs, from the imports: the inputs that rerun a rule when edited.

Snakemake reruns a job when one of its input files changes, so every rule
lists the lsbg source files its command can run. They are not kept by hand:
:func:`function_closure` follows the imports from the command's handler (the
function ``lsbg <command>`` calls, :func:`lsbg.cli.handler_of`), as Python
executes them:

* a module's module-level imports always run, and importing ``lsbg.a.b`` runs
  ``lsbg/a/__init__.py`` first (:func:`module_files` gives the ``__init__.py``
  of every package on the way);
* inside the command-line modules (``lsbg.cli``) only the functions the handler
  calls count, followed through the calls by name, within the module and into
  the other ``lsbg.cli`` modules it imports them from: that is where each
  command imports its stage, so a command depends on its stage and not on the
  others;
* every other module counts whole: all its imports, inside functions too;
* ``from lsbg.pkg import Name`` where ``pkg/__init__.py`` re-exports ``Name``
  lazily (:func:`lsbg.lazy_exports`, its ``_EXPORTS`` table) is the submodule
  that defines ``Name``.

Each source file is parsed once per process (:func:`import_statements`): nothing
is kept between Snakemake starts, so what a rule lists is always what its sources
import as they are now.
"""

from __future__ import annotations

import ast
import functools
import json
import os
import re
from pathlib import Path

from lsbg.files import kept_file_digest

__all__ = ["PACKAGE", "module_files", "import_statements", "module_imports", "module_closure",
           "function_closure", "notebook_closure", "closure_files", "sources_listing",
           "write_if_changed"]

#: The lsbg package directory.
PACKAGE = Path(__file__).resolve().parents[1]
#: The package whose functions are followed call by call (the command line).
COMMAND_PACKAGE = "cli"


@functools.lru_cache(maxsize=None)
def _path(name, package):
    """The source file of an lsbg module or package (its ``__init__.py``), or None.

    Kept per process: a dry run asks for the same modules' files thousands of times.
    """
    base = package.joinpath(*name.split(".")) if name else package
    if base.is_dir() and (base / "__init__.py").is_file():
        return base / "__init__.py"
    path = base.with_suffix(".py")
    return path if path.is_file() else None


def module_files(name, package=PACKAGE):
    """The files Python runs to import an lsbg module: every ``__init__.py`` on the way, then it.

    Parameters
    ----------
    name : str
        Dotted name below lsbg (``"contact.kernels"``, ``"stats"``; ``""``: lsbg).
    package : pathlib.Path

    Returns
    -------
    list of pathlib.Path

    Raises
    ------
    ValueError
        If there is no such module.
    """
    parts = name.split(".") if name else []
    files = [package / "__init__.py"]
    for end in range(1, len(parts) + 1):
        path = _path(".".join(parts[:end]), package)
        if path is None:
            raise ValueError(f"lsbg module {name!r}: no "
                             f"{Path(package.name, *parts).with_suffix('.py')}")
        files.append(path)
    return list(dict.fromkeys(files))


@functools.lru_cache(maxsize=None)
def _tree(path):
    return ast.parse(Path(path).read_text(encoding="utf-8"))


@functools.lru_cache(maxsize=None)
def _lazy_exports(path):
    """``{name: submodule}`` of a package ``__init__.py``'s ``_EXPORTS`` table (lazy_exports)."""
    for node in _tree(path).body:
        if (isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "_EXPORTS"
                                                 for t in node.targets)):
            table = ast.literal_eval(node.value)
            return {name: module for module, names in table.items() for name in names}
    return {}


def _resolve(dotted, package):
    """The lsbg module an imported dotted name stands for (``lsbg.contact.ContactParameters``
    -> ``contact.parameters``), or None outside lsbg."""
    parts = dotted.split(".")
    if parts[0] != "lsbg":
        return None
    parts = parts[1:]
    for end in range(len(parts), -1, -1):
        name = ".".join(parts[:end])
        path = _path(name, package)
        if path is None:
            continue
        if end < len(parts) and path.name == "__init__.py":
            owner = _lazy_exports(str(path)).get(parts[end])
            if owner:
                return f"{name}.{owner}" if name else owner
        return name
    return None


def _import_names(node):
    """The dotted names imported anywhere below an AST node (``from a import b``: ``a.b``),
    as written (absolute imports only)."""
    names = []
    for item in _import_nodes(node):
        if isinstance(item, ast.Import):
            names += [alias.name for alias in item.names]
        elif isinstance(item, ast.ImportFrom) and item.module and not item.level:
            names += [f"{item.module}.{alias.name}" for alias in item.names]
    return names


def _import_nodes(node):
    """The import statements below an AST node, in source order.

    Only statements are followed (the bodies, ``else``, ``finally``, handlers and
    ``case`` blocks): an import is a statement, and the expressions below them are
    most of a tree's nodes.
    """
    todo = [node]
    while todo:
        item = todo.pop()
        if isinstance(item, (ast.Import, ast.ImportFrom)):
            yield item
            continue
        for field in ("cases", "handlers", "finalbody", "orelse", "body"):
            block = getattr(item, field, None)
            if isinstance(block, list):
                todo.extend(reversed(block))


def _resolved(names, package):
    """The lsbg modules dotted names stand for (:func:`_resolve`), the others left out."""
    return {m for m in (_resolve(n, package) for n in names) if m is not None}


def _imports(node, package):
    """lsbg modules imported anywhere below an AST node (dotted names below lsbg)."""
    return _resolved(_import_names(node), package)


def import_statements(path):
    """The dotted names a source file imports: anywhere, and at module level.

    Parameters
    ----------
    path : str or pathlib.Path

    Returns
    -------
    everywhere, module_level : tuple of str
        As written (:func:`_import_names`), each once, not yet resolved to lsbg's
        modules; module level is outside the top-level functions and classes.
    """
    return _statements(Path(path).read_bytes())


@functools.lru_cache(maxsize=None)
def _statements(data):
    """:func:`import_statements` of a source's content (bytes), once per process.

    Read by one pass of a scanner over the text (:data:`_TOKEN`), not by building
    its syntax tree or compiling it: a dry run reads every lsbg source, and
    compiling them was most of the time its listings took. The
    scanner steps over strings and comments, counts brackets, and at the start
    of each logical line reads an ``import`` or ``from ... import`` statement
    (:func:`_imported`); a line at column 0 that starts a ``def``, ``class`` or
    decorator opens a top-level definition, any other line at column 0 closes it.
    A test checks that it names what the syntax tree names for every lsbg source.
    """
    text = data.decode("utf-8")
    everywhere, level = [], []
    depth, in_definition = 0, False
    for token in _TOKEN.finditer(text):
        kind = token.lastgroup
        if kind == "open":
            depth += 1
        elif kind == "close":
            depth -= 1
        elif kind == "line" and depth <= 0:
            start = token.end()
            if start == token.start():
                in_definition = _TOP_DEFINITION.match(text, start) is not None
            names = _imported(text, start)
            everywhere += names
            if not in_definition:
                level += names
    return tuple(dict.fromkeys(everywhere)), tuple(dict.fromkeys(level))


#: What the scanner of :func:`_statements` steps over or stops at, in this order: a
#: string (triple-quoted ones across lines, with their prefixes), a comment, a
#: bracket, and the start of a line's code.
_TOKEN = re.compile(r"""
    (?P<string>[rRbBuUfF]{0,2}(?:'''(?:\\[\s\S]|[^\\])*?'''|\"\"\"(?:\\[\s\S]|[^\\])*?\"\"\"
                              |'(?:\\.|[^\\'\n])*'|"(?:\\.|[^\\"\n])*"))
   |(?P<comment>\#[^\n]*)
   |(?P<open>[(\[{])|(?P<close>[)\]}])
   |(?P<line>^[ \t]*(?=[^\s#]))
""", re.M | re.X)
_TOP_DEFINITION = re.compile(r"(?:async\s+def|def|class)\b|@")
# a blank within a statement: spaces, tabs and backslash-continued line ends
_BLANK = r"(?:[ \t]|\\\n)"
_NAME = r"[A-Za-z_]\w*"
_DOTTED = rf"{_NAME}(?:{_BLANK}*\.{_BLANK}*{_NAME})*"
_ALIASED = rf"{_DOTTED}(?:{_BLANK}+as{_BLANK}+{_NAME})?"
_IMPORT = re.compile(rf"import{_BLANK}+(?P<names>{_ALIASED}(?:{_BLANK}*,{_BLANK}*{_ALIASED})*)")
_FROM = re.compile(rf"from{_BLANK}*(?P<level>\.*){_BLANK}*(?P<module>{_DOTTED})?{_BLANK}+"
                   rf"import{_BLANK}*(?:\((?P<group>[^)]*)\)|(?P<names>\*|{_ALIASED}"
                   rf"(?:{_BLANK}*,{_BLANK}*{_ALIASED})*))")
_ALIAS = re.compile(r"\s+as\s+")


def _imported(text, start):
    """The absolute imports of the statement at ``start``, as :func:`_import_names`
    names them (``from a import b``: ``a.b``), or [] if it imports nothing or relatively."""
    if text.startswith("import", start):
        found = _IMPORT.match(text, start)
        return [_ALIAS.split(name)[0] for name in _items(found["names"])] if found else []
    if not text.startswith("from", start):
        return []
    found = _FROM.match(text, start)
    if found is None or found["level"]:
        return []
    listed = found["group"] if found["group"] is not None else found["names"]
    module = re.sub(r"[\s\\]", "", found["module"])
    return [f"{module}.{_ALIAS.split(name)[0]}" for name in _items(listed)]


def _items(listed):
    """The items of an import's comma-separated list, blanks, comments and continuations out."""
    listed = re.sub(r"#[^\n]*", "", listed).replace("\\\n", " ")
    return [re.sub(r"\s*\.\s*", ".", item.strip()) for item in listed.split(",") if item.strip()]


def module_imports(name, package=PACKAGE):
    """The lsbg modules a module imports, at module level and inside functions.

    Parameters
    ----------
    name : str
        Dotted module name below lsbg (``"dynamics.model"``; a package: its ``__init__``).
    package : pathlib.Path

    Returns
    -------
    set of str
    """
    return set(_module_imports(name, package))


# Kept per process, as the trees are: a rule file asks for the same modules' imports
# dozens of times (a walk over every node of the module each time, half of a dry run).
@functools.lru_cache(maxsize=None)
def _module_imports(name, package):
    everywhere, _ = import_statements(module_files(name, package)[-1])
    return frozenset(_resolved(everywhere, package))


@functools.lru_cache(maxsize=None)
def _module_level_imports(name, package):
    _, level = import_statements(module_files(name, package)[-1])
    return frozenset(_resolved(level, package))


def _parents(name):
    """A module and the packages Python imports before it (``a.b.c`` -> a, a.b, a.b.c)."""
    parts = name.split(".") if name else []
    return {".".join(parts[:end]) for end in range(1, len(parts) + 1)} | {""}


def module_closure(names, package=PACKAGE):
    """Every lsbg module run by importing ``names``: their imports, inside functions too,
    and the packages on the way (``""`` is lsbg itself)."""
    todo, seen = list(names), set()
    while todo:
        name = todo.pop()
        for module in _parents(name):
            if module not in seen:
                seen.add(module)
                todo.extend(_module_imports(module, package))
    return seen


def _defined(tree):
    return {node.name: node for node in tree.body
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))}


def _imported_names(node, package):
    """``{local name: (lsbg module, name there)}`` of the ``from lsbg... import`` below ``node``."""
    names = {}
    for item in _import_nodes(node):
        if isinstance(item, ast.ImportFrom) and item.module and not item.level:
            module = _resolve(item.module, package)
            if module is not None:
                for alias in item.names:
                    names[alias.asname or alias.name] = (module, alias.name)
    return names


@functools.lru_cache(maxsize=None)
def _module_names(name, package):
    """A module's top-level definitions and the ``from lsbg... import`` names anywhere in it."""
    tree = _tree(str(module_files(name, package)[-1]))
    return _defined(tree), _imported_names(tree, package)


@functools.lru_cache(maxsize=None)
def _function_uses(name, function, package):
    """The lsbg modules a top-level definition imports and the names it uses
    (:func:`function_closure`'s step), or None where the module does not define it."""
    node = _module_names(name, package)[0].get(function)
    if node is None:
        return None
    used = frozenset(item.id for item in ast.walk(node)
                     if isinstance(item, ast.Name) and item.id != function)
    return frozenset(_imports(node, package)), _imported_names(node, package), used


def function_closure(module, function, package=PACKAGE):
    """Every lsbg module a function of the command line can run.

    Inside :data:`COMMAND_PACKAGE` the functions it calls are followed by name
    (in its module and into the command-line modules they come from); every
    other module reached counts whole (:func:`module_closure`).

    Parameters
    ----------
    module : str
        Dotted name below lsbg (``"cli.analysis"``).
    function : str
        A function (or class) defined at the module's top level.
    package : pathlib.Path

    Returns
    -------
    set of str
    """
    todo, visited, modules = [(module, function)], set(), set()
    while todo:
        where, name = todo.pop()
        if (where, name) in visited:
            continue
        visited.add((where, name))
        modules |= _parents(where) | _module_level_imports(where, package)
        uses = _function_uses(where, name, package)
        if uses is None:
            continue
        imports, own, used = uses
        modules |= imports
        local, in_module = _module_names(where, package)
        imported = {**in_module, **own}
        for used_name in sorted(used):
            if used_name in local:
                todo.append((where, used_name))
            elif used_name in imported:
                source, target = imported[used_name]
                if source.split(".")[0] == COMMAND_PACKAGE:
                    todo.append((source, target))
    command = {m for m in modules if m.split(".")[0] == COMMAND_PACKAGE}
    return command | module_closure(modules - command, package)


def notebook_closure(path, package=PACKAGE):
    """Every lsbg module a notebook's code cells can run (:func:`module_closure` of their
    imports).

    Parameters
    ----------
    path : str or pathlib.Path
        A Jupyter notebook (``.ipynb``).
    package : pathlib.Path

    Returns
    -------
    set of str
    """
    cells = json.loads(Path(path).read_text(encoding="utf-8"))["cells"]
    imported = set()
    for cell in cells:
        if cell["cell_type"] == "code":
            imported |= _imports(ast.parse("".join(cell["source"])), package)
    return module_closure(imported, package)


def closure_files(modules, root=None, package=PACKAGE):
    """The source files of a set of modules (:func:`module_closure`, :func:`function_closure`).

    Parameters
    ----------
    modules : iterable of str
    root : str or pathlib.Path, optional
        Directory the paths are made relative to (default: absolute paths).
    package : pathlib.Path

    Returns
    -------
    list of str
        Sorted.
    """
    files = {path for name in modules for path in module_files(name, package)}
    if root is None:
        return sorted(str(f) for f in files)
    root = Path(root).resolve()
    return sorted(f.relative_to(root).as_posix() if f.is_relative_to(root) else str(f)
                  for f in files)


def sources_listing(modules, package=PACKAGE):
    """The source files of ``modules`` with their SHA-256, as ``sha256sum`` prints them.

    Parameters
    ----------
    modules : iterable of str
    package : pathlib.Path

    Returns
    -------
    str
        One line per file, ``<hex digest>  lsbg/<path>`` (relative to the repository),
        sorted.
    """
    lines = []
    for name in closure_files(modules, package=package):
        path = Path(name)
        digest = kept_file_digest(path)
        lines.append(f"{digest}  {path.relative_to(package.parent).as_posix()}")
    return "\n".join(lines) + "\n"


def write_if_changed(path, text):
    """Write ``text`` to ``path`` (atomically) only if it holds something else.

    The file's time stamp then moves only when its content changes: a rule that
    takes it as an input reruns exactly then.

    Parameters
    ----------
    path : str or pathlib.Path
    text : str

    Returns
    -------
    pathlib.Path
    """
    path = Path(path)
    try:
        if path.read_text(encoding="utf-8") == text:
            return path
    except OSError:
        pass
    path.parent.mkdir(parents=True, exist_ok=True)
    # not lsbg.files.write_text_atomically: it removes every temporary of the target
    # as a dead writer's, and two Snakemakes may parse one study at once (a dry run
    # beside a run); a temporary named by the process is only ever its own
    part = path.with_name(f".{path.name}.{os.getpid()}.part")
    part.write_text(text, encoding="utf-8")
    part.replace(path)
    return path
