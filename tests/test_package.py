"""The package's shape: stages in data-flow order, no import cycle, no plotting in computation."""

import ast
import re
import subprocess
import sys

import pytest

from lsbg.study import stages

PACKAGE = stages.PACKAGE
#: Modules that draw (matplotlib) or render reports: everything else computes.
PLOTTING = ("figures", "reports", "cli")
#: Top-level modules in the order the data flows: a module may import only
#: modules of its own layer or of layers before it.
LAYERS = (
    ("numba_cache", "files", "config", "memo"),
    ("gear",),
    ("solid",),
    ("contact",),
    ("dynamics",),
    ("tca",),
    ("tooth",),
    ("rating",),
    ("practice",),
    ("optimise",),
    ("stats",),
    ("experiments",),
    ("aggregate",),
    ("matched",),
    ("tables",),
    ("figures",),
    ("reports",),
    ("study",),
    ("cli",),
)
MAX_LINES = 620


def module_name(path):
    """Dotted name below lsbg of a source file ('contact.law', 'stats')."""
    parts = list(path.relative_to(PACKAGE).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def import_graph():
    """{module: lsbg modules it imports anywhere (module level or inside functions)}."""
    graph = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        name = module_name(path)
        if not name:
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        # A package's own submodules are its parts, not edges of the graph.
        # (lsbg itself, "", is every module's package: not an edge)
        graph[name] = {m for m in stages._imports(tree, PACKAGE)
                       if m and m != name and not m.startswith(name + ".")}
    return graph


def find_cycle(graph):
    """One import cycle as a list of modules, or None (depth-first search)."""
    state, stack = {}, []

    def visit(node):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            # importing a submodule executes its package first
            targets = [nxt] + [".".join(nxt.split(".")[:k]) for k in range(1, nxt.count(".") + 1)]
            for target in targets:
                if target == node or node.startswith(target + "."):
                    continue
                if state.get(target) == "open":
                    return stack[stack.index(target):] + [target]
                if target not in state and target in graph:
                    found = visit(target)
                    if found:
                        return found
        stack.pop()
        state[node] = "done"
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def test_cycle_finder_finds_a_cycle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": set()}) is None
    # a submodule importing its own package's sibling through the package
    assert find_cycle({"p": {"p.x"}, "p.x": {"q"}, "q": {"p"}}) is not None


def test_no_import_cycle():
    cycle = find_cycle(import_graph())
    assert cycle is None, " -> ".join(cycle)


def test_imports_follow_the_data_flow():
    layer = {name: k for k, names in enumerate(LAYERS) for name in names}
    graph = import_graph()
    tops = {name.split(".")[0] for name in graph}
    assert tops <= set(layer), f"add {sorted(tops - set(layer))} to LAYERS"
    upward = sorted(f"lsbg.{a} imports lsbg.{b}" for a, targets in graph.items() for b in targets
                    if layer[b.split(".")[0]] > layer[a.split(".")[0]])
    assert not upward, upward


def computation_modules():
    return sorted("lsbg." + name for name in import_graph()
                  if name.split(".")[0] not in PLOTTING)


def test_computation_modules_do_not_import_plotting():
    modules = computation_modules()
    assert "lsbg.stats" in modules and "lsbg.tables.paper" in modules
    code = (f"import importlib, sys\n"
            f"for name in {modules!r}:\n"
            f"    importlib.import_module(name)\n"
            f"    bad = sorted(m for m in ('matplotlib', 'seaborn') if m in sys.modules)\n"
            f"    assert not bad, f'{{name}} imports {{bad}}'\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-2000:]


def test_plotting_check_detects_matplotlib():
    proc = subprocess.run([sys.executable, "-c", "import sys, lsbg.figures.base; "
                           "assert 'matplotlib' in sys.modules"], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr


@pytest.mark.parametrize("path", sorted(PACKAGE.rglob("*.py")), ids=module_name)
def test_module_is_one_topic(path):
    lines = len(path.read_text(encoding="utf-8").splitlines())
    assert lines <= MAX_LINES, f"{path.relative_to(PACKAGE.parent)}: {lines} lines"


def test_architecture_page_names_every_module_and_only_real_paths():
    page = (PACKAGE.parent / "docs" / "architecture.md").read_text(encoding="utf-8")
    named = set(re.findall(r"\b((?:lsbg|workflow|tests|docs)/[\w./-]*\w/?)", page))
    missing = sorted(p for p in named if not (PACKAGE.parent / p.rstrip("/")).exists())
    assert not missing, f"docs/architecture.md names paths that do not exist: {missing}"
    modules = {path.relative_to(PACKAGE.parent).as_posix() for path in PACKAGE.glob("*.py")
               if path.name != "__init__.py"}
    packages = {f"lsbg/{path.parent.name}/" for path in PACKAGE.glob("*/__init__.py")}
    unnamed = sorted(m for m in modules | packages
                     if m not in page and not any(m.startswith(p) for p in packages & named))
    assert not unnamed, f"add {unnamed} to docs/architecture.md"


def test_the_package_carries_its_data_files(tmp_path):
    """What an installed lsbg reads besides its modules (the configuration's schema, the
    report notebooks) is package data: setuptools copies it into the build, as into a wheel."""
    import shutil

    from lsbg.config import SCHEMA_PATH
    from lsbg.reports import NOTEBOOK_DIR, available_reports

    repo = PACKAGE.parent
    source = tmp_path / "source"
    source.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(repo / name, source / name)
    shutil.copytree(PACKAGE, source / "lsbg", ignore=shutil.ignore_patterns("__pycache__"))
    build = tmp_path / "build"
    code = ("import sys, setuptools; sys.argv = ['setup.py', '-q', 'build_py', '--build-lib', "
            f"{str(build)!r}]; setuptools.setup()")
    proc = subprocess.run([sys.executable, "-W", "ignore", "-c", code], cwd=source,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr

    def data_files(package):
        return {p.relative_to(package).as_posix() for p in package.rglob("*")
                if p.is_file() and p.suffix not in (".py", ".pyc")}

    shipped = data_files(build / "lsbg")
    assert shipped == data_files(source / "lsbg")
    assert SCHEMA_PATH.relative_to(PACKAGE).as_posix() in shipped
    assert sorted(available_reports()) == ["paper", "sweep", "verification"]
    for name in available_reports():
        assert (NOTEBOOK_DIR / f"{name}.ipynb").relative_to(PACKAGE).as_posix() in shipped
