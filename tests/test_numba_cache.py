"""numba's on-disk cache: one directory per version of lsbg's compiled sources."""

import os
import re
import shutil
from pathlib import Path

import lsbg

PACKAGE = Path(lsbg.__file__).resolve().parent


def test_every_module_with_cached_kernels_is_listed():
    cached = {p.relative_to(PACKAGE).as_posix() for p in PACKAGE.rglob("*.py")
              if re.search(r"jit\([^)]*cache=True", p.read_text(encoding="utf-8"))}
    assert cached == set(lsbg.COMPILED_MODULES)


def test_numba_uses_the_directory_of_this_version():
    import numba

    directory = Path(numba.config.CACHE_DIR)
    assert directory.name.startswith("numba-") and directory.is_dir()
    assert os.environ["NUMBA_CACHE_DIR"] == str(directory)
    assert str(directory) == lsbg.numba_cache_dir(PACKAGE, str(directory.parent))


def test_an_edit_of_a_kernel_source_starts_a_fresh_cache(tmp_path):
    copy = tmp_path / "lsbg"
    for name in lsbg.COMPILED_MODULES:
        (copy / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(PACKAGE / name, copy / name)
    root = tmp_path / "cache"
    before = lsbg.numba_cache_dir(copy, str(root))
    kernels = copy / "contact" / "kernels.py"
    kernels.write_text(kernels.read_text(encoding="utf-8") + "\n# edited\n", encoding="utf-8")
    after = lsbg.numba_cache_dir(copy, str(root))
    assert Path(before).parent == Path(after).parent == root
    assert before != after and Path(after).is_dir()
    # a child process (NUMBA_CACHE_DIR already set by lsbg) keeps the same directory
    assert lsbg.numba_cache_dir(copy, after) == after
    # old versions beyond KEEP_CACHES are removed
    for k in range(lsbg.KEEP_CACHES + 2):
        kernels.write_text(kernels.read_text(encoding="utf-8") + f"# edit {k}\n", encoding="utf-8")
        latest = lsbg.numba_cache_dir(copy, str(root))
    kept = sorted(p.name for p in root.glob("numba-*"))
    assert len(kept) == lsbg.KEEP_CACHES and Path(latest).name in kept
