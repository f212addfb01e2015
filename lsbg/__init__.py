"""lsbg: logarithmic spiral bevel gears, from exact geometry to meshing statistics.

Physics inside the package is in SI units (m, kg, s, N, rad); the paper's units
(mm, deg, deg/s, N*s/mm) appear only at the edges: configuration, reports and
the ``units`` attributes of written datasets.
"""

import hashlib
import importlib
import os
import shutil
from pathlib import Path

__version__ = "0.1.0"

#: The modules with numba-compiled code (``cache=True``).
COMPILED_MODULES = ("contact/law.py", "contact/kernels.py", "dynamics/settings.py",
                    "dynamics/compiled_engine.py", "render.py")
#: Versions of the compiled code whose numba caches are kept.
KEEP_CACHES = 3


def numba_cache_dir(package=None, given=None):
    """One numba cache directory per version of lsbg's compiled sources.

    numba keys a cached function on its own source file only. A kernel
    compiled into a function of another module (``lsbg.contact.kernels`` into
    ``lsbg.dynamics.compiled_engine.integrate``) is cached with that function
    and stays stale when only the kernel's file changes: measured, an edit of
    kernels.py left the compiled engine running the old kernel. So the cache
    lives in ``numba-<hash of COMPILED_MODULES>`` under ``NUMBA_CACHE_DIR`` (or
    lsbg's ``__pycache__``), and an edit of any of them starts a fresh one;
    all but the newest :data:`KEEP_CACHES` are removed.

    Parameters
    ----------
    package : pathlib.Path, optional
        The lsbg package directory (default: this one).
    given : str, optional
        The ``NUMBA_CACHE_DIR`` set by the user (default: the environment's).

    Returns
    -------
    str or None
        The directory (created), or None if it cannot be created.
    """
    package = Path(__file__).resolve().parent if package is None else Path(package)
    digest = hashlib.sha256()
    for name in COMPILED_MODULES:
        digest.update(name.encode())
        digest.update((package / name).read_bytes())
    tag = f"numba-{digest.hexdigest()[:16]}"
    given = os.environ.get("NUMBA_CACHE_DIR", "") if given is None else given
    if given and Path(given).name.startswith("numba-"):      # set by lsbg in a parent process
        given = str(Path(given).parent)
    root = Path(given) if given else package / "__pycache__"
    directory = root / tag
    try:
        directory.mkdir(parents=True, exist_ok=True)
        versions = sorted((p for p in root.glob("numba-*") if p.is_dir() and p != directory),
                          key=lambda p: p.stat().st_mtime, reverse=True)
        for old in versions[KEEP_CACHES - 1:]:
            shutil.rmtree(old, ignore_errors=True)
    except OSError:
        return None                                 # read-only install: numba's default
    return str(directory)


def _configure_numba_cache():
    directory = numba_cache_dir()
    if directory is None:
        return
    os.environ["NUMBA_CACHE_DIR"] = directory
    numba_config = __import__("sys").modules.get("numba.core.config")
    if numba_config is not None:                    # numba imported before lsbg
        numba_config.CACHE_DIR = directory


_configure_numba_cache()


def lazy_exports(package, exports):
    """``__getattr__`` and ``__dir__`` for a package that re-exports its submodules lazily.

    ``from lsbg import stats; stats.anderson_darling`` then imports
    :mod:`lsbg.stats.normality` (and scipy, statsmodels) only when it is first
    used, so that a stage which needs one light submodule (the steady state,
    the contact models' names) does not pay for all of them at start-up.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    exports : dict
        ``{submodule: names}``: the names each submodule exports.

    Returns
    -------
    tuple
        ``(__getattr__, __dir__)`` to assign in the package's namespace.
    """
    owner = {name: module for module, names in exports.items() for name in names}

    def __getattr__(name):
        if name not in owner:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        return getattr(importlib.import_module(f"{package}.{owner[name]}"), name)

    def __dir__():
        return sorted(owner)

    return __getattr__, __dir__
