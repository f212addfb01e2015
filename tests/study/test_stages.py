"""The lsbg sources a command runs, from the imports: what reruns a rule when edited."""

import ast
import json
from pathlib import Path

import pytest

from lsbg.cli import handler_of
from lsbg.study import stages

REPO = Path(__file__).resolve().parents[2]


def command_modules(command):
    handler = handler_of(command)
    return stages.function_closure(handler.__module__.removeprefix("lsbg."), handler.__name__)


def command_tops(command):
    return {name.split(".")[0] for name in command_modules(command)}


def test_a_command_depends_on_its_stage_and_not_on_the_others():
    # the geometry writes the solids: no dynamics, no loaded TCA, no tooth, no statistics
    tops = command_tops("geometry")
    assert {"gear", "solid"} <= tops
    assert not tops & {"dynamics", "tooth", "rating", "stats", "aggregate", "tables", "study"}
    # a run: the dynamics and the real flanks, not the unloaded or loaded TCA's analyses
    modules = command_modules("simulate")
    assert {"dynamics.model", "contact.kernels", "tca.separation"} <= modules
    assert not {"tca.loaded", "tca.vh_map", "tooth.ltca", "experiments.verification"} & modules
    # the loaded TCA reaches the FE stage (compliance fe) and its sensitivity cases
    assert {"tca.loaded", "tooth.ltca", "experiments.sensitivity"} <= command_modules("ltca")
    # the aggregates read datasets: no engine, no FE
    assert not {"dynamics.pybullet_engine", "tooth.ltca"} & command_modules("summary")
    assert "tca.vh_map" in command_modules("misalignment-map")
    assert "tca.vh_map" not in command_modules("tca")


def test_command_modules_import_only_the_shared_options_at_their_top():
    """Every command builds the whole parser, importing every module of lsbg.cli: what one
    imports at its top, every command runs (while its sources name it only for its own), so
    a command's stage is imported inside its handler."""
    for path in sorted((stages.PACKAGE / "cli").glob("*.py")):
        name = f"cli.{path.stem}" if path.stem != "__init__" else "cli"
        top = {m for m in stages._module_level_imports(name, stages.PACKAGE)
               if not m.startswith("cli")}
        # (lsbg.cli itself imports these: every command runs them already)
        allowed = {"", "config", "files", "gear", "gear.design"}
        assert top <= allowed, (name, sorted(top - allowed))


def test_every_subcommand_has_its_sources():
    files = stages.closure_files(command_modules("simulate"), root=REPO)
    assert "lsbg/__init__.py" in files and "lsbg/contact/kernels.py" in files
    assert "lsbg/numba_cache.py" in files     # imported by lsbg/__init__.py
    assert "lsbg/dynamics/__init__.py" in files   # runs before any dynamics submodule
    assert all((REPO / f).is_file() for f in files)
    with pytest.raises(ValueError, match="no such subcommand"):
        handler_of("nosuch")
    with pytest.raises(ValueError, match="no lsbg/nosuch.py"):
        stages.module_files("nosuch")


def write_package(root, files):
    package = root / "lsbg"
    for name, text in files.items():
        path = package / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return package


def test_imports_inside_functions_count_and_packages_run_first(tmp_path):
    package = write_package(tmp_path, {
        "__init__.py": "", "a.py": "import lsbg.b\n\ndef f():\n    from lsbg import c\n",
        "b.py": "", "c.py": "from lsbg.d.e import thing\n",
        "d/__init__.py": "from lsbg import f\n", "d/e.py": "", "f.py": ""})
    assert stages.module_imports("a", package=package) == {"b", "c"}
    # importing lsbg.d.e runs lsbg/d/__init__.py, which imports lsbg.f
    assert stages.module_closure({"c"}, package=package) == {"", "c", "d", "d.e", "f"}


def test_lazy_exports_resolve_to_their_submodule(tmp_path):
    package = write_package(tmp_path, {
        "__init__.py": "",
        "p/__init__.py": "_EXPORTS = {'one': ('A',), 'two': ('B',)}\n",
        "p/one.py": "", "p/two.py": "import lsbg.q\n", "q.py": "",
        "user.py": "from lsbg.p import A\n"})
    assert stages.module_imports("user", package=package) == {"p.one"}
    assert "p.two" not in stages.module_closure({"user"}, package=package)


def test_command_functions_are_followed_by_call(tmp_path):
    package = write_package(tmp_path, {
        "__init__.py": "", "cli/__init__.py": "", "heavy.py": "", "light.py": "",
        "cli/common.py": "def helper():\n    import lsbg.light\n\n"
                         "def unused():\n    import lsbg.heavy\n",
        "cli/cmd.py": "from lsbg.cli.common import helper\n\n"
                      "def run(args):\n    return helper()\n\n"
                      "def other(args):\n    import lsbg.heavy\n"})
    modules = stages.function_closure("cli.cmd", "run", package=package)
    assert "light" in modules and "heavy" not in modules
    assert "heavy" in stages.function_closure("cli.cmd", "other", package=package)


@pytest.mark.parametrize("name", ["paper", "sweep", "verification"])
def test_a_report_depends_on_its_notebooks_imports(name):
    path = REPO / "lsbg" / "notebooks" / f"{name}.ipynb"
    modules = stages.notebook_closure(path)
    cells = json.loads(path.read_text())["cells"]
    assert any("lsbg" in "".join(c["source"]) for c in cells if c["cell_type"] == "code")
    assert "tables" in {m.split(".")[0] for m in modules}


def test_import_statements_come_from_the_source_as_it_is_now(tmp_path):
    """Nothing is kept between processes: an edited source is read afresh (its content
    is the key of the process's own memo), so a rule's listing follows the edit."""
    source = tmp_path / "a.py"
    source.write_text("import lsbg.b\n\ndef f():\n    from lsbg.c import d\n")
    assert stages.import_statements(source) == (("lsbg.b", "lsbg.c.d"), ("lsbg.b",))
    source.write_text("import lsbg.e\n")
    assert stages.import_statements(source) == (("lsbg.e",), ("lsbg.e",))
    source.write_text("import lsbg.b\n\ndef f():\n    from lsbg.c import d\n")
    assert stages.import_statements(source)[1] == ("lsbg.b",)


def test_import_statements_read_by_the_scanner_agree_with_the_syntax_tree():
    """Every lsbg source: the names its scanned text imports (everywhere, and at module
    level) are those the syntax tree's import statements name."""
    for path in sorted(stages.PACKAGE.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        level = {name for node in tree.body
                 if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))
                 for name in stages._import_names(node)}
        everywhere, module_level = stages.import_statements(path)
        assert set(everywhere) == set(stages._import_names(tree)), path
        assert set(module_level) == level, path


@pytest.mark.parametrize("source, everywhere, module_level", [
    # nested blocks, a class body, a relative import and a star
    ("import os.path as p\nfrom . import sibling\nif p:\n    from lsbg.a import (b,\n"
     "        c)\nfrom lsbg.z import *\nclass K:\n    import lsbg.k\n    def f(self):\n"
     "        try:\n            import lsbg.t\n        finally:\n"
     "            import lsbg.f\n",
     {"os.path", "lsbg.a.b", "lsbg.a.c", "lsbg.z.*", "lsbg.k", "lsbg.t", "lsbg.f"},
     {"os.path", "lsbg.a.b", "lsbg.a.c", "lsbg.z.*"}),
    # strings and comments that read like imports, one at column 0 inside a function
    ('"""Docs.\n\nimport lsbg.nodoc\n"""\n# import lsbg.nocomment\ns = "from lsbg.x import y"\n'
     "def f():\n    t = '''\nimport lsbg.notemplate\n'''\n    import lsbg.inner\n",
     {"lsbg.inner"}, set()),
    # a decorated definition, a bracket closed at column 0, comments and continuations
    ("@decorate(\n    1)\ndef f():\n    x = [\n1,\n]\n    import lsbg.late\n"
     "from lsbg.m import (one,  # the first\n    two as second)\n"
     "from lsbg.n import three, \\\n    four\nimport lsbg . spaced, lsbg.other as o\n",
     {"lsbg.late", "lsbg.m.one", "lsbg.m.two", "lsbg.n.three", "lsbg.n.four", "lsbg.spaced",
      "lsbg.other"},
     {"lsbg.m.one", "lsbg.m.two", "lsbg.n.three", "lsbg.n.four", "lsbg.spaced", "lsbg.other"}),
])
def test_the_scanner_reads_statements_not_strings(source, everywhere, module_level):
    tree = ast.parse(source)
    assert set(stages._import_names(tree)) == everywhere     # the cases as Python reads them
    found, level = stages._statements(source.encode())
    assert set(found) == everywhere
    assert set(level) == module_level
