"""What every subcommand shares: the configuration, its inputs and outputs, CommandError.

One grammar sets every value: ``--config FILE`` (a study configuration, the
workflow's sections; repeatable, merged in order) and ``--set
section.key=value`` (repeatable), typed and checked by the configuration's
schema before any work (:mod:`lsbg.config`); keys a command does not read are
refused by nothing but ignored by it. The schema holds every default. What is
left on a command line is what a command reads and writes (``--geometry``,
``--out``, ...) and what it runs (``--engine``, ``--case``, the design points
of ``--spiral-angles``).

:func:`settings_of` resolves the configuration once per command;
:func:`design_of`, :func:`contact_of`, :func:`simulation_of` and
:func:`flanks_of` build lsbg's objects from its sections, in SI, their errors
naming the user's key. Outputs declared with :func:`add_output` are checked
before the handler runs (:func:`check_outputs`, called by
:func:`lsbg.cli.main`).
"""

from __future__ import annotations

import argparse
import functools
import math
import os
import sys
from pathlib import Path

__all__ = ["CommandError", "check_output", "check_outputs", "add_config_options", "settings_of",
           "add_output", "add_geometry_input", "add_engine_option", "command_line", "design_of",
           "contact_of", "simulation_of", "flanks_of", "flank_sections_of", "load_torque_of",
           "add_fe_ltca_option", "fe_compliance_of", "slice_stiffness_of", "add_case_options", "parse_pairs",
           "checked", "RESULT_FILES", "add_result_inputs", "read_results"]


class CommandError(ValueError):
    """Bad command-line input that is not a configuration key (exit code 2)."""


def check_output(path, option, directory=False):
    """Fail before the work starts if lsbg could not write ``path`` at its end.

    The writers (:func:`lsbg.files.write_atomically`,
    :func:`lsbg.solid.export.write_geometry`) create missing folders, so the
    nearest existing folder above ``path`` must be a writable directory.

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


def add_output(parser, option="--out", metavar="FILE.nc", help="output NetCDF file",
               directory=False, required=True):
    """Add an output option whose path :func:`check_outputs` checks before the handler runs.

    Parameters
    ----------
    parser : argparse.ArgumentParser
    option : str
        ``--out``, ``--csv``, ...
    metavar, help : str
    directory : bool
        The output is a directory (``lsbg geometry``).
    required : bool
    """
    dest = option.lstrip("-").replace("-", "_")
    parser.add_argument(option, dest=dest, required=required, metavar=metavar, help=help)
    declared = parser.get_default("outputs") or ()
    parser.set_defaults(outputs=(*declared, (dest, option, directory)))


def check_outputs(args):
    """:func:`check_output` for every output of :func:`add_output` that was given."""
    for dest, option, directory in getattr(args, "outputs", ()):
        if getattr(args, dest, None):
            check_output(getattr(args, dest), option, directory=directory)


def add_geometry_input(parser):
    """Add ``--geometry DIR``: a design point's geometry directory (``lsbg geometry``)."""
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory written by 'lsbg geometry'")


def add_engine_option(parser, default="pybullet"):
    """Add ``--engine``: the integrator of a command's runs."""
    parser.add_argument("--engine", choices=("pybullet", "scipy", "compiled"), default=default,
                        help=f"integrator: pybullet (multibody, fixed step), scipy (solve_ivp) or "
                             f"compiled (embedded Runge-Kutta compiled with numba) "
                             f"(default: {default})")


#: The files of results ``lsbg combine`` and ``lsbg summary`` read besides the runs:
#: option, metavar and the keyword of :func:`lsbg.aggregate.combine.combine_runs` and
#: :func:`lsbg.aggregate.summary.summary_table` that takes them.
RESULT_FILES = (("--meshes", "MESH.nc", "meshes"), ("--tca", "TCA.nc", "tca"),
                ("--vh", "MAP.nc", "vh_maps"))


def add_result_inputs(parser, runs, meshes, tca, vh):
    """Add ``--runs RUN.nc ...`` (required) and ``--meshes``, ``--tca``, ``--vh`` (optional).

    Parameters
    ----------
    parser : argparse.ArgumentParser
    runs, meshes, tca, vh : str
        The help of each option: run files (lsbg simulate), loaded TCAs (lsbg
        ltca), unloaded TCAs (lsbg tca) and V-H maps (lsbg misalignment-map).
    """
    parser.add_argument("--runs", nargs="+", required=True, metavar="RUN.nc", help=runs)
    for (option, metavar, _), text in zip(RESULT_FILES, (meshes, tca, vh)):
        parser.add_argument(option, nargs="+", default=[], metavar=metavar, help=text)


def read_results(build, args):
    """``build(args.runs, meshes=..., tca=..., vh_maps=...)`` of :func:`add_result_inputs`'
    files; a file's OSError or ValueError as a CommandError under ``--runs``."""
    files = {keyword: getattr(args, option.lstrip("-")) for option, _, keyword in RESULT_FILES}
    try:
        return build(args.runs, **files)
    except (OSError, ValueError) as err:
        raise CommandError(f"--runs: {err}") from None


# ------------------------------------------------------------- configuration
def add_config_options(parser, sections):
    """Add ``--config FILE`` and ``--set SECTION.KEY=VALUE``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
    sections : sequence of str
        The configuration's sections the command reads (named in its help and
        kept as the parser's default ``sections``: the workflow reruns the
        command's jobs when one of them changes).
    """
    parser.add_argument("--config", dest="config_files", action="append", default=[],
                        metavar="FILE.yaml",
                        help=f"a study configuration as workflow/config.yaml (this command reads "
                             f"its sections {', '.join(sections)}); repeatable, merged in order")
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="SECTION.KEY=VALUE",
                        help="set one key over --config in the configuration's units, e.g. "
                             "contact.model=line or design.spiral_angle_deg=30; repeatable. "
                             "Keys, units and defaults: lsbg/schemas/config.schema.yaml")
    parser.set_defaults(sections=tuple(sections))
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = settings_help(sections)


def settings_help(sections):
    """The keys of the configuration's ``sections`` with their defaults, from the schema
    (the design's from :class:`lsbg.gear.design.GearPairDesign`: the paper's Table 1)."""
    return _settings_help(tuple(sections))


@functools.lru_cache(maxsize=None)  # every command's parser asks, at every lsbg start
def _settings_help(sections):
    from lsbg.config import load_schema, section_keys
    from lsbg.gear.design import GearPairDesign

    table1 = GearPairDesign().to_config()
    schema, lines = load_schema(), ["settings (--set SECTION.KEY=VALUE; default in brackets):"]
    for section in sections:
        for key, text, default in section_keys(schema, section):
            default = table1.get(key, default) if section == "design" else default
            shown = "" if default is None else f" [{default}]"
            lines.append(f"  {section}.{key}{shown}")
            if text:
                lines.append(f"      {text[:150]}{'...' if len(text) > 150 else ''}")
    return "\n".join(lines)


def settings_of(args):
    """The command's configuration: the schema's defaults, ``--config``, then ``--set``.

    Resolved once per command and kept as ``args.settings``.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed by a parser with :func:`add_config_options`.

    Returns
    -------
    dict
        Every section of the schema (:func:`lsbg.config.resolve_config`).

    Raises
    ------
    lsbg.config.ConfigError
        One line naming each bad key and value (exit code 2).
    """
    if getattr(args, "settings", None) is None:
        from lsbg.config import resolve_config
        from lsbg.files import read_yaml_file

        args.settings = resolve_config(getattr(args, "config_files", ()),
                                       getattr(args, "overrides", ()), read=read_yaml_file)
    return args.settings


#: The arguments of the running ``lsbg`` call, set by :func:`lsbg.cli.main`: the
#: argv a caller passed (``main([...])`` from Python), else ``sys.argv[1:]``.
_ARGUMENTS = None


def command_line():
    """This command as typed (the provenance attribute of what it writes)."""
    return " ".join(["lsbg", *(sys.argv[1:] if _ARGUMENTS is None else _ARGUMENTS)])


def checked(build):
    """``build()``, its ValueError (whose message names the user's key) as a CommandError."""
    try:
        return build()
    except ValueError as err:
        raise CommandError(str(err)) from None


def design_of(settings):
    """The design of the ``design`` section (:class:`lsbg.gear.design.GearPairDesign`), its
    errors under the user's key and units (``design.face_width_mm = 500: ...``)."""
    from lsbg.gear.checks import user_message
    from lsbg.gear.design import DesignError, GearPairDesign

    section = {k: v for k, v in settings.get("design", {}).items() if v is not None}
    try:
        return GearPairDesign.from_config(section)
    except DesignError as err:
        where, why = user_message(err, settings, ("design.spiral_angle_deg",))
        raise DesignError(f"{where}: {why}") from None


def contact_of(settings, **changes):
    """The contact parameters of the ``contact`` section, with ``changes`` to its keys."""
    from lsbg.contact import ContactParameters

    return checked(lambda: ContactParameters.from_config({**settings["contact"], **changes}))


def simulation_of(settings, engine):
    """The simulation settings of the ``simulation`` section for ``engine``."""
    from lsbg.dynamics import SimulationSettings

    return checked(lambda: SimulationSettings.from_config(settings["simulation"], engine=engine))


def driveline_of(settings):
    """The ``driveline`` section (:mod:`lsbg.dynamics.driveline`), its keys checked."""
    from lsbg.dynamics.driveline import driveline_values

    section = dict(settings.get("driveline", {}))
    checked(lambda: driveline_values(section))
    return section


def load_torque_of(settings):
    """The load on the gear [N m] of the ``simulation`` section, checked."""
    return simulation_of(settings, "compiled").load_torque


def flank_sections_of(settings):
    """The ``flank_modification`` and ``misalignment`` sections (configuration units)."""
    return dict(settings["flank_modification"]), dict(settings["misalignment"])


def flanks_of(settings):
    """The real flanks (:class:`lsbg.tca.separation.RealFlanks`) of the ``flank_modification``
    and ``misalignment`` sections (without them: the conjugate, aligned pair)."""
    from lsbg.tca.separation import RealFlanks

    return checked(lambda: RealFlanks.from_config(*flank_sections_of(settings)))


def parse_pairs(texts, option, keys=None):
    """``{name: value}`` of ``NAME=VALUE`` texts (``--run line=RUN.nc``), checked.

    Parameters
    ----------
    texts : sequence of str
    option : str
        The option, for the message.
    keys : sequence of str, optional
        The names allowed.

    Raises
    ------
    CommandError
        Naming the text: no ``=``, an empty part, or a name not in ``keys``.
    """
    pairs = {}
    for text in texts:
        name, sep, value = text.partition("=")
        name, value = name.strip(), value.strip()
        if not sep or not name or not value or (keys is not None and name not in keys):
            allowed = f" with NAME one of {list(keys)}" if keys is not None else ""
            raise CommandError(f"{option} {text!r}: must be NAME=VALUE{allowed}")
        pairs[name] = value
    return pairs


# ------------------------------------------------- the tooth's slice stiffness
def fe_compliance_of(args):
    """The FE compliance of ``--compliance-file`` (reused if it holds these inputs, else
    computed and written there) and the FE loaded TCA's positions of the ``tooth`` section.

    Parameters
    ----------
    args : argparse.Namespace
        With ``settings``, ``geometry`` and ``compliance_file``.

    Returns
    -------
    (xarray.Dataset, int)
    """
    from lsbg.gear.geometry import GearPair
    from lsbg.solid.directory import read_design
    from lsbg.tooth.config import compliance_for_design, tooth_from_config

    material, mesh, positions = checked(lambda: tooth_from_config(args.settings["tooth"]))
    if not args.compliance_file:
        raise CommandError("contact.compliance = 'fe' needs --compliance-file (where the "
                           "design point's FE compliance is, or goes)")
    pair = GearPair(read_design(args.geometry))
    compliance, _ = compliance_for_design(pair, material, mesh, args.compliance_file)
    return compliance, positions


def add_fe_ltca_option(parser):
    """Add ``--fe-ltca``: the slice stiffness of a line-model run under compliance fe."""
    parser.add_argument("--fe-ltca", metavar="MESH.nc",
                        help="loaded TCA with the tooth's FE compliance of this design point "
                             "and load (lsbg ltca under contact.compliance: fe): its slice "
                             "stiffness replaces the uniform bed in line-model runs with "
                             "compliance fe")


def slice_stiffness_of(path, params, geometry_dir, load_torque):
    """The slice stiffness of ``--fe-ltca`` for a run with ``params``, or None.

    Parameters
    ----------
    path : str or None
        ``--fe-ltca``.
    params : lsbg.contact.ContactParameters
    geometry_dir : str
    load_torque : float
        The run's load [N m].

    Raises
    ------
    CommandError
        ``--fe-ltca`` missing under compliance fe (line model), or of another
        design point or load.
    """
    import xarray as xr

    from lsbg.contact.slices import SliceStiffness
    from lsbg.solid.directory import read_design

    if not (params.model == "line" and params.compliance == "fe"):
        return None
    if not path:
        raise CommandError("contact.compliance = 'fe': a line-model run needs --fe-ltca (the "
                           "design point's loaded TCA with the FE compliance)")
    with xr.open_dataset(path) as ds:
        ds = ds.load()
    difference = read_design(geometry_dir).attrs_difference(ds.attrs)
    if difference is not None:
        key, stored, value = difference
        raise CommandError(f"--fe-ltca {path}: design {key} = {stored!r}, the geometry's "
                           f"{value!r}")
    stored_load = float(ds.attrs.get("load_torque_N_m", math.nan))
    if not math.isclose(stored_load, load_torque, rel_tol=1e-9):
        raise CommandError(f"--fe-ltca {path}: computed at {stored_load!r} N m, the run's load "
                           f"is {load_torque!r} N m (its slice stiffness is the secant at its "
                           f"own load)")
    return checked(lambda: SliceStiffness.from_dataset(ds))


# ------------------------------------------------------------ sensitivity cases
def add_case_options(parser, stage, out=True):
    """Add ``--case KEY=VALUE`` (repeatable) and, with ``out``, ``--case-out TEMPLATE``: the
    sensitivity cases (:mod:`lsbg.experiments.sensitivity`) of ``stage`` that a command
    computes beside its own output, in the same process."""
    # (lsbg.experiments.sensitivity is imported when the cases are read, not here: building
    # the parser must not make every stage depend on it, lsbg.study.stages)
    parser.add_argument("--case", action="append", default=[], metavar="KEY=VALUE",
                        help=f"a sensitivity case as in the sensitivity section whose key "
                             f"reaches the {stage.replace('_', ' ')} (lsbg.experiments."
                             f"sensitivity.CASE_STAGES), e.g. crowning=0.5; repeatable")
    if out:
        parser.add_argument("--case-out", metavar="FILE.nc",
                            help="output file template of the cases, with the field {case} "
                                 "(the case's name, e.g. crowning_x0.5)")
