"""Command line interface: ``lsbg <subcommand> ...``.

Every subcommand is a function ``add_<name>_parser(subparsers)`` that adds its
parser and sets ``handler=<function(args) -> exit code>`` as a default. They
are listed in :data:`PARSERS`, either as the function itself or as a
``"module:function"`` string imported when the parser is built. To add a
subcommand (e.g. ``simulate``), write, in its own module::

    from lsbg import cli

    def add_simulate_parser(subparsers):
        parser = subparsers.add_parser("simulate", help="...")
        cli.add_design_options(parser)       # the same design options as geometry
        parser.set_defaults(handler=run_simulate)

and add ``"lsbg.<module>:add_simulate_parser"`` to :data:`PARSERS`. Keep heavy
imports inside the handler, so that ``lsbg --help`` stays fast. Handlers may
raise :class:`lsbg.design.DesignError` (or :class:`CommandError`): :func:`main`
prints the message on stderr and returns exit code 2.

Exit codes: 0 success; 2 bad input (argparse usage errors raise
``SystemExit(2)``, design errors return 2).
"""

from __future__ import annotations

import argparse
import importlib
import logging
import math
import sys

from lsbg import __version__
from lsbg.design import BASE_CONE_RULES, CONFIG_KEYS, HANDS, TRACES, DesignError, GearPairDesign

__all__ = ["main", "build_parser", "add_design_options", "design_from_args", "CommandError",
           "PARSERS", "add_geometry_parser", "add_simulate_parser", "add_convergence_parser",
           "add_ltca_parser", "add_combine_parser", "add_summary_parser", "add_report_parser"]


class CommandError(ValueError):
    """Bad command-line input that is not a design parameter (exit code 2)."""


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

    Options are generated from :data:`lsbg.design.CONFIG_KEYS` (``module_mm``
    -> ``--module-mm``), in the paper's units; each defaults to ``None`` so
    that :func:`design_from_args` can tell what was given.

    Parameters
    ----------
    parser : argparse.ArgumentParser
    """
    paper = GearPairDesign().to_config()
    group = parser.add_argument_group(
        "design parameters (paper units; they override --design; defaults: the paper's "
        "Table 1 and lsbg.design.GearPairDesign)")
    group.add_argument("--design", metavar="FILE.yaml",
                       help="YAML file with design keys as in lsbg.design.CONFIG_KEYS")
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


def _read_yaml(path, option="--design"):
    import yaml

    try:
        with open(path, encoding="utf-8") as handle:
            data = yaml.safe_load(handle)
    except OSError as error:
        raise CommandError(f"{option} {path}: {error.strerror}") from None
    except yaml.YAMLError as error:
        raise CommandError(f"{option} {path}: not valid YAML ({error})") from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise CommandError(f"{option} {path}: must hold a mapping of keys")
    return data


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
    config = _read_yaml(args.design) if getattr(args, "design", None) else {}
    for key in CONFIG_KEYS:
        value = getattr(args, key, None)
        if value is not None:
            config[key] = value
    return GearPairDesign.from_config(config)


# --------------------------------------------------------------- geometry
def add_geometry_parser(subparsers):
    """``lsbg geometry``: design.json, flanks, meshes, URDF and picture of one design."""
    parser = subparsers.add_parser(
        "geometry", help="write the geometry of one design point",
        description="Write design.json, flanks.nc, pinion/gear STL and OBJ, pair.urdf and "
                    "pair.png of one design point into --out (replaced atomically).")
    add_design_options(parser)
    parser.add_argument("--out", required=True, metavar="DIR", help="output directory")
    parser.set_defaults(handler=run_geometry)


def run_geometry(args):
    """Handler of ``lsbg geometry`` [exit code]."""
    from lsbg.export import STAGES, write_geometry

    design = design_from_args(args)
    result = write_geometry(design, args.out)
    times = ", ".join(f"{stage} {result.timings[stage]:.2f}" for stage in STAGES)
    print(f"lsbg geometry: {design.trace}, spiral angle {math.degrees(design.spiral_angle):g} deg "
          f"-> {result.directory} ({times}; total {result.timings['total']:.2f} s)")
    return 0


# --------------------------------------------------------------- simulate
def _read_study_sections(path, *sections):
    """The named sections of a study configuration file (``{}`` if no file)."""
    if path is None:
        return [{} for _ in sections]
    config = _read_yaml(path, "--config")
    return [config.get(section) or {} for section in sections]


#: Command-line options of ``lsbg simulate`` -> key of the ``simulation`` section.
_SIMULATION_OPTIONS = {
    "duration": ("duration_s", float, "simulated time [s] (paper: 1)"),
    "samples": ("samples", int, "output intervals; samples+1 instants (paper: 500)"),
    "dt": ("time_step_s", float, "fixed time step of the pybullet engine [s] (1e-6)"),
    "rtol": ("rtol", float, "relative tolerance of the scipy engine (1e-8)"),
    "method": ("method", str, "solve_ivp method of the scipy engine (LSODA)"),
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


def contact_from_args(args):
    """Contact parameters from the ``contact`` section of ``--config``, ``--set-contact``
    and ``--contact-model``."""
    import yaml

    from lsbg.contact import ContactParameters

    (contact,) = _read_study_sections(args.config, "contact")
    contact = dict(contact)
    for text in getattr(args, "set_contact", []):
        key, sep, value = text.partition("=")
        if not sep or not key.strip():
            raise CommandError(f"--set-contact {text!r}: must be KEY=VALUE")
        contact[key.strip()] = yaml.safe_load(value)
    if args.contact_model is not None:
        contact["model"] = args.contact_model
    try:
        return ContactParameters.from_config(contact)
    except ValueError as err:
        raise CommandError(str(err)) from None


def add_simulation_options(parser):
    """Add ``--geometry``, ``--engine``, the contact options and the simulation settings."""
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory written by 'lsbg geometry'")
    parser.add_argument("--engine", choices=("pybullet", "scipy", "compiled"), default="pybullet",
                        help="integrator: pybullet (multibody, fixed step), scipy (solve_ivp) or "
                             "compiled (embedded Runge-Kutta compiled with numba) "
                             "(default: pybullet)")
    add_contact_options(parser)
    for option, (key, kind, text) in _SIMULATION_OPTIONS.items():
        parser.add_argument(f"--{option.replace('_', '-')}", dest=option, type=kind, help=text)


def simulation_from_args(args):
    """(settings, contact parameters) from ``--config`` and the options."""
    from lsbg.dynamics import SimulationSettings

    (simulation,) = _read_study_sections(args.config, "simulation")
    simulation = dict(simulation)
    for option, (key, _, _) in _SIMULATION_OPTIONS.items():
        value = getattr(args, option, None)
        if value is not None:
            simulation[key] = value
    try:
        settings = SimulationSettings.from_config(simulation, engine=args.engine)
    except ValueError as err:
        raise CommandError(str(err)) from None
    return settings, contact_from_args(args)


def add_simulate_parser(subparsers):
    """``lsbg simulate``: one meshing simulation -> one NetCDF time series."""
    parser = subparsers.add_parser(
        "simulate", help="simulate the meshing of one design point",
        description="Simulate the meshing of the pair in --geometry (paper §3: pinion speed "
                    "ramped to 7703 deg/s, gear loaded with 1964.99 N m) and write the time "
                    "series to --out (NetCDF, CF-1.11). A blow-up (NaN, penetration beyond d, "
                    "runaway speed) stops the run with exit code 3 and writes nothing.")
    add_simulation_options(parser)
    parser.add_argument("--out", required=True, metavar="RUN.nc", help="output NetCDF file")
    parser.set_defaults(handler=run_simulate)


def run_simulate(args):
    """Handler of ``lsbg simulate`` [exit code]."""
    from lsbg.dynamics import SimulationError, simulate
    from lsbg.results import write_dataset

    settings, params = simulation_from_args(args)
    try:
        ds = simulate(args.geometry, settings, params, command=" ".join(["lsbg", *sys.argv[1:]]))
    except SimulationError as err:
        print(f"lsbg simulate: simulation stopped: {err}", file=sys.stderr)
        return 3
    write_dataset(ds, args.out)
    print(f"lsbg simulate: {settings.engine} engine, {params.model} model -> {args.out} "
          f"({ds.attrs['wall_time_s']:.1f} s wall)")
    return 0


# ------------------------------------------------------------------- ltca
def add_ltca_parser(subparsers):
    """``lsbg ltca``: quasi-static loaded tooth contact analysis of the line model."""
    parser = subparsers.add_parser(
        "ltca", help="loaded tooth contact analysis (line model) of one design point",
        description="Solve the static equilibrium of the line contact model under the load at "
                    "--phases mesh positions over one base pitch and write the transmission "
                    "error, mesh stiffness, contact length, tooth-pair loads and contact "
                    "pattern to --out (NetCDF, CF-1.11). The line model's stiffness and slices "
                    "come from the 'contact' section of --config.")
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory written by 'lsbg geometry'")
    add_contact_options(parser, model=False)
    parser.add_argument("--load-torque", type=float, metavar="N_M",
                        help="torque on the gear [N m] (default: simulation.load_torque_N_m of "
                             "--config, else the paper's 1964.99)")
    parser.add_argument("--phases", type=int, default=256, metavar="N",
                        help="mesh positions over one base pitch (default 256)")
    parser.add_argument("--out", required=True, metavar="MESH.nc", help="output NetCDF file")
    parser.set_defaults(handler=run_ltca, contact_model="line")


def run_ltca(args):
    """Handler of ``lsbg ltca`` [exit code]."""
    from lsbg.dynamics import SimulationSettings
    from lsbg.ltca import ltca_for_geometry
    from lsbg.results import write_dataset

    (simulation,) = _read_study_sections(args.config, "simulation")
    load = args.load_torque
    if load is None:
        try:
            load = SimulationSettings.from_config(simulation).load_torque
        except ValueError as err:
            raise CommandError(str(err)) from None
    params = contact_from_args(args)
    try:
        ds = ltca_for_geometry(args.geometry, load, params, phases=args.phases)
    except ValueError as err:
        raise CommandError(str(err)) from None
    ds.attrs["history"] += f"; {' '.join(['lsbg', *sys.argv[1:]])}"
    write_dataset(ds, args.out)
    print(f"lsbg ltca: {ds.attrs['phases']} phases, transmission error "
          f"{ds.attrs['transmission_error_peak_to_peak_urad']:.4g} urad peak to peak, mesh "
          f"stiffness {ds.attrs['mesh_stiffness_per_face_width_N_per_mm_um']:.4g} N/(mm um) "
          f"-> {args.out}")
    return 0


# ------------------------------------------------------------ convergence
def add_convergence_parser(subparsers):
    """``lsbg convergence``: standard deviations against time step and tolerance."""
    parser = subparsers.add_parser(
        "convergence", help="convergence table of one design point",
        description="Run one design point with pybullet at dt = 4e-6, 2e-6, 1e-6 s and scipy "
                    "at rtol = 1e-6, 1e-8, 1e-10, and write the standard deviations of gear "
                    "speed and tangential force after the steady-state start to --out (CSV).")
    add_simulation_options(parser)
    parser.add_argument("--steady-state-after", type=float, default=0.2, metavar="S",
                        help="start of the steady state [s] (default 0.2)")
    parser.add_argument("--out", required=True, metavar="TABLE.csv", help="output CSV file")
    parser.set_defaults(handler=run_convergence)


def run_convergence(args):
    """Handler of ``lsbg convergence`` [exit code]."""
    from lsbg.dynamics import SimulationError, load_model
    from lsbg.results import write_atomically
    from lsbg.verification import convergence_study

    settings, params = simulation_from_args(args)
    model = load_model(args.geometry, params)
    try:
        table = convergence_study(model, settings, steady_start=args.steady_state_after)
    except SimulationError as err:
        print(f"lsbg convergence: simulation stopped: {err}", file=sys.stderr)
        return 3
    write_atomically(args.out, lambda tmp: table.to_csv(tmp, index=False))
    print(table.to_string(index=False))
    return 0


# ---------------------------------------------------------------- combine
def add_combine_parser(subparsers):
    """``lsbg combine``: the run files of a sweep -> one NetCDF dataset."""
    parser = subparsers.add_parser(
        "combine", help="combine the runs of a sweep into one dataset",
        description="Stack run files (lsbg simulate) of one engine and one time axis into a "
                    "dataset with dims (contact_model, trace, spiral_angle, time) and "
                    "per-point variables such as contact_ratio(trace, spiral_angle) and, from "
                    "loaded TCAs (lsbg ltca), the static transmission error and mesh "
                    "stiffness; missing points are NaN (NetCDF, CF-1.11).")
    parser.add_argument("--runs", nargs="+", required=True, metavar="RUN.nc",
                        help="run files, one per contact model and design point")
    parser.add_argument("--meshes", nargs="+", default=[], metavar="MESH.nc",
                        help="loaded-TCA files (lsbg ltca), one per design point")
    parser.add_argument("--out", required=True, metavar="SWEEP.nc", help="output NetCDF file")
    parser.set_defaults(handler=run_combine)


def run_combine(args):
    """Handler of ``lsbg combine`` [exit code]."""
    from lsbg.results import write_dataset
    from lsbg.study import combine_runs

    try:
        ds = combine_runs(args.runs, meshes=args.meshes)
    except (OSError, ValueError) as err:
        raise CommandError(f"--runs: {err}") from None
    write_dataset(ds, args.out)
    print(f"lsbg combine: {len(args.runs)} runs ({ds.attrs['solver_engine']}), traces "
          f"{', '.join(map(str, ds.trace.values))}, spiral angles "
          f"{', '.join(f'{a:g}' for a in ds.spiral_angle.values)} deg -> {args.out}")
    return 0


# ---------------------------------------------------------------- summary
def add_summary_parser(subparsers):
    """``lsbg summary``: the paper's §4 statistics of every run -> CSV."""
    parser = subparsers.add_parser(
        "summary", help="steady-state statistics of runs as a CSV table",
        description="For every run and quantity (gear_speed, tangential_force, "
                    "tangential_force_outer, transmission_error, contact_torque): "
                    "steady-state mean and std, Anderson-Darling A2 and p, the theoretical "
                    "value (Eq. 12/13, the load), the error rate, the number of Xbar-R "
                    "subgroups out of control, and from the full-rate record the std, the "
                    "spread of the sampled std over sampling phases and the dynamic factor; "
                    "for every loaded TCA the static transmission error (peak to peak, mesh "
                    "harmonics) and the mesh stiffness. Settings from the 'statistics' "
                    "section of --config, overridden by the options.")
    parser.add_argument("--runs", nargs="+", required=True, metavar="RUN.nc", help="run files")
    parser.add_argument("--meshes", nargs="+", default=[], metavar="MESH.nc",
                        help="loaded-TCA files (lsbg ltca): two rows each, the static "
                             "transmission error and the mesh stiffness")
    parser.add_argument("--config", metavar="FILE.yaml",
                        help="study configuration; its 'statistics' section is used "
                             "(steady_state_after_s, control_chart_window_s, subgroup_size)")
    parser.add_argument("--steady-state-after", type=float, metavar="S",
                        help="end of the transient [s] (default 0.2)")
    parser.add_argument("--window", type=float, nargs=2, metavar=("START", "STOP"),
                        help="Xbar-R window [s] (default 0.8 1.0)")
    parser.add_argument("--subgroup-size", type=int, metavar="N",
                        help="Xbar-R subgroup size (default 4)")
    parser.add_argument("--out", required=True, metavar="SUMMARY.csv", help="output CSV file")
    parser.set_defaults(handler=run_summary)


def run_summary(args):
    """Handler of ``lsbg summary`` [exit code]."""
    from lsbg.results import write_atomically
    from lsbg.study import statistics_options, summary_table

    (section,) = _read_study_sections(args.config, "statistics")
    try:
        options = statistics_options(section)
    except ValueError as err:
        raise CommandError(f"--config {args.config}: {err}") from None
    for option, key in (("steady_state_after", "steady_state_after"), ("window", "window"),
                        ("subgroup_size", "subgroup_size")):
        value = getattr(args, option, None)
        if value is not None:
            options[key] = tuple(value) if option == "window" else value
    try:
        table = summary_table(args.runs, meshes=args.meshes, **options)
    except (OSError, ValueError) as err:
        raise CommandError(f"--runs: {err}") from None
    write_atomically(args.out, lambda tmp: table.to_csv(tmp, index=False))
    print(f"lsbg summary: {len(args.runs)} runs, {len(table)} rows -> {args.out}")
    return 0


# ----------------------------------------------------------------- report
def add_report_parser(subparsers):
    """``lsbg report``: execute a report notebook and render it as HTML."""
    parser = subparsers.add_parser(
        "report", help="render a report notebook to a self-contained HTML file",
        description="Execute workflow/notebooks/NAME.ipynb with papermill (parameters from "
                    "--param, relative paths resolved against the current directory) and "
                    "convert it with nbconvert to one HTML file without code, figures "
                    "embedded. Exit code 1 if the notebook fails (nothing written), 2 on bad "
                    "input.")
    parser.add_argument("name", metavar="NAME", help="report name: paper, sweep, verification")
    parser.add_argument("--out", required=True, metavar="REPORT.html", help="output HTML file")
    parser.add_argument("--param", action="extend", nargs="+", default=[], metavar="KEY=VALUE",
                        help="notebook parameter; VALUE is read as YAML ([a.nc, b.nc] is a "
                             "list, an empty VALUE is the empty string)")
    parser.add_argument("--notebook-dir", metavar="DIR",
                        help="folder of the notebooks (default: workflow/notebooks of the "
                             "lsbg repository)")
    parser.add_argument("--timeout", type=float, metavar="S", help="time limit per cell [s]")
    parser.set_defaults(handler=run_report)


def run_report(args):
    """Handler of ``lsbg report`` [exit code]."""
    from lsbg.reports import ReportError, parse_parameter, render_report

    parameters = {}
    for text in args.param:
        try:
            key, value = parse_parameter(text)
        except ValueError as err:
            raise CommandError(str(err)) from None
        parameters[key] = value
    try:
        out = render_report(args.name, args.out, parameters, notebook_dir=args.notebook_dir,
                            timeout=args.timeout)
    except ValueError as err:
        raise CommandError(str(err)) from None
    except ReportError as err:
        print(f"lsbg report: error: {err}", file=sys.stderr)
        return 1
    print(f"lsbg report: {args.name} -> {out}")
    return 0


#: One ``add_<name>_parser(subparsers)`` per subcommand: a function or a
#: ``"module:function"`` string.
PARSERS = [add_geometry_parser, add_simulate_parser, add_convergence_parser, add_ltca_parser,
           add_combine_parser, add_summary_parser, add_report_parser]


def build_parser():
    """The ``lsbg`` argument parser with every subcommand of :data:`PARSERS`."""
    parser = argparse.ArgumentParser(
        prog="lsbg", description="Logarithmic spiral bevel gears: geometry, meshing dynamics "
                                 "and statistics (SI inside, paper units at the edges).")
    parser.add_argument("--version", action="version", version=f"lsbg {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress on stderr")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for add in PARSERS:
        if isinstance(add, str):
            module, _, name = add.partition(":")
            add = getattr(importlib.import_module(module), name)
        add(subparsers)
    for sub in subparsers.choices.values():
        # Also accept -v after the subcommand (SUPPRESS keeps the global value).
        sub.add_argument("-v", "--verbose", action="store_true", default=argparse.SUPPRESS,
                         help="log progress on stderr")
    return parser


def main(argv=None):
    """Run ``lsbg`` with ``argv`` (default ``sys.argv[1:]``).

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        Exit code: 0 on success, 2 on bad input (message on stderr, nothing
        written). Usage errors found by argparse raise ``SystemExit(2)``.
    """
    args = build_parser().parse_args(argv)
    if args.verbose:
        logging.basicConfig(level=logging.INFO, format="%(name)s: %(message)s")
    try:
        return args.handler(args)
    except (DesignError, CommandError) as error:
        print(f"lsbg {args.command}: error: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
