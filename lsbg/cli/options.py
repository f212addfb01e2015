"""Options shared by the subcommands: the design, the study configuration's
sections, the contact and simulation settings; :class:`CommandError`.

Every option is in the paper's units (mm, deg, deg/s, N m) as in the
workflow's configuration; the handlers convert to SI through
:class:`lsbg.gear.design.GearPairDesign`, :class:`lsbg.contact.ContactParameters`
and :class:`lsbg.dynamics.SimulationSettings`.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

from lsbg.files import read_yaml_file
from lsbg.gear.design import BASE_CONE_RULES, CONFIG_KEYS, HANDS, TRACES, GearPairDesign

__all__ = ["CommandError", "check_output", "add_design_options", "design_from_args",
           "read_study_sections", "add_contact_options", "contact_from_args",
           "add_simulation_options", "simulation_from_args", "SIMULATION_OPTIONS",
           "add_fe_ltca_option", "slice_stiffness_from_args"]


class CommandError(ValueError):
    """Bad command-line input that is not a design parameter (exit code 2)."""


def check_output(path, option, directory=False):
    """Fail before the work starts if lsbg could not write ``path`` at its end.

    The writers (:func:`lsbg.files.write_atomically`,
    :func:`lsbg.solid.export.write_geometry`) create missing folders, so the nearest
    existing folder above ``path`` must be a writable directory.

    Parameters
    ----------
    path : str or os.PathLike
        Output file (or, with ``directory``, output directory).
    option : str
        The option that gave it, for the message (``"--out"``).
    directory : bool
        ``path`` is a directory that replaces an existing one.

    Raises
    ------
    CommandError
        Naming the option and path: ``path`` exists as a directory where a
        file goes (or a file where a directory goes), a folder above it is a
        file, or the folder it goes in is not writable.
    """
    path = Path(path)
    if path.exists() and path.is_dir() != directory:
        found, wanted = ("a directory", "file") if path.is_dir() else ("a file", "directory")
        raise CommandError(f"{option} {path}: is {found}, not an output {wanted}")
    folder = path.absolute().parent
    while not folder.exists():
        folder = folder.parent
    if not folder.is_dir():
        raise CommandError(f"{option} {path}: {folder} is a file, not a folder")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise CommandError(f"{option} {path}: cannot write in {folder} (permission denied or "
                           f"read-only)")
    # root passes os.access everywhere, and some folders take no new entries whatever
    # their mode (/proc, a full or read-only mount): create a file there and remove it
    import tempfile

    try:
        handle, probe = tempfile.mkstemp(prefix=".lsbg-probe-", dir=folder)
    except OSError as error:
        raise CommandError(f"{option} {path}: cannot create files in {folder} "
                           f"({error.strerror})") from None
    os.close(handle)
    os.unlink(probe)


# What each design key means; the unit comes from the key's suffix.
_DESCRIPTIONS = {
    "pinion_teeth": "number of pinion teeth z1",
    "gear_teeth": "number of gear teeth z2",
    "module_mm": "outer transverse module m",
    "shaft_angle_deg": "shaft angle Sigma",
    "normal_pressure_angle_deg": "normal pressure angle at the mean point",
    "spiral_angle_deg": "mean spiral angle on the pitch cone",
    "pinion_hand": "hand of spiral of the pinion",
    "addendum_mm": "outer addendum",
    "dedendum_mm": "outer dedendum",
    "trace": "tooth trace: logarithmic (LSBG) or circular (SBG)",
    "face_width_mm": "face width along the pitch cone generator",
    "cutter_radius_mm": "radius of the circular cutter arc (SBG)",
    "base_cone_rule": "base cone rule: involute (20 deg normal pressure angle) or paper (Eq. 6)",
    "backlash_mm": "circumferential backlash on the mean pitch circle",
    "density_kg_m3": "density of both gears",
    "pinion_bore_mm": "pinion bore diameter",
    "gear_bore_mm": "gear bore diameter",
}
_UNITS = {"_mm": "mm", "_deg": "deg", "_kg_m3": "kg/m^3"}
_CHOICES = {"trace": TRACES, "base_cone_rule": BASE_CONE_RULES, "pinion_hand": HANDS}
# Short spellings used in the paper's workflow, besides --<key>.
_ALIASES = {"spiral_angle_deg": ("--spiral-angle",)}


def _unit(key):
    for suffix, unit in _UNITS.items():
        if key.endswith(suffix):
            return unit
    return None


def add_design_options(parser):
    """Add ``--design FILE.yaml`` and one option per design parameter.

    Options are generated from :data:`lsbg.gear.design.CONFIG_KEYS` (``module_mm``
    -> ``--module-mm``), in the paper's units; each defaults to ``None`` so
    that :func:`design_from_args` can tell what was given.

    Parameters
    ----------
    parser : argparse.ArgumentParser
    """
    paper = GearPairDesign().to_config()
    group = parser.add_argument_group(
        "design parameters (paper units; they override --design; defaults: the paper's "
        "Table 1 and lsbg.gear.design.GearPairDesign)")
    group.add_argument("--design", metavar="FILE.yaml",
                       help="YAML file with design keys as in lsbg.gear.design.CONFIG_KEYS, or a study "
                       "configuration with them under 'design:'")
    for key in CONFIG_KEYS:
        unit = _unit(key)
        value = paper[key]
        shown = f"{value:g}" if isinstance(value, float) else value
        description = _DESCRIPTIONS.get(key, key.replace("_", " "))
        units = f" [{unit}]" if unit else ""
        kwargs = dict(dest=key, default=None, help=f"{description}{units} (default: {shown})")
        if key in _CHOICES:
            kwargs["choices"] = _CHOICES[key]
        elif isinstance(value, int) and not isinstance(value, bool):
            kwargs["type"] = int
            kwargs["metavar"] = "N"
        elif isinstance(value, float):
            kwargs["type"] = float
        if unit:
            kwargs["metavar"] = unit.upper().replace("/", "_").replace("^", "")
        flags = _ALIASES.get(key, ()) + ("--" + key.replace("_", "-"),)
        group.add_argument(*flags, **kwargs)


def design_from_args(args) -> GearPairDesign:
    """The design from ``--design`` (if any) overridden by the design options.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed by a parser with :func:`add_design_options`.

    Returns
    -------
    GearPairDesign

    Raises
    ------
    DesignError
        Unknown key in the YAML file or an invalid value; the message names the key.
    CommandError
        The YAML file cannot be read.
    """
    config = read_yaml_file(args.design, "--design") if getattr(args, "design", None) else {}
    if isinstance(config.get("design"), dict):
        # a study configuration (workflow/config.yaml, results/config.yaml)
        config = dict(config["design"])
    for key in CONFIG_KEYS:
        value = getattr(args, key, None)
        if value is not None:
            config[key] = value
    return GearPairDesign.from_config(config)


def read_study_sections(path, *sections):
    """The named sections of a study configuration file (``{}`` if no file)."""
    if path is None:
        return [{} for _ in sections]
    config = read_yaml_file(path, "--config")
    return [config.get(section) or {} for section in sections]


#: Command-line options of ``lsbg simulate`` -> key of the ``simulation`` section.
SIMULATION_OPTIONS = {
    "duration": ("duration_s", float, "simulated time [s] (paper: 1)"),
    "samples": ("samples", int, "output intervals; samples+1 instants (paper: 500)"),
    "dt": ("time_step_s", float, "fixed time step of the pybullet engine [s] (1e-6)"),
    "rtol": ("rtol", float, "relative tolerance of the scipy engine (1e-8)"),
    "method": ("method", str, "method of the scipy engine (LSODA, or a solve_ivp method)"),
    "pinion_speed": ("pinion_speed_deg_s", float, "final pinion speed [deg/s] (paper: 7703)"),
    "ramp_time": ("ramp_time_s", float, "STEP ramp time of the pinion speed [s] (paper: 0.2)"),
    "load_torque": ("load_torque_N_m", float, "resisting torque on the gear [N m] (paper: 1964.99)"),
    "full_rate": ("full_rate_hz", float, "rate of the full-rate record [1/s] (50000)"),
    "full_rate_after": ("full_rate_after_s", float,
                        "start of the full-rate record [s] (default: the end of the ramp)"),
}


def add_contact_options(parser, model=True):
    """Add ``--config`` (its ``contact`` section), ``--set-contact`` and, with
    ``model``, ``--contact-model``."""
    parser.add_argument("--config", metavar="FILE.yaml",
                        help="study configuration; its 'simulation' and 'contact' sections are used")
    if model:
        parser.add_argument("--contact-model", choices=("point", "line"),
                            help="contact model: point (the paper's IMPACT law, one incident "
                                 "per tooth pair) or line (sliced contact lines) (default: "
                                 "contact.model of --config, else point)")
    parser.add_argument("--set-contact", action="append", default=[], metavar="KEY=VALUE",
                        help="override a key of the contact section (paper units), e.g. "
                             "mesh_damping_ratio=0.1; repeatable")
    parser.add_argument("--compliance", choices=("uniform", "fe"),
                        help="line model's tooth compliance: the uniform bed of springs or the "
                             "tooth's own from finite elements (default: contact.compliance of "
                             "--config, else uniform)")
    add_flank_options(parser)


def add_flank_options(parser):
    """Add ``--modification`` and ``--misalignment`` (over the sections of ``--config``)."""
    parser.add_argument("--modification", action="append", default=[], metavar="KEY=VALUE",
                        help="set a key of the flank_modification section (um), e.g. "
                             "lengthwise_crowning_um=25; repeatable. Without --config and "
                             "these, the flanks are the conjugate ones")
    parser.add_argument("--misalignment", action="append", default=[], metavar="KEY=VALUE",
                        help="set an assembly displacement: a key of the misalignment section "
                             "or its letter, E, P, G [mm] or Sigma [deg], e.g. P=0.05; "
                             "repeatable (default: the aligned pair)")


def _assignments(texts, option):
    """{key: value} of KEY=VALUE option texts (values read as YAML)."""
    import yaml

    out = {}
    for text in texts:
        key, sep, value = text.partition("=")
        if not sep or not key.strip():
            raise CommandError(f"{option} {text!r}: must be KEY=VALUE")
        out[key.strip()] = yaml.safe_load(value)
    return out


def flank_sections_from_args(args):
    """``--config``'s ``flank_modification`` and ``misalignment`` sections with the
    options' keys set (``--misalignment`` letters as their keys), in config units."""
    from lsbg.tca.misalignment import DISPLACEMENTS

    modification, misalignment = read_study_sections(getattr(args, "config", None),
                                                     "flank_modification", "misalignment")
    modification = {**modification, **_assignments(args.modification, "--modification")}
    given = _assignments(args.misalignment, "--misalignment")
    misalignment = {**misalignment, **{DISPLACEMENTS[k][1] if k in DISPLACEMENTS else k: v
                                       for k, v in given.items()}}
    return modification, misalignment


def flanks_from_args(args):
    """The real flanks (:class:`lsbg.tca.separation.RealFlanks`) of ``--config``'s
    ``flank_modification`` and ``misalignment`` sections and the options."""
    from lsbg.tca.separation import RealFlanks

    modification, misalignment = flank_sections_from_args(args)
    try:
        return RealFlanks.from_config(modification, misalignment)
    except ValueError as err:
        raise CommandError(str(err)) from None


def contact_from_args(args):
    """Contact parameters from the ``contact`` section of ``--config``, ``--set-contact``
    and ``--contact-model``."""
    from lsbg.contact import ContactParameters

    (contact,) = read_study_sections(args.config, "contact")
    contact = {**contact, **_assignments(getattr(args, "set_contact", []), "--set-contact")}
    if args.contact_model is not None:
        contact["model"] = args.contact_model
    if getattr(args, "compliance", None) is not None:
        contact["compliance"] = args.compliance
    try:
        return ContactParameters.from_config(contact)
    except ValueError as err:
        raise CommandError(str(err)) from None


def add_simulation_options(parser, contact_model=True):
    """Add ``--geometry``, ``--engine``, the contact options (``--contact-model`` with
    ``contact_model``) and the simulation settings."""
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory written by 'lsbg geometry'")
    parser.add_argument("--engine", choices=("pybullet", "scipy", "compiled"), default="pybullet",
                        help="integrator: pybullet (multibody, fixed step), scipy (scipy's LSODA) or "
                             "compiled (embedded Runge-Kutta compiled with numba) "
                             "(default: pybullet)")
    add_contact_options(parser, model=contact_model)
    for option, (key, kind, text) in SIMULATION_OPTIONS.items():
        parser.add_argument(f"--{option.replace('_', '-')}", dest=option, type=kind, help=text)


def simulation_from_args(args):
    """(settings, contact parameters) from ``--config`` and the options."""
    from lsbg.dynamics import SimulationSettings

    (simulation,) = read_study_sections(args.config, "simulation")
    simulation = dict(simulation)
    for option, (key, _, _) in SIMULATION_OPTIONS.items():
        value = getattr(args, option, None)
        if value is not None:
            simulation[key] = value
    try:
        settings = SimulationSettings.from_config(simulation, engine=args.engine)
    except ValueError as err:
        raise CommandError(str(err)) from None
    return settings, contact_from_args(args)


def add_fe_ltca_option(parser):
    """Add ``--fe-ltca``: the slice stiffness of a line-model run under compliance fe."""
    parser.add_argument("--fe-ltca", metavar="MESH.nc",
                        help="loaded TCA with the tooth's FE compliance of this design point "
                             "and load (lsbg ltca under contact.compliance: fe): its slice "
                             "stiffness replaces the uniform bed in line-model runs with "
                             "compliance fe")


def slice_stiffness_from_args(args, params, geometry_dir, load_torque):
    """The slice stiffness of ``--fe-ltca`` for a run with ``params``, or None.

    Raises
    ------
    CommandError
        ``--fe-ltca`` missing under compliance fe (line model), given otherwise,
        or of another design point or load.
    """
    import xarray as xr

    from lsbg.contact.slices import SliceStiffness
    from lsbg.solid.directory import read_design

    path = getattr(args, "fe_ltca", None)
    wanted = params.model == "line" and params.compliance == "fe"
    if not wanted:
        return None
    if not path:
        raise CommandError("contact.compliance = 'fe': a line-model run needs --fe-ltca (the "
                           "design point's loaded TCA with the FE compliance)")
    with xr.open_dataset(path) as ds:
        ds = ds.load()
    design = read_design(geometry_dir)
    difference = design.attrs_difference(ds.attrs)
    if difference is not None:
        key, stored, value = difference
        raise CommandError(f"--fe-ltca {path}: design {key} = {stored!r}, the geometry's "
                           f"{value!r}")
    stored_load = float(ds.attrs.get("load_torque_N_m", math.nan))
    if not math.isclose(stored_load, load_torque, rel_tol=1e-9):
        raise CommandError(f"--fe-ltca {path}: computed at {stored_load!r} N m, the run's load "
                           f"is {load_torque!r} N m (its slice stiffness is the secant at its "
                           f"own load)")
    try:
        return SliceStiffness.from_dataset(ds)
    except ValueError as err:
        raise CommandError(f"--fe-ltca {path}: {err}") from None


# ------------------------------------------------------------ sensitivity cases
def add_case_options(parser, stage):
    """Add ``--case KEY=VALUE`` (repeatable) and ``--case-out TEMPLATE``: the sensitivity
    cases (:mod:`lsbg.experiments.sensitivity`) of ``stage`` that a command
    computes beside its own output, in the same process."""
    # (lsbg.experiments.sensitivity is imported when the cases are read, not here: building the
    # parser must not make every stage depend on it, lsbg.study.stages)
    parser.add_argument("--case", action="append", default=[], metavar="KEY=VALUE",
                        help=f"a sensitivity case as in the sensitivity section whose key "
                             f"reaches the {stage.replace('_', ' ')} (lsbg.experiments.sensitivity."
                             f"CASE_STAGES), e.g. crowning=0.5; repeatable")
    parser.add_argument("--case-out", metavar="FILE.nc",
                        help="output file template of the cases, with the field {case} "
                             "(the case's name, e.g. crowning_x0.5)")
