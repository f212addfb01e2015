"""numba's on-disk cache of lsbg's kernels: one per machine and version of the compiled sources."""

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import pytest

import lsbg
from lsbg import numba_cache

PACKAGE = Path(lsbg.__file__).resolve().parent
NUMBA = "0.68.1"
OLD = 978_307_200                                          # 2001-01-01, an mtime [s]

#: Imports a copy of lsbg and calls a small cached kernel (compiles in about 1 s).
_PROBE = """
import json, lsbg
from lsbg.dynamics.settings import pinion_state
angle, speed = pinion_state(0.01, 100.0, 0.05)
stats = pinion_state.stats
print(json.dumps({"lsbg": lsbg.__file__, "cache": stats.cache_path, "speed": speed,
                  "hits": sum(stats.cache_hits.values()),
                  "misses": sum(stats.cache_misses.values())}))
"""


def _copy_package(destination, mtime=None):
    """A copy of the whole lsbg package under ``destination`` (optionally with old mtimes)."""
    copy = destination / "lsbg"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    if mtime is not None:
        for path in copy.rglob("*"):
            os.utime(path, (mtime, mtime))
    return copy


def _copy_compiled(destination, mtime=None):
    """Only the files of COMPILED_MODULES, enough for numba_cache.numba_cache_dir."""
    for name in numba_cache.COMPILED_MODULES:
        (destination / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(PACKAGE / name, destination / name)
        if mtime is not None:
            os.utime(destination / name, (mtime, mtime))
    return destination


def _probe(copy, xdg, numba_cache_dir=None):
    """Run :data:`_PROBE` with the lsbg package ``copy`` and an isolated cache root."""
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "PYTHONPATH")}
    env.update(XDG_CACHE_HOME=str(xdg), PYTHONPATH=str(copy.parent), PYTHONDONTWRITEBYTECODE="1")
    if numba_cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(numba_cache_dir)
    proc = subprocess.run([sys.executable, "-c", _PROBE], cwd=copy.parent, env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout.splitlines()[-1])
    assert Path(out["lsbg"]).parent == copy               # the copy ran, not /work/main
    assert out["speed"] == pytest.approx(10.4)            # the ramp's STEP at t = 0.01 s
    return out


@pytest.fixture(scope="module")
def first_copy(tmp_path_factory):
    """A copy of lsbg that compiled the probe into a fresh machine-wide cache."""
    root = tmp_path_factory.mktemp("numba_cache")
    xdg = root / "xdg"
    copy = _copy_package(root / "first")
    out = _probe(copy, xdg)
    return dict(root=root, xdg=xdg, copy=copy, out=out)


def test_every_module_with_cached_kernels_is_listed():
    cached = {p.relative_to(PACKAGE).as_posix() for p in PACKAGE.rglob("*.py")
              if re.search(r"jit\([^)]*cache=True", p.read_text(encoding="utf-8"))}
    assert cached == set(numba_cache.COMPILED_MODULES)


def test_the_directory_depends_on_content_and_numba_version_not_on_path(tmp_path, monkeypatch):
    import numba

    here = _copy_compiled(tmp_path / "here")
    there = _copy_compiled(tmp_path / "deeper" / "there", mtime=OLD)
    root = tmp_path / "cache"
    directory = numba_cache.numba_cache_dir(here, str(root), NUMBA)
    assert Path(directory).parent == root and Path(directory).is_dir()
    assert numba_cache.numba_cache_dir(there, str(root), NUMBA) == directory
    assert numba_cache.numba_cache_dir(here, str(root), "0.69.0") != directory
    assert numba_cache.compiled_sources_tag(here) == numba_cache.compiled_sources_tag(here, numba.__version__)
    name = Path(directory).name
    # the root: the user's NUMBA_CACHE_DIR, else $XDG_CACHE_HOME/lsbg, else ~/.cache/lsbg
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert Path(numba_cache.numba_cache_dir(here, None, NUMBA)) == tmp_path / "xdg" / "lsbg" / name
    monkeypatch.setenv("XDG_CACHE_HOME", "relative/ignored")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert Path(numba_cache.numba_cache_dir(here, None, NUMBA)) == tmp_path / "home/.cache/lsbg" / name
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "user"))
    assert Path(numba_cache.numba_cache_dir(here, None, NUMBA)) == tmp_path / "user" / name


def test_lsbg_kernels_use_the_content_keyed_locator():
    from numba.core import caching

    from lsbg.dynamics import settings

    LsbgCacheLocator = numba_cache.numba_cache_locator()
    assert caching.CacheImpl._locator_classes[0] is LsbgCacheLocator
    locator = settings.pinion_state._cache._impl.locator
    assert isinstance(locator, LsbgCacheLocator)
    path = Path(locator.get_cache_path())
    assert path.name == "lsbg.dynamics.settings" and path.parent.name == numba_cache.compiled_sources_tag()
    assert locator.get_source_stamp() == (
        numba_cache.compiled_sources_tag(),
        hashlib.sha256((PACKAGE / "dynamics" / "settings.py").read_bytes()).hexdigest())

    def elsewhere(x):
        return x

    assert LsbgCacheLocator.from_function(elsewhere, __file__) is None   # numba's own


def test_import_lsbg_stays_light_and_registers_the_locator_whatever_the_order():
    check = ("from numba.core import caching; locator = numba_cache.numba_cache_locator(); "
             "assert caching.CacheImpl._locator_classes[0] is locator; "
             "assert caching.CacheImpl._locator_classes.count(locator) == 1; "
             "numba_cache.register_numba_cache_locator(); "
             "assert caching.CacheImpl._locator_classes.count(locator) == 1")
    for code in ("import sys, lsbg; from lsbg import numba_cache; assert 'numba' not in sys.modules; import numba; " + check,
                 "import numba, lsbg; from lsbg import numba_cache; " + check):
        proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                              env=dict(os.environ, PYTHONDONTWRITEBYTECODE="1"))
        assert proc.returncode == 0, proc.stderr


def test_a_second_copy_at_another_path_loads_from_the_cache(first_copy):
    first = first_copy["out"]
    assert (first["misses"], first["hits"]) == (1, 0)     # a fresh cache: compiled
    cache = Path(first["cache"])
    assert cache.name == "lsbg.dynamics.settings"
    assert cache.parent.parent == first_copy["xdg"] / "lsbg"
    second = _copy_package(first_copy["root"] / "elsewhere" / "second", mtime=OLD)
    out = _probe(second, first_copy["xdg"])
    assert (out["hits"], out["misses"]) == (1, 0)         # loaded, not compiled
    assert out["cache"] == first["cache"]
    for copy in (first_copy["copy"], second):
        assert not list(copy.rglob("numba-*"))             # nothing next to the sources


def test_an_edited_kernel_source_gets_a_fresh_cache(first_copy, tmp_path):
    edited = _copy_package(tmp_path)
    # step_scalar (law.py) is compiled into pinion_state (settings.py): numba alone would
    # load the old machine code, as settings.py is unchanged
    law = edited / "contact" / "law.py"
    law.write_text(law.read_text(encoding="utf-8") + "\n# edited\n", encoding="utf-8")
    out = _probe(edited, first_copy["xdg"])
    assert (out["misses"], out["hits"]) == (1, 0)
    assert Path(out["cache"]).parent != Path(first_copy["out"]["cache"]).parent
    assert Path(out["cache"]).parent.parent == first_copy["xdg"] / "lsbg"


def test_old_versions_beyond_keep_caches_are_removed_least_recently_used_first(tmp_path):
    copy = _copy_compiled(tmp_path / "copy")
    root = tmp_path / "cache"
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
    kept = {p for p in root.iterdir()}
    assert kept == {latest, directories[0], directories[2]}   # the second one was least used


def test_an_unwritable_cache_root_falls_back(tmp_path, monkeypatch):
    copy = _copy_compiled(tmp_path / "copy")
    blocked = tmp_path / "a-file"
    blocked.write_text("")                     # nothing can be created below a file, even as root
    directory = Path(numba_cache.numba_cache_dir(copy, str(blocked / "cache"), NUMBA))
    assert directory.parent == copy / "__pycache__" and directory.is_dir()
    shutil.rmtree(copy / "__pycache__")
    (copy / "__pycache__").write_text("")
    assert numba_cache.numba_cache_dir(copy, str(blocked / "cache"), NUMBA) is None
    # no directory at all: the locator declines and numba's own locators take over
    from lsbg.dynamics import settings

    monkeypatch.setattr(numba_cache, "_cache_directory", lambda *args: None)
    assert numba_cache.numba_cache_locator().from_function(
        settings.pinion_state.py_func, settings.__file__) is None


def test_an_unwritable_cache_root_falls_back_to_the_package_pycache(first_copy, tmp_path):
    copy = _copy_package(tmp_path)
    blocked = tmp_path / "a-file"
    blocked.write_text("")
    out = _probe(copy, first_copy["xdg"], numba_cache_dir=blocked / "cache")
    cache = Path(out["cache"])
    assert cache.parent.parent == copy / "__pycache__" and cache.name == "lsbg.dynamics.settings"
    assert (out["misses"], out["hits"]) == (1, 0)


def test_concurrent_saves_into_one_cache_are_serialised(tmp_path, monkeypatch):
    """Two processes saving different signatures of one function must not lose either.

    numba reads a function's index, adds the signature and writes it back;
    without the lock a second save that starts in between loses the first
    signature (or points it at the other's machine code).
    """
    from numba.core.caching import IndexDataCacheFile

    path = tmp_path / "lsbg.module"
    path.mkdir()
    monkeypatch.setattr(numba_cache, "_lsbg_cache_paths", {str(path)})
    first = IndexDataCacheFile(str(path), "module.f-1.py311", ("numba-0", "digest"))
    second = IndexDataCacheFile(str(path), "module.f-1.py311", ("numba-0", "digest"))
    others = []
    load_index = first._load_index

    def load_then_let_the_other_save():
        overloads = load_index()
        if not others:                                     # during the first save only
            other = threading.Thread(target=second.save, args=("signature 2", "code 2"))
            other.start()
            other.join(0.5)
            others.append((other, other.is_alive()))
        return overloads

    first._load_index = load_then_let_the_other_save
    first.save("signature 1", "code 1")
    other, waited = others[0]
    other.join(30)
    assert waited and not other.is_alive()                 # the second save waited for the first
    assert first.load("signature 1") == "code 1"
    assert first.load("signature 2") == "code 2"
    assert sorted(p.name for p in path.glob("*.nbc")) == ["module.f-1.py311.1.nbc",
                                                          "module.f-1.py311.2.nbc"]
