"""The ``tooth`` section of the study configuration, and the compliance file's reuse.

The section (paper-style units at the edge: GPa, multiples of the mean normal
module) becomes a :class:`lsbg.tooth.compliance.ToothMaterial`, a
:class:`lsbg.tooth.compliance.FEMeshSettings` and the LTCA's positions per
mesh cycle; a bad value raises an error naming ``tooth.<key>`` and its value.

:func:`compliance_for_design` computes a design point's compliance once and
reuses the NetCDF file whose inputs' hash (design, material, mesh settings,
the stage's sources) matches.
"""

from __future__ import annotations

import logging
import math
from pathlib import Path

from lsbg.config import config_key, section_objects

__all__ = ["TOOTH_CONFIG_KEYS", "TOOTH_DEFAULTS", "tooth_from_config",
           "compliance_for_design", "fe_design_points", "tooth_problems", "fillet_problem"]

log = logging.getLogger(__name__)

#: Key of the ``tooth`` section -> (object, field, SI value of one unit of the key).
TOOTH_CONFIG_KEYS = {
    "young_modulus_GPa": ("material", "young_modulus", 1e9),
    "poisson_ratio": ("material", "poisson_ratio", 1.0),
    "element_size_module": ("mesh", "tooth_size", 1.0),
    "rim_element_factor": ("mesh", "body_size", 1.0),
    "fillet_radius_module": ("mesh", "fillet_radius", 1.0),
    "face_points": ("mesh", "face_points", 1.0),
    "profile_points": ("mesh", "profile_points", 1.0),
    "ltca_positions": ("ltca", "positions", 1.0),
}

#: The section's defaults: steel, and the mesh whose convergence docs/model.md shows.
TOOTH_DEFAULTS = {"young_modulus_GPa": 206.0, "poisson_ratio": 0.3, "ltca_positions": 200}

#: Whole-number keys.
_WHOLE = ("face_points", "profile_points", "ltca_positions")


def tooth_from_config(section):
    """Material, mesh settings and LTCA positions of a ``tooth`` section.

    Parameters
    ----------
    section : dict
        Keys of :data:`TOOTH_CONFIG_KEYS` (``young_modulus_GPa`` [GPa],
        ``poisson_ratio`` [-], ``element_size_module`` and
        ``fillet_radius_module`` [mean normal modules], ``rim_element_factor``
        [-], ``face_points``, ``profile_points``, ``ltca_positions`` [-]);
        missing keys take the defaults.

    Returns
    -------
    material : lsbg.tooth.compliance.ToothMaterial
    settings : lsbg.tooth.compliance.FEMeshSettings
    positions : int
        Mesh positions of the LTCA over one base pitch [-].

    Raises
    ------
    ValueError
        Naming ``tooth.<key>`` and its value: an unknown key, a value that is
        not a number (or not whole), or one the material or mesh rejects.
    """
    from lsbg.tooth.compliance import FEMeshSettings, ToothMaterial

    section = dict(section or {})
    values = {"material": {}, "mesh": {}, "ltca": {}}
    for key, value in section.items():
        if key not in TOOTH_CONFIG_KEYS:
            raise ValueError(f"tooth.{key} = {value!r}: unknown key (known: "
                             f"{sorted(TOOTH_CONFIG_KEYS)})")
        if value is None:
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise ValueError(f"tooth.{key} = {value!r}: must be a finite number")
        if key in _WHOLE and int(value) != value:
            raise ValueError(f"tooth.{key} = {value!r}: must be a whole number")
        target, field, unit = TOOTH_CONFIG_KEYS[key]
        values[target][field] = int(value) if key in _WHOLE else value * unit
    positions = values["ltca"].get("positions", TOOTH_DEFAULTS["ltca_positions"])
    if not 8 <= positions <= 2000:
        raise ValueError(f"tooth.ltca_positions = {positions!r}: must lie in [8, 2000]")
    def named(target, field):
        key = config_key(TOOTH_CONFIG_KEYS, target, field)
        return None if key is None else (f"tooth.{key}", section.get(key))

    built = section_objects(values, {"material": ToothMaterial, "mesh": FEMeshSettings}, named,
                            "tooth")
    return built["material"], built["mesh"], int(positions)


def compliance_for_design(pair, material, settings, path):
    """The FE compliance of a design point, from ``path`` if it holds these inputs.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    material : lsbg.tooth.compliance.ToothMaterial
    settings : lsbg.tooth.compliance.FEMeshSettings
    path : str or pathlib.Path
        NetCDF file of the compliance; read when its ``inputs_hash`` matches
        (:func:`lsbg.tooth.compliance.compliance_hash`), else computed and
        written there (atomically).

    Returns
    -------
    xarray.Dataset
    bool
        True if the file was reused.
    """
    import xarray as xr

    from lsbg.files import write_dataset
    from lsbg.tooth.compliance import compliance_hash, tooth_compliance

    path = Path(path)
    wanted = compliance_hash(pair.design, material, settings)
    if path.is_file():
        with xr.open_dataset(path) as stored:
            if stored.attrs.get("inputs_hash") == wanted:
                log.info("compliance %s reused (inputs hash %s)", path, wanted)
                return stored.load(), True
    dataset = tooth_compliance(pair, material, settings)
    write_dataset(dataset, path)
    return dataset, False


def fe_design_points(config, pairs):
    """The design points whose FE compliance the study computes.

    Parameters
    ----------
    config : dict
        The study configuration, defaults filled in.
    pairs : dict
        ``(trace, spiral label) -> lsbg.gear.geometry.GearPair`` of the design points.

    Returns
    -------
    dict
        The paper's point of each trace under ``contact.compliance:
        uniform``; every point under ``fe``.
    """
    from lsbg.files import number_label

    if config["contact"].get("compliance", "uniform") == "fe":
        return dict(pairs)
    paper = number_label(config["paper_spiral_angle_deg"])
    return {key: pair for key, pair in pairs.items() if key[1] == paper}


def tooth_problems(config, pairs, memory_limit, memory_source):
    """The ``tooth`` section, the compliance case and the FE cost, checked before any job.

    Parameters
    ----------
    config : dict
        The study configuration, defaults filled in.
    pairs : dict
        ``(trace, spiral label) -> lsbg.gear.geometry.GearPair`` of the design
        points that passed their own checks.
    memory_limit : float
        Memory one job may use [GB].
    memory_source : str
        Where that limit comes from, for the message (``limits.memory_gb``).

    Returns
    -------
    list of str
        One line per problem, starting with the key and its value.
    """
    from lsbg.tooth.resources import fe_resource_estimate

    try:
        _, settings, _ = tooth_from_config(config.get("tooth", {}))
    except ValueError as error:
        return [str(error)]
    problems = []
    base = config["contact"].get("compliance", "uniform")
    for k, value in enumerate(config["sensitivity"].get("compliance", [])):
        if value == base:
            problems.append(f"sensitivity.compliance[{k}] = {value!r}: the same as "
                            f"contact.compliance = {base!r} (a case switches it)")
    minutes = config["limits"].get("tooth_minutes", 10)
    size = config.get("tooth", {}).get("element_size_module", settings.tooth_size)
    for (trace, spiral), pair in fe_design_points(config, pairs).items():
        # the root fillets must fit in the gaps (the loft's sections, without gmsh)
        rho = settings.fillet_radius * pair.design.mean_module * math.cos(pair.design.spiral_angle)
        for member in (1, 2):
            error = fillet_problem(pair, member, settings.segment_teeth, rho)
            if error:
                problems.append(f"tooth.fillet_radius_module = {settings.fillet_radius!r}: "
                                f"{trace} {spiral} deg: {error}")
        cost = fe_resource_estimate(pair, settings)
        beyond = []
        if cost.memory / 1e9 > memory_limit:
            beyond.append(f"{cost.memory / 1e9:.3g} GB of memory, more than {memory_source} = "
                          f"{memory_limit:.3g} GB")
        if cost.seconds / 60 > minutes:
            beyond.append(f"{cost.seconds / 60:.3g} min, more than limits.tooth_minutes = "
                          f"{minutes!r}")
        if beyond:
            problems.append(f"tooth.element_size_module = {size!r}: the FE compliance of "
                            f"{trace} {spiral} deg ({cost.dofs:.3g} degrees of freedom) "
                            f"would need about {' and '.join(beyond)}")
    return problems


def fillet_problem(pair, member, teeth, fillet_radius):
    """Why the root fillets of a member's FE segment do not fit, or None if they do.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
        Pinion or gear.
    teeth : int
        Teeth of the FE segment.
    fillet_radius : float
        The fillets' radius rho [m].

    Returns
    -------
    str or None
        The error of :func:`lsbg.tooth.outline.segment_sections` (the loft's sections,
        made with numpy and scipy's splines, without gmsh).
    """
    from lsbg.tooth.outline import segment_sections  # scipy.interpolate: 0.7 s to import

    try:
        segment_sections(pair, member, teeth, fillet_radius)
    except ValueError as error:
        return str(error)
    return None

