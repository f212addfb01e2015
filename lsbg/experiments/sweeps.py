"""Parameter sweeps of any setting, from the configuration's ``sweeps`` section.

A sweep names settings of the physics sections by their path
(``contact.dynamic_friction``) and their values; the study then runs every
combination at the design points it names (the paper's point, both traces, by
default) and combines the runs into one dataset with a coordinate per swept
key (``results/sweeps/{name}.nc``, :mod:`lsbg.aggregate.sweep_dataset`)::

    sweeps:
      friction:                                  # one key: its values
        contact.dynamic_friction: [0, 0.05, 0.1, 0.15, 0.2]
      damping_and_stiffness:
        product:                                 # every combination of several keys
          contact.mesh_damping_ratio: [0.025, 0.05, 0.1]
          contact.line_stiffness_N_per_mm_um: [10, 19.4, 40]
      pairs:
        combinations:                            # a list of combinations
          - {contact.mesh_damping_ratio: 0.025, simulation.load_torque_N_m: 1000}
          - {contact.mesh_damping_ratio: 0.1, simulation.load_torque_N_m: 3000}

Keys without a dot are the sweep's options (:data:`SWEEP_OPTIONS`): the traces,
the spiral angles, the contact model and engine, and how many points a job
carries (``batch_size``, so that a cluster pays its per-job start-up once per
batch). The table of points is a :class:`snakemake.utils.Paramspace` (one row
per point, one column per key), whose instance patterns name the points' files
(``dynamic_friction~0.05``); a value is written as Python writes it, so a
negative or fractional value is named safely and 0.1 and 0.1000001 are two
points. :func:`sweep_problems` checks every point as if its values were set in
their own sections, before any job (:mod:`lsbg.study.sweep_checks`).

Beside the dynamics, every point records its quasi-static contact
(:func:`contact_figures`): the loaded TCA of the line model on the uniform bed
(``lsbg ltca``'s, at the point's load and flanks) and the unloaded TCA's bearing
pattern at the marking-compound thickness (``lsbg tca``'s).
"""

from __future__ import annotations

import copy
import itertools
from dataclasses import dataclass

__all__ = ["SWEEPABLE_SECTIONS", "FIXED_KEYS", "SWEEP_OPTIONS", "CONTACT_FIGURES", "Sweep",
           "sweeps_from_config", "point_sections", "swept_attribute", "contact_figures"]

#: Sections whose keys a sweep may set: those a run reads.
SWEEPABLE_SECTIONS = ("design", "contact", "simulation", "flank_modification", "misalignment")

#: Keys a sweep may not set, and why.
FIXED_KEYS = {
    "design.trace": "a coordinate of every design point: use the sweep's traces",
    "design.spiral_angle_deg": "a coordinate of every design point: use the sweep's "
                               "spiral_angles_deg",
    "contact.model": "the contact model of a sweep is its option contact_model",
    "contact.compliance": "a sweep's runs take the uniform bed (the FE compliance is "
                          "computed at the study's own design points)",
    "flank_modification.topography_file": "a file path, not a value",
}

#: A sweep's options (keys without a dot) and their defaults (None: the study's).
SWEEP_OPTIONS = {"traces": ["logarithmic", "circular"], "spiral_angles_deg": None,
                 "contact_model": "line", "engine": None, "batch_size": 10}


#: The quasi-static figures a sweep records per point: variable -> (TCA, its attribute,
#: units, long_name); TCA "loaded" is :func:`lsbg.tca.loaded.loaded_tca`, "unloaded"
#: :func:`lsbg.tca.analysis.tooth_contact_summary`.
CONTACT_FIGURES = {
    "loaded_te_peak_to_peak": ("loaded", "transmission_error_peak_to_peak_urad", "urad",
                               "quasi-static loaded TE, peak to peak"),
    "loaded_te_harmonic_1": ("loaded", "transmission_error_harmonic_1_urad", "urad",
                             "quasi-static loaded TE, mesh harmonic"),
    "loaded_mesh_stiffness": ("loaded", "mesh_stiffness_per_face_width_N_per_mm_um",
                              "N/(mm um)", "mean mesh stiffness per face width"),
    "loaded_pattern_length": ("loaded", "loaded_pattern_length_per_face_width", "1",
                              "loaded pattern length / face width"),
    "edge_load_share": ("loaded", "edge_load_share", "1", "share of the load at the edges"),
    "pattern_centre_cone_distance": ("unloaded", "pattern_centre_cone_distance_mm", "mm",
                                     "bearing pattern centre, cone distance"),
    "pattern_centre_height": ("unloaded", "pattern_centre_height_mm", "mm",
                              "bearing pattern centre, height"),
    "pattern_length": ("unloaded", "pattern_length_mm", "mm", "bearing pattern length"),
    "pattern_height": ("unloaded", "pattern_height_mm", "mm", "bearing pattern height"),
    "unloaded_te_peak_to_peak": ("unloaded", "transmission_error_peak_to_peak_urad", "urad",
                                 "unloaded TE, peak to peak"),
}


def contact_figures(geometry, load_torque, params, flanks, tca):
    """The quasi-static contact of one sweep point: :data:`CONTACT_FIGURES`.

    Parameters
    ----------
    geometry : str or pathlib.Path
        The point's geometry directory (``lsbg geometry``).
    load_torque : float
        Torque on the gear [N m].
    params : lsbg.contact.ContactParameters
        The point's contact (its line-model fields; the bed is the uniform one).
    flanks : lsbg.tca.separation.RealFlanks
        The point's flank modification and displacements.
    tca : dict
        The configuration's ``tca`` section (``positions``, ``marking_compound_um``,
        ``loaded_positions``).

    Returns
    -------
    dict
        ``{variable: value}`` in :data:`CONTACT_FIGURES`' units; the unloaded ones NaN
        where the flanks lose contact or interfere (the loaded TCA still answers).
    """
    from lsbg.gear.geometry import GearPair
    from lsbg.solid.directory import read_design
    from lsbg.tca.analysis import tooth_contact_summary
    from lsbg.tca.loaded import ltca_for_geometry

    found = {"loaded": ltca_for_geometry(geometry, load_torque, params,
                                         phases=tca["loaded_positions"], flanks=flanks).attrs}
    try:
        found["unloaded"] = tooth_contact_summary(
            GearPair(read_design(geometry)), flanks.modification, flanks.misalignment,
            tca["positions"], float(tca["marking_compound_um"]) * 1e-6)
    except ValueError:
        found["unloaded"] = {}
    return {name: float(found[kind].get(attribute, float("nan")))
            for name, (kind, attribute, _, _) in CONTACT_FIGURES.items()}


def swept_attribute(key):
    """The run attribute that records a swept key's value: ``sweep_contact_dynamic_friction``."""
    return "sweep_" + key.replace(".", "_")


@dataclass(frozen=True)
class Sweep:
    """One named sweep: its points and where and how they run.

    Attributes
    ----------
    name : str
    keys : tuple of str
        The swept keys (``section.key``).
    points : tuple of dict
        ``{key: value}`` per point (configuration units).
    kind : str
        ``"values"`` (one key), ``"product"`` or ``"combinations"``.
    traces : tuple of str
    spiral_angles : tuple of float
        [deg].
    contact_model, engine : str
    batch_size : int
        Points per job [-].
    """

    name: str
    keys: tuple
    points: tuple
    kind: str
    traces: tuple
    spiral_angles: tuple
    contact_model: str
    engine: str
    batch_size: int

    @property
    def columns(self):
        """The points' column names: the key alone where that is unique, else
        ``section_key`` (Paramspace names files by them; a dot would break them)."""
        short = [k.split(".", 1)[1] for k in self.keys]
        return [s if short.count(s) == 1 else k.replace(".", "_")
                for s, k in zip(short, self.keys)]

    def paramspace(self):
        """The points as a :class:`snakemake.utils.Paramspace` (one column per key)."""
        import pandas as pd
        from snakemake.utils import Paramspace

        table = pd.DataFrame([[p[k] for k in self.keys] for p in self.points],
                             columns=self.columns)
        return Paramspace(table, filename_params="*", param_sep="~", filename_sep="_")

    def patterns(self):
        """Each point's file-name part (Paramspace's instance pattern), in point order."""
        return list(self.paramspace().instance_patterns)

    def batches(self):
        """The point indices of each job: ``batch_size`` points a job."""
        n = len(self.points)
        return [list(range(k, min(k + self.batch_size, n)))
                for k in range(0, n, self.batch_size)]


def _points(spec):
    """(kind, keys, points) of a sweep's entry; raises ValueError naming what is wrong."""
    swept = {k: v for k, v in spec.items() if "." in str(k)}
    if "product" in spec or "combinations" in spec:
        if swept:
            raise ValueError(f"{sorted(swept)[0]}: give swept keys either at the sweep's top "
                             f"or under product/combinations, not both")
    if "product" in spec and "combinations" in spec:
        raise ValueError("product and combinations: one of them")
    if "combinations" in spec:
        combos = spec["combinations"]
        if not isinstance(combos, list) or not combos or not all(isinstance(c, dict)
                                                                for c in combos):
            raise ValueError("combinations: must be a non-empty list of {key: value} mappings")
        keys = list(dict.fromkeys(k for c in combos for k in c))
        for k, combo in enumerate(combos):
            missing = [key for key in keys if key not in combo]
            if missing:
                raise ValueError(f"combinations[{k}]: lacks {missing[0]} (every combination "
                                 f"sets the same keys)")
        return "combinations", keys, [{key: c[key] for key in keys} for c in combos]
    grid = spec["product"] if "product" in spec else swept
    if not isinstance(grid, dict) or not grid:
        raise ValueError("no swept key: give section.key: [values] (or product / combinations)")
    for key, values in grid.items():
        if not isinstance(values, list) or not values:
            raise ValueError(f"{key} = {values!r}: must be a non-empty list of values")
    keys = list(grid)
    if "product" not in spec and len(keys) > 1:
        raise ValueError(f"{keys[0]}, {keys[1]}: several keys: put them under product (every "
                         f"combination) or combinations (a list)")
    kind = "product" if "product" in spec else "values"
    return kind, keys, [dict(zip(keys, combo))
                        for combo in itertools.product(*(grid[k] for k in keys))]


def _sweep(name, spec, config):
    if not isinstance(spec, dict):
        raise ValueError(f"must be a mapping of swept keys and options, got {spec!r}")
    unknown = [k for k in spec if "." not in str(k) and k not in SWEEP_OPTIONS
               and k not in ("product", "combinations")]
    if unknown:
        raise ValueError(f"{unknown[0]}: unknown option (swept keys are section.key; options: "
                         f"{', '.join(SWEEP_OPTIONS)}, product, combinations)")
    kind, keys, points = _points(spec)
    options = {**SWEEP_OPTIONS, **{k: v for k, v in spec.items() if k in SWEEP_OPTIONS}}
    angles = options["spiral_angles_deg"] or [config["paper_spiral_angle_deg"]]
    return Sweep(name=str(name), keys=tuple(keys), points=tuple(points), kind=kind,
                 traces=tuple(options["traces"]), spiral_angles=tuple(float(a) for a in angles),
                 contact_model=options["contact_model"],
                 engine=options["engine"] or config["engines"]["sweep"],
                 batch_size=int(options["batch_size"]))


def sweeps_from_config(config):
    """The sweeps of a configuration's ``sweeps`` section, in its order.

    Raises
    ------
    ValueError
        Naming ``sweeps.<name>`` and what is wrong; :func:`sweep_problems` gives
        every problem at once.
    """
    out = []
    for name, spec in (config.get("sweeps") or {}).items():
        try:
            out.append(_sweep(name, spec, config))
        except ValueError as error:
            raise ValueError(f"sweeps.{name}: {error}") from None
    return out


def point_sections(config, values):
    """The sections a run of one point reads: the study's, the point's values set.

    Parameters
    ----------
    config : dict
        The configuration (defaults filled in).
    values : dict
        ``{section.key: value}`` of the point.

    Returns
    -------
    dict
        ``{section: dict}`` for :data:`SWEEPABLE_SECTIONS` (new dictionaries).
    """
    sections = {s: copy.deepcopy(config.get(s, {})) for s in SWEEPABLE_SECTIONS}
    for key, value in values.items():
        section, field = key.split(".", 1)
        sections[section][field] = value
    return sections
