"""numba's on-disk cache of lsbg's kernels, in a directory named by their sources.

numba keys a cached function on its own source file (path, modification time
and size). A kernel compiled into a function of another module
(``lsbg.contact.kernels`` into ``lsbg.dynamics.compiled_engine.integrate``)
is cached with that function, so numba alone keeps loading the old machine
code when only the kernel's file changes. lsbg therefore sets numba's own
setting ``NUMBA_CACHE_DIR`` to a directory ``<root>/numba-<hash>``
(:func:`numba_cache_dir`), the hash taken over the content of every module
with cached kernels (:data:`COMPILED_MODULES`) and numba's version
(:func:`compiled_sources_tag`): an edit of any of them, or another numba,
gives another directory, and a stale cache is never read.

The root (:func:`numba_cache_root`) is the user's ``NUMBA_CACHE_DIR`` if set,
else ``$XDG_CACHE_HOME/lsbg``, else ``~/.cache/lsbg``. ``import lsbg`` sets
the variable (:func:`install`) before any kernel is decorated, without
importing numba; processes started from there (the workflow's jobs) inherit
it. Every numba function with ``cache=True`` in the process is then cached
there, lsbg's or not. Inside the directory numba keeps each source folder's
functions apart by the folder's path, so each copy of lsbg (a clone, an
installation) compiles its kernels once. numba's update of a function's
index is not locked between processes; the workflow's first job (rule
``kernels``) compiles the study's kernels before the jobs that share them.
"""

import hashlib
import os
import re
import shutil
import sys
import tempfile
from importlib import metadata
from pathlib import Path

__all__ = ["COMPILED_MODULES", "KEEP_CACHES", "numba_cache_root", "compiled_sources_tag",
           "numba_cache_dir", "numba_module_name", "install"]

#: The modules with numba-compiled code (``cache=True``), relative to the package.
COMPILED_MODULES = ("contact/law.py", "contact/kernels.py", "contact/statics.py",
                    "dynamics/settings.py", "dynamics/compiled_engine.py", "dynamics/driveline.py",
                    "solid/render.py",
                    "stats/kernels.py", "tca/surface.py", "tooth/cholesky.py")
#: Versions of the compiled sources whose caches are kept in a root (the most recently used).
KEEP_CACHES = 3
PACKAGE = Path(__file__).resolve().parent                  # lsbg/
VERSION_DIRECTORY = re.compile(r"numba-[0-9a-f]{16}")


def numba_cache_root(given=None):
    """The directory that holds the caches of lsbg's kernels, one per version.

    Parameters
    ----------
    given : str, optional
        ``NUMBA_CACHE_DIR`` (default: the environment's; ``""`` means not
        set). A value that is itself one version's directory (``.../numba-<hash>``,
        as :func:`install` sets it for the processes it starts) stands for its parent.

    Returns
    -------
    pathlib.Path
        ``given`` if set, else ``$XDG_CACHE_HOME/lsbg``, else ``~/.cache/lsbg``
        (a relative ``XDG_CACHE_HOME`` is ignored, as the XDG specification asks).
    """
    given = os.environ.get("NUMBA_CACHE_DIR", "") if given is None else given
    if given:
        path = Path(given)
        return path.parent if VERSION_DIRECTORY.fullmatch(path.name) else path
    xdg = os.environ.get("XDG_CACHE_HOME", "")
    return (Path(xdg) if os.path.isabs(xdg) else Path.home() / ".cache") / "lsbg"


def compiled_sources_tag(package=None, numba_version=None):
    """``numba-<hash>``: the name of the cache of one version of the compiled sources.

    The hash covers the name and content of every file in
    :data:`COMPILED_MODULES` and numba's version, nothing about where the
    package lives or when its files were written.

    Parameters
    ----------
    package : pathlib.Path, optional
        The lsbg package directory (default: this one).
    numba_version : str, optional
        Default: the installed numba's (read from its metadata, numba is not imported).

    Returns
    -------
    str
        ``"numba-"`` and 16 hexadecimal digits.
    """
    package = PACKAGE if package is None else Path(package)
    if numba_version is None:
        numba_version = metadata.version("numba")
    digest = hashlib.sha256(f"numba {numba_version}".encode())
    for name in COMPILED_MODULES:
        digest.update(b"\0" + name.encode() + b"\0")
        digest.update((package / name).read_bytes())
    return f"numba-{digest.hexdigest()[:16]}"


def _prepare(root, tag):
    """Create and check ``root/tag``, mark it used, drop all but :data:`KEEP_CACHES` versions."""
    directory = root / tag
    directory.mkdir(parents=True, exist_ok=True)
    tempfile.TemporaryFile(dir=directory).close()          # writable, as numba checks
    try:
        os.utime(directory)                                # the most recently used
    except OSError:                                        # not ours (a shared directory)
        pass
    versions = sorted((p for p in root.iterdir() if p != directory and p.is_dir()
                       and VERSION_DIRECTORY.fullmatch(p.name)),
                      key=lambda p: p.stat().st_mtime, reverse=True)
    for old in versions[KEEP_CACHES - 1:]:
        shutil.rmtree(old, ignore_errors=True)
    return directory


def numba_cache_dir(package=None, given=None, numba_version=None):
    """The directory of numba's cache for this version of lsbg's compiled sources.

    ``<root>/<tag>`` (:func:`numba_cache_root`, :func:`compiled_sources_tag`),
    created and marked as used (its modification time); all but the
    :data:`KEEP_CACHES` most recently used versions in the root are removed.
    If the root cannot be written, the package's own ``__pycache__`` is used.

    Parameters
    ----------
    package : pathlib.Path, optional
        The lsbg package directory (default: this one).
    given : str, optional
        ``NUMBA_CACHE_DIR`` (default: the environment's).
    numba_version : str, optional
        Default: the installed numba's.

    Returns
    -------
    str or None
        The directory (created and writable), or None if neither place can be
        written (numba then caches where it would by itself).
    """
    package = PACKAGE if package is None else Path(package)
    tag = compiled_sources_tag(package, numba_version)
    try:
        roots = [numba_cache_root(given)]
    except RuntimeError:                                   # no home directory
        roots = []
    for root in roots + [package / "__pycache__"]:
        try:
            return str(_prepare(root, tag))
        except OSError:
            continue
    return None


def numba_module_name(py_file, package=None):
    """The dotted module name of a source file inside the lsbg package.

    Parameters
    ----------
    py_file : str or pathlib.Path
        A source file.
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
    package = PACKAGE if package is None else Path(package).resolve()
    try:
        parts = path.resolve().relative_to(package).with_suffix("").parts
    except ValueError:
        return None
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(("lsbg",) + parts)


def install(environ=None):
    """Point numba's ``NUMBA_CACHE_DIR`` at :func:`numba_cache_dir` (called by ``import lsbg``).

    numba reads the variable when it is imported and again before each
    compilation, and picks a function's cache directory when the function is
    decorated: so if numba is already imported, its configuration is
    reloaded (``numba.core.config.reload_config``) for the kernels lsbg
    decorates afterwards. Idempotent.

    Parameters
    ----------
    environ : dict, optional
        The environment to set (default: ``os.environ``).

    Returns
    -------
    str or None
        The directory set, or None if none can be written (the variable is
        then left as it was).
    """
    environ = os.environ if environ is None else environ
    directory = numba_cache_dir(given=environ.get("NUMBA_CACHE_DIR", ""))
    if directory is None:
        return None
    environ["NUMBA_CACHE_DIR"] = directory
    if "numba" in sys.modules and environ is os.environ:
        from numba.core import config
        config.reload_config()
    return directory
