"""The lsbg code each workflow stage runs: the inputs that rerun a rule when edited.

Snakemake reruns a job when one of its input files changes, so every rule
lists the lsbg modules its command runs (:data:`STAGE_MODULES`, written out
here for a reader to see; :func:`stage_sources` turns them into files). A test
(tests/test_stages.py) checks each list against the real import graph of the
stage's entry points (:data:`STAGE_ENTRIES`), imports inside functions
included, so that a new import cannot be forgotten. An answer of a stage's
code computed while Snakemake starts (the configuration check) is kept on the
same terms: :func:`cached_answer` asks again when a source of the stage changes.
"""

from __future__ import annotations

import ast
import copy
import functools
import hashlib
import json
import os
from pathlib import Path

#: The lsbg package directory.
PACKAGE = Path(__file__).resolve().parents[1]

#: Stage -> the lsbg modules (or packages) its command imports, directly or not.
STAGE_MODULES = {
    # (contact ... theory, ltca and tca: lsbg.cli.options reads the contact and simulation
    # options and the flanks, lsbg.tca, too)
    "geometry": ("cli", "gear", "files", "solid", "contact", "dynamics", "tca"),
    "ltca": ("cli", "gear", "files", "contact", "dynamics", "tca", "tooth", "solid", "sections", "experiments"),
    "tooth": ("cli", "gear", "files", "contact", "dynamics", "tca", "tooth", "solid", "sections"),
    "points": ("cli", "gear", "files", "solid", "contact", "dynamics", "tca", "tooth", "sections"),
    "simulate": ("cli", "gear", "files", "solid", "contact", "dynamics", "experiments", "tca"),
    "convergence": ("cli", "gear", "files", "solid", "contact", "dynamics", "experiments", "tca"),
    "speed": ("cli", "gear", "files", "solid", "contact", "dynamics", "stats", "experiments", "tca"),
    "contact_state": ("cli", "gear", "files", "solid", "contact", "dynamics", "tca", "experiments"),
    "sweep": ("cli", "gear", "files", "contact", "dynamics", "tca", "experiments", "aggregate", "stats", "solid", "numba_cache"),
    "rating": ("cli", "gear", "files", "solid", "contact", "dynamics", "tca", "rating", "aggregate", "stats", "sections"),
    "aggregate": ("cli", "gear", "files", "solid", "contact", "dynamics", "stats", "aggregate", "tca"),
    # the notebooks' imports too (tests/test_stages.py reads them)
    "report": ("cli", "gear", "files", "solid", "contact", "dynamics", "stats", "aggregate", "tca", "reports", "experiments", "tables", "figures", "rating", "sections"),
}

#: Stage -> where its command starts: ``"module:function"`` of the lsbg.cli
#: handlers (the test follows their imports and, from there, every import of
#: every module reached, inside functions too; the module-level imports of all
#: of lsbg.cli count for every stage, since building the parser imports them).
STAGE_ENTRIES = {
    "geometry": ("cli.geometry:run_geometry", "cli.options:design_from_args",
                 "cli.options:_read_yaml"),
    "ltca": ("cli.analysis:run_ltca", "cli.options:contact_from_args",
             "cli.options:flanks_from_args", "cli.options:read_study_sections",
             "cli.options:_read_yaml", "cli.tooth:compliance_from_args",
             "cli.tooth:tooth_from_args"),
    "tooth": ("cli.tooth:run_compliance", "cli.tooth:tooth_from_args",
              "cli.options:read_study_sections", "cli.options:_read_yaml"),
    "rating": ("cli.rating:run_rate", "cli.options:read_study_sections",
               "cli.options:_read_yaml"),
    "points": ("cli.geometry:run_points", "cli.options:design_from_args",
               "cli.options:flanks_from_args", "cli.options:read_study_sections",
               "cli.options:_read_yaml"),
    "simulate": ("cli.simulate:run_simulate", "cli.simulate:run_sensitivity",
                 "cli.options:simulation_from_args", "cli.options:contact_from_args",
                 "cli.options:flanks_from_args", "cli.options:read_study_sections",
                 "cli.options:_read_yaml"),
    "convergence": ("cli.simulate:run_convergence", "cli.options:simulation_from_args",
                    "cli.options:contact_from_args", "cli.options:flanks_from_args",
                    "cli.options:read_study_sections", "cli.options:_read_yaml"),
    "speed": ("cli.speed:run_speed_run", "cli.speed:run_speed_curve",
              "cli.options:simulation_from_args", "cli.options:contact_from_args",
              "cli.options:flanks_from_args", "cli.options:read_study_sections",
              "cli.options:_read_yaml"),
    "contact_state": ("cli.contact_state:run_misalignment_map", "cli.contact_state:run_tca",
                      "cli.contact_state:_tca", "cli.contact_state:_design_pair",
                      "cli.contact_state:_section", "cli.options:contact_from_args",
                      "cli.options:flanks_from_args", "cli.options:read_study_sections",
                      "cli.options:_read_yaml"),
    "aggregate": ("cli.analysis:run_combine", "cli.analysis:run_summary",
                  "cli.options:read_study_sections", "cli.options:_read_yaml"),
    "report": ("cli.analysis:run_report",),
    "sweep": ("cli.sweep:run_sweep_run", "cli.sweep:run_sweep_combine",
              "cli.options:read_study_sections", "cli.options:_read_yaml"),
}


def module_files(name, package=PACKAGE):
    """The source files of an lsbg module or subpackage (``"contact"``, ``"dynamics.model"``).

    Returns
    -------
    list of pathlib.Path
        Absolute paths, sorted.

    Raises
    ------
    ValueError
        If there is no such module.
    """
    base = package.joinpath(*name.split("."))
    if base.is_dir():
        return sorted(base.glob("*.py"))
    path = base.with_suffix(".py")
    if not path.is_file():
        raise ValueError(f"lsbg module {name!r}: no {path.relative_to(package.parent)}")
    return [path]


def stage_sources(stage, root=None):
    """The lsbg source files of a stage (:data:`STAGE_MODULES`), for rule inputs.

    Parameters
    ----------
    stage : str
        A key of :data:`STAGE_MODULES`.
    root : str or pathlib.Path, optional
        Directory the paths are made relative to (default: absolute paths).

    Returns
    -------
    list of str
        ``lsbg/__init__.py`` with ``lsbg/numba_cache.py``, which it imports, and the
        files of the stage's modules.
    """
    if stage not in STAGE_MODULES:
        raise ValueError(f"stage = {stage!r}: must be one of {sorted(STAGE_MODULES)}")
    files = {PACKAGE / "__init__.py", PACKAGE / "numba_cache.py"}
    for name in STAGE_MODULES[stage]:
        files.update(module_files(name))
    if root is None:
        return sorted(str(f) for f in files)
    root = Path(root).resolve()
    return sorted(f.relative_to(root).as_posix() if f.is_relative_to(root) else str(f)
                  for f in files)


def _imports(node, package):
    """lsbg modules imported anywhere below an AST node (dotted names)."""
    found = set()
    for item in ast.walk(node):
        if isinstance(item, ast.Import):
            names = [alias.name for alias in item.names]
        elif isinstance(item, ast.ImportFrom) and item.module and not item.level:
            names = [item.module] + [f"{item.module}.{alias.name}" for alias in item.names]
        else:
            continue
        for imported in names:
            parts = imported.split(".")
            if parts[0] != "lsbg" or len(parts) == 1:
                continue
            # the longest prefix that is a module or package of lsbg
            for end in range(len(parts), 1, -1):
                base = package.joinpath(*parts[1:end])
                if base.is_dir() or base.with_suffix(".py").is_file():
                    found.add(".".join(parts[1:end]))
                    break
    return found


def imported_modules(name, functions=None, package=PACKAGE):
    """The lsbg modules a module imports, at module level and inside functions.

    Parameters
    ----------
    name : str
        Dotted module name below lsbg (``"study"``, ``"dynamics.model"``).
    functions : sequence of str, optional
        Follow only the module-level statements and these functions.
    package : pathlib.Path

    Returns
    -------
    set of str
        Dotted names; ``from lsbg import x`` names the module x.
    """
    found = set()
    for path in module_files(name, package):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        if functions is None:
            found |= _imports(tree, package)
            continue
        for node in tree.body:
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
                if node.name in functions:
                    found |= _imports(node, package)
            else:
                found |= _imports(node, package)
    return found


def module_closure(names, package=PACKAGE):
    """Every lsbg module reached from ``names`` by imports, inside functions too."""
    todo, seen = list(names), set()
    while todo:
        name = todo.pop()
        if name not in seen:
            seen.add(name)
            todo.extend(imported_modules(name, package=package))
    return seen


def stage_closure(stage, package=PACKAGE):
    """Every lsbg module a stage's command can run (dotted names).

    Starts from the module-level imports of lsbg.cli and the stage's handlers
    (:data:`STAGE_ENTRIES`) and follows every import of every module reached.
    """
    start = imported_modules("cli", functions=(), package=package)
    for entry in STAGE_ENTRIES[stage]:
        module, _, function = entry.partition(":")
        start |= imported_modules(module, functions=(function,), package=package)
    return {"cli"} | module_closure(start, package)


# ------------------------------------------------------ answers of a stage
#: Answers :func:`cached_answer` keeps in a folder (the most recently used).
CACHE_ENTRIES = 2000
#: Answers of this process, by key.
_ANSWERS = {}


@functools.lru_cache(maxsize=None)
def sources_digest(stage):
    """SHA-256 of the names and content of a stage's source files (:func:`stage_sources`),
    hexadecimal; computed once per process."""
    digest = hashlib.sha256()
    for name in stage_sources(stage):
        path = Path(name)
        digest.update(path.relative_to(PACKAGE.parent).as_posix().encode() + b"\0")
        digest.update(path.read_bytes() + b"\0")
    return digest.hexdigest()


def cached_answer(folder, stage, inputs, compute):
    """``compute()``, or its answer kept from an earlier call with the same inputs.

    Parameters
    ----------
    folder : str or os.PathLike or None
        Where answers are kept between processes (created if missing; at most
        :data:`CACHE_ENTRIES` files, the least recently used go); None: only in
        this process. A folder that cannot be written keeps nothing.
    stage : str
        The stage whose code ``compute`` runs: a change of its sources
        (:func:`sources_digest`) asks again.
    inputs : JSON-serialisable
        Everything else the answer depends on.
    compute : callable
        Returns the answer, a JSON-serialisable value.
    """
    key = hashlib.sha256(json.dumps([inputs, sources_digest(stage)], sort_keys=True,
                                    default=repr).encode()).hexdigest()[:40]
    if key not in _ANSWERS:
        path = Path(folder) / f"{key}.json" if folder is not None else None
        try:
            _ANSWERS[key] = json.loads(path.read_text(encoding="utf-8"))["answer"]
            os.utime(path)
        except (AttributeError, OSError, ValueError, KeyError, TypeError):
            _ANSWERS[key] = compute()
            if path is not None:
                _keep(path, _ANSWERS[key])
    return copy.deepcopy(_ANSWERS[key])


def _keep(path, answer):
    """Write an answer atomically and drop the least recently used beyond the limit."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        part = path.with_name(f"{path.name}.{os.getpid()}.part")
        part.write_text(json.dumps({"answer": answer}), encoding="utf-8")
        part.replace(path)
        entries = sorted(path.parent.glob("*.json"), key=lambda p: p.stat().st_mtime)
        for old in entries[:max(0, len(entries) - CACHE_ENTRIES)]:
            old.unlink(missing_ok=True)
    except OSError:
        pass
