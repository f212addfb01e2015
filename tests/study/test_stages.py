"""The lsbg sources a command runs, from the imports: what reruns a rule when edited."""

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


def test_answers_are_kept_until_an_input_or_a_source_changes(tmp_path, monkeypatch):
    monkeypatch.setattr(stages, "_ANSWERS", {})
    calls = []
    code = "tca.checks"

    def compute():
        calls.append(1)
        return ["a problem"]

    assert stages.cached_answer(tmp_path, code, {"x": 1}, compute) == ["a problem"]
    assert stages.cached_answer(tmp_path, code, {"x": 1}, compute) == ["a problem"]
    assert len(calls) == 1 and len(list(tmp_path.glob("*.json"))) == 1
    monkeypatch.setattr(stages, "_ANSWERS", {})                 # another process: from disk
    assert stages.cached_answer(tmp_path, code, {"x": 1}, compute) == ["a problem"]
    assert len(calls) == 1
    stages.cached_answer(tmp_path, code, {"x": 2}, compute)   # another input
    assert len(calls) == 2
    # the key holds the code's sources: their digest changes with any of its files
    assert stages.sources_digest(code) != stages.sources_digest("aggregate.summary")
    monkeypatch.setattr(stages, "sources_digest", lambda modules: "edited")
    stages.cached_answer(tmp_path, code, {"x": 1}, compute)
    assert len(calls) == 3
    # a corrupt entry is computed again; the oldest go beyond CACHE_ENTRIES
    monkeypatch.setattr(stages, "_ANSWERS", {})
    for path in tmp_path.glob("*.json"):
        path.write_text("{not json")
    monkeypatch.setattr(stages, "CACHE_ENTRIES", 2)
    stages.cached_answer(tmp_path, code, {"x": 1}, compute)
    assert len(calls) == 4 and len(list(tmp_path.glob("*.json"))) == 2
    # without a folder, or one that cannot be written: kept by the process only
    assert stages.cached_answer(None, code, {"x": 9}, compute) == ["a problem"]
    blocked = tmp_path / "file"
    blocked.write_text("")
    assert stages.cached_answer(blocked, code, {"x": 10}, compute) == ["a problem"]
    assert len(calls) == 6


def test_import_statements_are_kept_by_content_between_processes(tmp_path, monkeypatch):
    kept = tmp_path / "cache" / "source-imports.json"
    monkeypatch.setattr(stages, "_statements_file", lambda: kept)
    monkeypatch.setattr(stages, "_STATEMENTS", {"known": None, "grown": False})
    source = tmp_path / "a.py"
    source.write_text("import lsbg.b\n\ndef f():\n    from lsbg.c import d\n")
    assert stages.import_statements(source) == [["lsbg.b", "lsbg.c.d"], ["lsbg.b"]]
    stages._keep_statements()                           # the process's end
    assert len(json.loads(kept.read_text())) == 1
    # another process reads them from the file, without parsing the source
    monkeypatch.setattr(stages, "_STATEMENTS", {"known": None, "grown": False})
    monkeypatch.setattr(stages.ast, "parse", lambda text: pytest.fail("parsed again"))
    assert stages.import_statements(source) == [["lsbg.b", "lsbg.c.d"], ["lsbg.b"]]
    monkeypatch.undo()
    # an edited source is read afresh: the key is its content
    monkeypatch.setattr(stages, "_statements_file", lambda: kept)
    monkeypatch.setattr(stages, "_STATEMENTS", {"known": None, "grown": False})
    source.write_text("import lsbg.e\n")
    assert stages.import_statements(source) == [["lsbg.e"], ["lsbg.e"]]
    # a corrupt file is ignored (and replaced at the end)
    kept.write_text("{not json")
    monkeypatch.setattr(stages, "_STATEMENTS", {"known": None, "grown": False})
    assert stages.import_statements(source) == [["lsbg.e"], ["lsbg.e"]]
    stages._keep_statements()
    assert len(json.loads(kept.read_text())) == 1


def test_the_package_digest_follows_content_names_and_new_files(tmp_path):
    """The key under which the commands' closures are kept (workflow/rules/common.smk):
    it moves with a file's content, its name or a new file, not with a time stamp alone."""
    import os

    package = write_package(tmp_path, {"__init__.py": "", "a.py": "import lsbg.b\n",
                                       "b.py": "X = 1\n"})
    first = stages.package_digest(package)
    assert stages.package_digest(package) == first
    os.utime(package / "a.py", ns=(1, 1))                  # touched, the same content
    assert stages.package_digest(package) == first
    (package / "b.py").write_text("X = 2\n")
    second = stages.package_digest(package)
    assert second != first
    (package / "b.py").write_text("X = 1\n")
    assert stages.package_digest(package) == first
    (package / "c").mkdir()
    (package / "c" / "__init__.py").write_text("")
    assert stages.package_digest(package) not in (first, second)
    (package / "c" / "__init__.py").unlink()
    (package / "b.py").rename(package / "d.py")
    assert stages.package_digest(package) not in (first, second)
