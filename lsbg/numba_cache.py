"""numba's on-disk cache of lsbg's compiled kernels: one per machine and version.

numba keys a cached function on its own source file's path, so each clone of
lsbg compiled its kernels again (about 20 s), and a kernel compiled into a
function of another module went stale when only the kernel's file changed.
Here lsbg's own cache locator keys lsbg's functions on content instead: one
directory ``numba-<hash>`` per version of the compiled sources and of numba,
in a machine-wide root (:func:`numba_cache_root`), shared by every clone.
Importing :mod:`lsbg` installs it (:func:`install`) before any kernel is
compiled; it touches numba only once numba is imported.
"""

import contextlib
import functools
import os
import re
import sys
from pathlib import Path

#: The modules with numba-compiled code (``cache=True``), relative to the package.
COMPILED_MODULES = ("contact/law.py", "contact/kernels.py", "contact/statics.py",
                    "dynamics/settings.py", "dynamics/compiled_engine.py", "solid/render.py",
                    "stats/kernels.py", "tca/surface.py", "tooth/cholesky.py")
#: Versions of the compiled code whose numba caches are kept (the most recently used).
KEEP_CACHES = 3
#: Lock file of each cache sub-directory (see :func:`numba_cache_locator`).
SAVE_LOCK = ".lsbg-save.lock"
_PACKAGE = Path(__file__).resolve().parent            # lsbg/
_VERSION_DIRECTORY = re.compile(r"numba-[0-9a-f]{16}")
_lsbg_cache_paths = set()                                  # sub-directories of lsbg's locators


# ---------------------------------------------------------------------------
# numba's on-disk cache of the compiled kernels: one per machine and version
# ---------------------------------------------------------------------------

def numba_cache_root(given=None):
    """The machine-wide directory that holds the caches of lsbg's compiled kernels.

    Parameters
    ----------
    given : str, optional
        The ``NUMBA_CACHE_DIR`` set by the user (default: the environment's;
        ``""`` means not set).

    Returns
    -------
    pathlib.Path
        ``given`` if set, else ``$XDG_CACHE_HOME/lsbg``, else ``~/.cache/lsbg``
        (a relative ``XDG_CACHE_HOME`` is ignored, as the XDG specification asks).
    """
    given = os.environ.get("NUMBA_CACHE_DIR", "") if given is None else given
    if given:
        return Path(given)
    xdg = os.environ.get("XDG_CACHE_HOME", "")
    return (Path(xdg) if os.path.isabs(xdg) else Path.home() / ".cache") / "lsbg"


def compiled_sources_tag(package=None, numba_version=None):
    """``numba-<hash>``: the name of the cache of one version of the compiled code.

    The hash covers the name and content of every file in
    :data:`COMPILED_MODULES` and the numba version, and nothing about where the
    package lives or when its files were written, so all copies of the same
    sources share one cache.

    Parameters
    ----------
    package : pathlib.Path, optional
        The lsbg package directory (default: this one).
    numba_version : str, optional
        Default: the installed numba's.

    Returns
    -------
    str
        ``"numba-"`` and 16 hexadecimal digits.
    """
    import hashlib

    package = _PACKAGE if package is None else Path(package)
    if numba_version is None:
        numba = sys.modules.get("numba")
        if numba is not None and hasattr(numba, "__version__"):
            numba_version = numba.__version__
        else:
            from importlib.metadata import version
            numba_version = version("numba")
    digest = hashlib.sha256(f"numba {numba_version}".encode())
    for name in COMPILED_MODULES:
        digest.update(b"\0" + name.encode() + b"\0")
        digest.update((package / name).read_bytes())
    return f"numba-{digest.hexdigest()[:16]}"


def _prepare_cache(root, tag):
    """Create and check ``root/tag``, mark it used, drop all but :data:`KEEP_CACHES`."""
    import shutil
    import tempfile

    directory = root / tag
    directory.mkdir(parents=True, exist_ok=True)
    tempfile.TemporaryFile(dir=directory).close()           # writable, as numba checks
    with contextlib.suppress(OSError):                     # not ours (a shared directory)
        os.utime(directory)                                # the most recently used
    versions = sorted((p for p in root.iterdir() if p != directory and p.is_dir()
                       and _VERSION_DIRECTORY.fullmatch(p.name)),
                      key=lambda p: p.stat().st_mtime, reverse=True)
    for old in versions[KEEP_CACHES - 1:]:
        shutil.rmtree(old, ignore_errors=True)
    return directory


def numba_cache_dir(package=None, given=None, numba_version=None):
    """The directory of numba's cache for this version of lsbg's compiled sources.

    numba keys a cached function on its own source file only. A kernel
    compiled into a function of another module (``lsbg.contact.kernels`` into
    ``lsbg.dynamics.compiled_engine.integrate``) is cached with that function
    and stays stale when only the kernel's file changes: measured, an edit of
    kernels.py left the compiled engine running the old kernel. So the cache
    lives in ``numba-<hash>`` (:func:`compiled_sources_tag`: the content of
    every file in :data:`COMPILED_MODULES` and the numba version), and an edit
    of any of them starts a fresh one. The hash does not depend on where the
    package lives, so all copies (clones) of the same sources on a machine
    share one cache under :func:`numba_cache_root`; if that cannot be
    written, the package's own ``__pycache__`` is used. The directory is
    marked as used (its modification time), and all but the
    :data:`KEEP_CACHES` most recently used versions are removed.
    :func:`numba_cache_locator` points numba at this directory for lsbg's
    functions only.

    Parameters
    ----------
    package : pathlib.Path, optional
        The lsbg package directory (default: this one).
    given : str, optional
        The ``NUMBA_CACHE_DIR`` set by the user (default: the environment's).
    numba_version : str, optional
        Default: the installed numba's.

    Returns
    -------
    str or None
        The directory (created and writable), or None if neither place can
        be written (numba then caches lsbg's functions where it would by itself).
    """
    package = _PACKAGE if package is None else Path(package)
    tag = compiled_sources_tag(package, numba_version)
    try:
        roots = [numba_cache_root(given)]
    except RuntimeError:                                   # no home directory
        roots = []
    for root in roots + [package / "__pycache__"]:
        try:
            return str(_prepare_cache(root, tag))
        except OSError:
            continue
    return None


def numba_module_name(py_file, package=None):
    """The dotted module name of a source file inside the lsbg package.

    Parameters
    ----------
    py_file : str or pathlib.Path
        A function's source file (``inspect.getfile``).
    package : pathlib.Path, optional
        The lsbg package directory (default: this one).

    Returns
    -------
    str or None
        E.g. ``"lsbg.contact.kernels"``; None if the file is not a Python
        source file inside ``package``.
    """
    path = Path(py_file)
    if path.suffix != ".py" or not path.is_file():
        return None
    package = _PACKAGE if package is None else Path(package).resolve()
    try:
        parts = path.resolve().relative_to(package).with_suffix("").parts
    except ValueError:
        return None
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(("lsbg",) + parts)


@functools.lru_cache(maxsize=None)
def _cache_directory(given, xdg_cache_home, home, numba_version):
    # one numba_cache_dir (hash, mkdir, clean-up) per process and setting
    return numba_cache_dir(None, given, numba_version)


@contextlib.contextmanager
def numba_save_lock(cache_path):
    """Hold the exclusive save lock of one cache sub-directory.

    Parameters
    ----------
    cache_path : str
        The directory of the index and data files.

    Yields
    ------
    bool
        Whether the lock is held (False where file locks are not available:
        no ``fcntl``, or a file system that refuses them; numba's own
        unlocked save then runs as it would without lsbg).
    """
    try:
        import fcntl
        fd = os.open(os.path.join(cache_path, SAVE_LOCK), os.O_RDWR | os.O_CREAT, 0o666)
    except (ImportError, OSError):
        yield False
        return
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX)
            locked = True
        except OSError:
            locked = False
        yield locked
    finally:
        os.close(fd)                                       # releases the lock


@functools.lru_cache(maxsize=None)
def numba_cache_locator():
    """numba's cache locator for lsbg's functions: by content, one cache per machine.

    numba's own locators key a cached function on the *path* of its source
    file (the cache sub-directory is a hash of the directory) and keep it
    next to the sources or under ``NUMBA_CACHE_DIR``: every fresh clone of
    the repository compiled all kernels again (measured: about 2 x 17 s in
    the first jobs of a study). This locator keys lsbg's functions on content
    only:

    - directory: :func:`numba_cache_dir`, ``<root>/numba-<hash>`` (an edited
      kernel file gets a fresh directory, which numba alone would not do for
      a kernel compiled into another module's function);
    - sub-directory: the module's dotted name (``lsbg.contact.kernels``), not
      a hash of its path;
    - source stamp (stored in the index, compared on load): the directory's
      name and the sha256 of the file's content, not its path or mtime.

    Its ``from_function`` declines (returns None) for functions whose source
    file is outside the lsbg package, and when no cache directory can be
    written: numba's own locators then take over. Importing numba is the
    cost of the first call, so :func:`register_numba_cache_locator` calls it
    only once numba is imported.

    Returns
    -------
    type
        The locator class, a subclass of ``numba.core.caching._CacheLocator``
        (the same class on every call).
    """
    import numba
    from numba.core import caching, config

    class LsbgCacheLocator(caching._CacheLocator):
        """Locates the on-disk cache of a compiled lsbg function by content, not by path.

        Parameters
        ----------
        py_func : function
            The Python function being compiled.
        py_file : str
            Its source file.
        directory : str
            The cache of this version of the compiled sources (:func:`numba_cache_dir`).
        module : str
            The dotted module name of ``py_file`` (:func:`numba_module_name`).
        """

        def __init__(self, py_func, py_file, directory, module):
            self._py_file = py_file                        # numba's warnings use it
            self._lineno = py_func.__code__.co_firstlineno
            self._cache_path = os.path.join(directory, module)
            from lsbg.files import kept_file_digest  # (numba is imported by now)

            self._source_stamp = (Path(directory).name, kept_file_digest(py_file))

        def get_cache_path(self):
            """``<numba_cache_dir()>/<dotted module name>``: the index and data files."""
            return self._cache_path

        def get_source_stamp(self):
            """``("numba-<hash>", sha256 of the source)``: the same for every copy."""
            return self._source_stamp

        def get_disambiguator(self):
            """The function's first line number (as numba's own locators)."""
            return str(self._lineno)

        @classmethod
        def from_function(cls, py_func, py_file):
            """The locator of an lsbg function; None leaves the function to numba."""
            module = numba_module_name(py_file)
            if module is None:
                return None
            directory = _cache_directory(config.CACHE_DIR, os.environ.get("XDG_CACHE_HOME", ""),
                                         os.environ.get("HOME", ""), numba.__version__)
            if directory is None:
                return None
            self = cls(py_func, py_file, directory, module)
            try:
                self.ensure_cache_path()
            except OSError:
                return None
            _lsbg_cache_paths.add(os.path.abspath(self._cache_path))
            return self

    return LsbgCacheLocator


def register_numba_cache_locator():
    """Put :func:`numba_cache_locator` first in numba's locators; lock lsbg's saves.

    The locator must be registered before an lsbg module's cached numba
    functions (``cache=True``) are decorated: numba picks the locator then.
    ``import lsbg`` arranges that without importing numba itself (about
    0.4 s that a stage without kernels does not pay): it registers at once
    if numba is already imported, else right after numba's import (an import
    hook that removes itself), which every compiled module does before its
    decorators. Without effect if the user chose numba's locators with
    ``NUMBA_CACHE_LOCATOR_CLASSES`` (numba then ignores its default list).

    Concurrency: numba writes every index and data file to a temporary file
    and renames it into place, so no process reads a half-written file. Its
    update of a function's index (read, add the new signature, write) is not
    atomic across processes, though: two processes saving different
    signatures (or CPUs, on a cache shared by cluster nodes) of one function
    at once can lose an entry or, with unlucky timing, leave the index
    pointing at the other signature's machine code. So saves into lsbg's
    cache directories hold a lock file (:func:`numba_save_lock`); loads need
    none, because within one ``numba-<hash>`` directory a data file, once
    written, always holds the same signature.

    Idempotent.

    Returns
    -------
    list
        numba's list of locator classes (``CacheImpl._locator_classes``).
    """
    from numba.core import caching

    locator = numba_cache_locator()
    classes = caching.CacheImpl._locator_classes
    classes[:] = [c for c in classes                      # also one of a reloaded lsbg
                  if (c.__module__, c.__qualname__) != (locator.__module__, locator.__qualname__)]
    classes.insert(0, locator)
    save = caching.IndexDataCacheFile.save
    if not getattr(save, "lsbg_locked", False):

        @functools.wraps(save)
        def save_under_lock(self, key, data):
            if os.path.abspath(self._cache_path) not in _lsbg_cache_paths:
                return save(self, key, data)
            with numba_save_lock(self._cache_path):
                return save(self, key, data)

        save_under_lock.lsbg_locked = True
        caching.IndexDataCacheFile.save = save_under_lock
    return classes


class _AfterNumbaImport:
    """Import hook: registers lsbg's cache locator right after numba's import."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname != "numba":
            return None
        with contextlib.suppress(ValueError):
            sys.meta_path.remove(self)                     # once, and not for ourselves
        for finder in sys.meta_path:
            find_spec = getattr(finder, "find_spec", None)
            spec = find_spec(fullname, path, target) if find_spec is not None else None
            if spec is not None:
                break
        else:
            return None
        loader = spec.loader
        if loader is None or not hasattr(loader, "exec_module"):
            return spec
        exec_module = loader.exec_module

        def exec_then_register(module):
            try:
                exec_module(module)
            finally:
                loader.__dict__.pop("exec_module", None)
            _register_or_warn()

        try:
            loader.exec_module = exec_then_register          # this spec's own loader only
        except (AttributeError, TypeError):                  # a loader without __dict__
            pass                                           # numba's default cache
        return spec


def _register_or_warn():
    try:
        register_numba_cache_locator()
    except Exception as error:                              # never break numba's import
        import warnings
        warnings.warn(f"lsbg's kernels use numba's default cache ({error!r})",
                      RuntimeWarning, stacklevel=2)


def install():
    """Register lsbg's cache locator now if numba is loaded, else when it is imported."""
    if "numba" in sys.modules:                                 # numba imported before lsbg
        _register_or_warn()
    elif not any(type(f).__name__ == "_AfterNumbaImport" for f in sys.meta_path):
        sys.meta_path.insert(0, _AfterNumbaImport())
