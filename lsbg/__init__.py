"""lsbg: logarithmic spiral bevel gears, from exact geometry to meshing statistics.

Physics inside the package is in SI units (m, kg, s, N, rad); the paper's units
(mm, deg, deg/s, N*s/mm) appear only at the edges: configuration, reports and
the ``units`` attributes of written datasets.
"""

import importlib

__version__ = "0.1.0"

from lsbg import numba_cache as _numba_cache  # noqa: E402  (before any kernel compiles)

_numba_cache.install()


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
