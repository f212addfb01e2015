"""numba's on-disk cache of lsbg's kernels: a directory named by the kernels' sources and numba."""

import ast
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import lsbg
from lsbg import numba_cache

PACKAGE = Path(lsbg.__file__).resolve().parent
NUMBA = "0.68.1"
OLD = 978_307_200                                          # 2001-01-01, an mtime [s]

#: Imports a copy of lsbg and calls a small cached kernel (compiles in about 1 s).
#: pinion_state (dynamics/settings.py) calls contact/law.py's step_scalar, compiled into it.
_PROBE = """
import json, os, lsbg
from lsbg.dynamics.settings import pinion_state
angle, speed = pinion_state(0.01, 100.0, 0.05)
stats = pinion_state.stats
print(json.dumps({"lsbg": lsbg.__file__, "cache": stats.cache_path, "speed": speed,
                  "NUMBA_CACHE_DIR": os.environ["NUMBA_CACHE_DIR"],
                  "hits": sum(stats.cache_hits.values()),
                  "misses": sum(stats.cache_misses.values())}))
"""


def _copy_package(destination):
    """A copy of the whole lsbg package under ``destination``."""
    copy = destination / "lsbg"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    return copy


def _copy_compiled(destination):
    """Only the files of COMPILED_MODULES, enough for numba_cache.numba_cache_dir."""
    for name in numba_cache.COMPILED_MODULES:
        (destination / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(PACKAGE / name, destination / name)
    return destination


def _run(code, copy, xdg, **env):
    """Run ``code`` with the lsbg package ``copy``, an isolated cache root and ``env``."""
    environ = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "PYTHONPATH")}
    environ.update(XDG_CACHE_HOME=str(xdg), PYTHONPATH=str(copy.parent),
                   PYTHONDONTWRITEBYTECODE="1", **env)
    proc = subprocess.run([sys.executable, "-c", code], cwd=copy.parent, env=environ,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def _probe(copy, xdg, **env):
    """Run :data:`_PROBE`: what the kernel's call compiled or loaded, and where."""
    out = json.loads(_run(_PROBE, copy, xdg, **env).splitlines()[-1])
    assert Path(out["lsbg"]).parent == copy               # the copy ran, not /work/main
    assert out["speed"] == pytest.approx(10.4)            # the ramp's STEP at t = 0.01 s
    return out


@pytest.fixture(scope="module")
def first_copy(tmp_path_factory):
    """A copy of lsbg that compiled the probe into a fresh cache root."""
    root = tmp_path_factory.mktemp("numba_cache")
    xdg = root / "xdg"
    copy = _copy_package(root / "first")
    out = _probe(copy, xdg)
    return dict(root=root, xdg=xdg, copy=copy, out=out)


def test_every_module_with_cached_kernels_is_listed():
    cached = {p.relative_to(PACKAGE).as_posix() for p in PACKAGE.rglob("*.py")
              if re.search(r"jit\([^)]*cache=True", p.read_text(encoding="utf-8"))}
    assert cached == set(numba_cache.COMPILED_MODULES)


def test_the_directory_is_named_by_the_sources_and_numba_version_not_their_path(tmp_path):
    here = _copy_compiled(tmp_path / "here")
    there = _copy_compiled(tmp_path / "deeper" / "there")
    for path in there.rglob("*.py"):
        os.utime(path, (OLD, OLD))
    root = tmp_path / "cache"
    directory = Path(numba_cache.numba_cache_dir(here, str(root), NUMBA))
    assert directory.parent == root and directory.is_dir()
    assert numba_cache.VERSION_DIRECTORY.fullmatch(directory.name)
    assert Path(numba_cache.numba_cache_dir(there, str(root), NUMBA)) == directory
    # another numba: another directory; the default is the installed numba's
    assert Path(numba_cache.numba_cache_dir(here, str(root), "0.69.0")) != directory
    import numba

    assert numba_cache.compiled_sources_tag(here) == \
        numba_cache.compiled_sources_tag(here, numba.__version__)
    # an edit of any compiled module: another directory
    for name in ("contact/law.py", "tooth/cholesky.py"):
        edited = _copy_compiled(tmp_path / name.replace("/", "-"))
        (edited / name).write_text((edited / name).read_text(encoding="utf-8") + "\n# edited\n",
                                   encoding="utf-8")
        assert numba_cache.compiled_sources_tag(edited, NUMBA) != directory.name, name


def test_the_root_is_the_users_numba_cache_dir_else_the_xdg_cache(tmp_path, monkeypatch):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert numba_cache.numba_cache_root() == tmp_path / "xdg" / "lsbg"
    monkeypatch.setenv("XDG_CACHE_HOME", "relative/ignored")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert numba_cache.numba_cache_root() == tmp_path / "home" / ".cache" / "lsbg"
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "user"))
    assert numba_cache.numba_cache_root() == tmp_path / "user"
    # what install() hands the processes it starts: one version's directory, not a new root
    tag = numba_cache.compiled_sources_tag()
    assert numba_cache.numba_cache_root(str(tmp_path / "user" / tag)) == tmp_path / "user"
    assert numba_cache.numba_cache_dir(given=str(tmp_path / "user" / tag)) == \
        str(tmp_path / "user" / tag)


def test_import_lsbg_sets_numba_cache_dir_whatever_the_order(tmp_path):
    copy = _copy_package(tmp_path / "copy")
    directory = str(tmp_path / "xdg" / "lsbg" / numba_cache.compiled_sources_tag(copy))
    out = _run("import os, sys, lsbg; assert 'numba' not in sys.modules; "
               "import numba; print(numba.config.CACHE_DIR)", copy, tmp_path / "xdg")
    assert out.split() == [directory]
    out = _run("import os, numba, lsbg; print(numba.config.CACHE_DIR)", copy, tmp_path / "xdg")
    assert out.split() == [directory]
    user = tmp_path / "user"
    out = _run("import os, lsbg; print(os.environ['NUMBA_CACHE_DIR'])", copy, tmp_path / "xdg",
               NUMBA_CACHE_DIR=str(user))
    assert out.split() == [str(user / Path(directory).name)]
    environ = {"NUMBA_CACHE_DIR": str(user)}
    before = os.environ.get("NUMBA_CACHE_DIR")
    tag = numba_cache.compiled_sources_tag()
    assert numba_cache.install(environ) == str(user / tag) == environ["NUMBA_CACHE_DIR"]
    assert numba_cache.install(environ) == str(user / tag)          # idempotent
    assert os.environ.get("NUMBA_CACHE_DIR") == before


def test_a_second_process_loads_the_kernel_from_the_cache(first_copy):
    first = first_copy["out"]
    assert (first["misses"], first["hits"]) == (1, 0)     # a fresh cache: compiled
    directory = Path(first["NUMBA_CACHE_DIR"])
    assert directory == first_copy["xdg"] / "lsbg" / numba_cache.compiled_sources_tag(
        first_copy["copy"])
    assert Path(first["cache"]).parent == directory
    assert list(Path(first["cache"]).glob("settings.pinion_state-*.nbc"))
    out = _probe(first_copy["copy"], first_copy["xdg"])
    assert (out["hits"], out["misses"]) == (1, 0)         # loaded, not compiled
    assert out["cache"] == first["cache"]
    # a job started by an lsbg process inherits its NUMBA_CACHE_DIR: the same cache
    out = _probe(first_copy["copy"], first_copy["xdg"], NUMBA_CACHE_DIR=str(directory))
    assert (out["hits"], out["misses"]) == (1, 0) and out["cache"] == first["cache"]
    assert not list(first_copy["copy"].rglob("*.nbi"))    # nothing next to the sources


def test_an_edited_kernel_source_gets_a_fresh_cache(first_copy, tmp_path):
    edited = _copy_package(tmp_path)
    # step_scalar (law.py) is compiled into pinion_state (settings.py): numba alone would
    # load the old machine code, as settings.py is unchanged
    law = edited / "contact" / "law.py"
    law.write_text(law.read_text(encoding="utf-8") + "\n# edited\n", encoding="utf-8")
    out = _probe(edited, first_copy["xdg"])
    assert (out["misses"], out["hits"]) == (1, 0)
    assert Path(out["NUMBA_CACHE_DIR"]) != Path(first_copy["out"]["NUMBA_CACHE_DIR"])
    assert Path(out["NUMBA_CACHE_DIR"]).parent == first_copy["xdg"] / "lsbg"


def test_old_versions_beyond_keep_caches_are_removed_least_recently_used_first(tmp_path):
    copy = _copy_compiled(tmp_path / "copy")
    root = tmp_path / "cache"
    (root / "not-a-version").mkdir(parents=True)           # someone else's: kept
    kernels = copy / "contact" / "kernels.py"
    sources, directories = [], []
    for k in range(numba_cache.KEEP_CACHES):
        kernels.write_text(kernels.read_text(encoding="utf-8") + f"# edit {k}\n", encoding="utf-8")
        sources.append(kernels.read_text(encoding="utf-8"))
        directories.append(Path(numba_cache.numba_cache_dir(copy, str(root), NUMBA)))
        os.utime(directories[-1], (OLD + k, OLD + k))       # used in this order
    assert len(set(directories)) == numba_cache.KEEP_CACHES
    kernels.write_text(sources[0], encoding="utf-8")       # the oldest version used again
    assert Path(numba_cache.numba_cache_dir(copy, str(root), NUMBA)) == directories[0]
    kernels.write_text(sources[-1] + "# a new version\n", encoding="utf-8")
    latest = Path(numba_cache.numba_cache_dir(copy, str(root), NUMBA))
    kept = set(root.iterdir())
    assert kept == {latest, directories[0], directories[2], root / "not-a-version"}


def test_an_unwritable_cache_root_falls_back_to_the_package_pycache(tmp_path):
    copy = _copy_compiled(tmp_path / "copy")
    blocked = tmp_path / "a-file"
    blocked.write_text("")                     # nothing can be created below a file, even as root
    directory = Path(numba_cache.numba_cache_dir(copy, str(blocked / "cache"), NUMBA))
    assert directory.parent == copy / "__pycache__" and directory.is_dir()
    shutil.rmtree(copy / "__pycache__")
    (copy / "__pycache__").write_text("")
    assert numba_cache.numba_cache_dir(copy, str(blocked / "cache"), NUMBA) is None


def _numba_names(tree):
    """Every dotted numba name a module imports or uses (``numba.core.config.reload_config``)."""
    aliases, names = {}, set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "numba":
                    names.add(alias.name)
                    aliases[alias.asname or alias.name.split(".")[0]] = \
                        alias.name if alias.asname else "numba"
        elif isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "numba":
            for alias in node.names:
                names.add(f"{node.module}.{alias.name}")
                aliases[alias.asname or alias.name] = f"{node.module}.{alias.name}"
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute):
            parts, value = [node.attr], node.value
            while isinstance(value, ast.Attribute):
                parts.append(value.attr)
                value = value.value
            if isinstance(value, ast.Name) and value.id in aliases:
                names.add(".".join([aliases[value.id], *reversed(parts)]))
    return names


def test_the_private_name_check_sees_private_names():
    tree = ast.parse("from numba.core import caching as c\nimport numba\n"
                     "c._CacheLocator\nnumba.core.caching.IndexDataCacheFile.save\n")
    assert {"numba.core.caching._CacheLocator",
            "numba.core.caching.IndexDataCacheFile.save"} <= _numba_names(tree)


def test_lsbg_uses_no_private_name_of_numba():
    private = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        for name in _numba_names(ast.parse(path.read_text(encoding="utf-8"))):
            if name.startswith("numba.core.caching") or \
                    any(part.startswith("_") and not part.startswith("__")
                        for part in name.split(".")):
                private.setdefault(path.relative_to(PACKAGE).as_posix(), []).append(name)
    assert private == {}
