"""The lsbg sources each workflow stage lists cover the code its command really runs."""

import ast
import json
from pathlib import Path

import pytest

from lsbg.study import stages

REPO = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("stage", sorted(stages.STAGE_MODULES))
def test_stage_modules_cover_the_import_graph(stage):
    reached = {name.split(".")[0] for name in stages.stage_closure(stage)}
    declared = set(stages.STAGE_MODULES[stage])
    assert reached <= declared, f"{stage}: add {sorted(reached - declared)} to STAGE_MODULES"
    assert "cli" in declared


def notebook_imports(name):
    cells = json.loads((REPO / "workflow" / "notebooks" / f"{name}.ipynb").read_text())["cells"]
    found = set()
    for cell in cells:
        if cell["cell_type"] == "code":
            tree = ast.parse("".join(cell["source"]))
            found |= stages._imports(tree, stages.PACKAGE)
    return found


@pytest.mark.parametrize("name", ["paper", "sweep", "verification"])
def test_report_stage_covers_the_notebooks(name):
    imported = notebook_imports(name)
    assert imported, name
    reached = {m.split(".")[0] for m in stages.module_closure(imported)}
    declared = set(stages.STAGE_MODULES["report"])
    assert reached <= declared, f"report: add {sorted(reached - declared)}"


def test_stage_sources_are_files_of_the_package():
    files = stages.stage_sources("simulate", root=REPO)
    assert "lsbg/__init__.py" in files and "lsbg/contact/kernels.py" in files
    assert "lsbg/numba_cache.py" in files     # imported by lsbg/__init__.py
    assert "lsbg/dynamics/compiled_engine.py" in files
    assert all((REPO / f).is_file() for f in files)
    assert "lsbg/stats.py" not in files
    with pytest.raises(ValueError, match="stage = 'nosuch'"):
        stages.stage_sources("nosuch")
    with pytest.raises(ValueError, match="no lsbg/nosuch.py"):
        stages.module_files("nosuch")


def test_imports_inside_functions_count(tmp_path):
    package = tmp_path / "lsbg"
    package.mkdir()
    (package / "a.py").write_text("import lsbg.b\n\ndef f():\n    from lsbg import c\n")
    (package / "b.py").write_text("")
    (package / "c.py").write_text("from lsbg.d import thing\n")
    (package / "d.py").write_text("")
    assert stages.imported_modules("a", package=package) == {"b", "c"}
    assert stages.imported_modules("a", functions=(), package=package) == {"b"}


def test_answers_are_kept_until_an_input_or_a_source_changes(tmp_path, monkeypatch):
    monkeypatch.setattr(stages, "_ANSWERS", {})
    calls = []

    def compute():
        calls.append(1)
        return ["a problem"]

    assert stages.cached_answer(tmp_path, "contact_state", {"x": 1}, compute) == ["a problem"]
    assert stages.cached_answer(tmp_path, "contact_state", {"x": 1}, compute) == ["a problem"]
    assert len(calls) == 1 and len(list(tmp_path.glob("*.json"))) == 1
    monkeypatch.setattr(stages, "_ANSWERS", {})                 # another process: from disk
    assert stages.cached_answer(tmp_path, "contact_state", {"x": 1}, compute) == ["a problem"]
    assert len(calls) == 1
    stages.cached_answer(tmp_path, "contact_state", {"x": 2}, compute)   # another input
    assert len(calls) == 2
    # the key holds the stage's sources: their digest changes with any of its files
    assert stages.sources_digest("contact_state") != stages.sources_digest("aggregate")
    monkeypatch.setattr(stages, "sources_digest", lambda stage: "edited")
    stages.cached_answer(tmp_path, "contact_state", {"x": 1}, compute)
    assert len(calls) == 3
    # a corrupt entry is computed again; the oldest go beyond CACHE_ENTRIES
    monkeypatch.setattr(stages, "_ANSWERS", {})
    for path in tmp_path.glob("*.json"):
        path.write_text("{not json")
    monkeypatch.setattr(stages, "CACHE_ENTRIES", 2)
    stages.cached_answer(tmp_path, "contact_state", {"x": 1}, compute)
    assert len(calls) == 4 and len(list(tmp_path.glob("*.json"))) == 2
    # without a folder, or one that cannot be written: kept by the process only
    assert stages.cached_answer(None, "contact_state", {"x": 9}, compute) == ["a problem"]
    blocked = tmp_path / "file"
    blocked.write_text("")
    assert stages.cached_answer(blocked, "contact_state", {"x": 10}, compute) == ["a problem"]
    assert len(calls) == 6
