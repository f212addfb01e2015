"""lsbg: logarithmic spiral bevel gears, from exact geometry to meshing statistics.

Physics inside the package is in SI units (m, kg, s, N, rad); the paper's units
(mm, deg, deg/s, N*s/mm) appear only at the edges: configuration, reports and
the ``units`` attributes of written datasets.

``import lsbg`` gives what a researcher needs (:data:`PUBLIC`, imported when first
used), e.g.::

    import lsbg

    design = lsbg.GearPairDesign.from_units(module_mm=4.5, spiral_angle_deg=35)
    pair = lsbg.GearPair(design)
    crowned = lsbg.RealFlanks.from_config({"lengthwise_crowning_um": 25}, {})
    tca = lsbg.tooth_contact_analysis(pair, crowned.modification)
    ltca = lsbg.pair_loaded_tca(pair, 1964.99, flanks=crowned)

(docs/api.md: the quick start, and where each stage's functions are).
"""

import importlib

__version__ = "0.1.0"

from lsbg import numba_cache as _numba_cache  # noqa: E402

_numba_cache.install()  # NUMBA_CACHE_DIR, before any kernel is decorated

#: The public API: submodule -> the names ``import lsbg`` gives from it.
PUBLIC = {
    "gear.design": ("GearPairDesign", "DesignError"),
    "gear.geometry": ("GearPair",),
    "solid.export": ("write_geometry",),
    "solid.directory": ("read_design",),
    "contact.parameters": ("ContactParameters",),
    "contact.mesh": ("MeshContact",),
    "tca.modification": ("FlankModification",),
    "tca.misalignment": ("Misalignment",),
    "tca.separation": ("RealFlanks",),
    "tca.analysis": ("tooth_contact_analysis",),
    "tca.loaded": ("loaded_tca", "pair_loaded_tca", "ltca_for_geometry"),
    "tca.vh_map": ("misalignment_map",),
    "tooth.compliance": ("ToothMaterial", "FEMeshSettings", "tooth_compliance"),
    "tooth.analysis": ("fe_ltca",),
    "rating.virtual": ("rating_geometry",),
    "rating.iso10300": ("rate",),
    "dynamics.settings": ("SimulationSettings", "SimulationError"),
    "dynamics.model": ("load_model", "simulate"),
    "dynamics.dataset": ("open_run", "open_runs"),
    "files": ("write_dataset", "open_dataset", "InputError"),
    "config": ("resolve_config", "load_schema", "ConfigError"),
}


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


__getattr__, _dir = lazy_exports(__name__, PUBLIC)


def __dir__():
    return sorted(set(globals()) | set(_dir()))


__all__ = ["lazy_exports", "PUBLIC", *(name for names in PUBLIC.values() for name in names)]
