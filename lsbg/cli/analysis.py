"""Subcommands after the runs: ``lsbg ltca``, ``combine``, ``summary``, ``report``."""

from __future__ import annotations

import sys

from lsbg.cli.options import (CommandError, add_case_options, add_contact_options, check_output,
                              contact_from_args, flanks_from_args, read_study_sections)

__all__ = ["add_ltca_parser", "add_combine_parser", "add_summary_parser", "add_report_parser"]


# ------------------------------------------------------------------- ltca
def add_ltca_parser(subparsers):
    """``lsbg ltca``: quasi-static loaded tooth contact analysis of the line model."""
    from lsbg.cli.tooth import add_tooth_options

    parser = subparsers.add_parser(
        "ltca", help="loaded tooth contact analysis (line model) of one design point",
        description="Solve the static equilibrium of the line contact model under the load at "
                    "--phases mesh positions over one base pitch and write the transmission "
                    "error, mesh stiffness, contact length, tooth-pair loads and contact "
                    "pattern to --out (NetCDF, CF-1.11). The line model's stiffness and slices "
                    "come from the 'contact' section of --config; the flank modification and "
                    "the assembly displacements from its 'flank_modification' and "
                    "'misalignment' sections (without them: the conjugate, aligned pair). Under "
                    "contact.compliance: fe (or --compliance fe) the teeth's own compliance "
                    "replaces the uniform bed: the contact problem is solved with the FE "
                    "influence coefficients of --compliance-file and Hertz's local contact, and "
                    "--out gains the contact pressure, the root stresses and the slice "
                    "stiffness that line-model runs take (--fe-ltca).")
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory written by 'lsbg geometry'")
    add_contact_options(parser, model=False)
    parser.add_argument("--load-torque", type=float, metavar="N_M",
                        help="torque on the gear [N m] (default: simulation.load_torque_N_m of "
                             "--config, else the paper's 1964.99)")
    parser.add_argument("--phases", type=int, metavar="N",
                        help="mesh positions over one base pitch (default 256; with the FE "
                             "compliance tooth.ltca_positions of --config, else 200)")
    add_tooth_options(parser)
    parser.add_argument("--envelope", action="store_true",
                        help="with the FE compliance: solve the contact at each corner of the "
                             "assembly's displacement envelope instead (misalignment_map.axes "
                             "of --config at +-misalignment_map.range, added to its "
                             "misalignment section) and write the largest contact pressure and "
                             "root stresses at each corner and mesh position to --out")
    add_case_options(parser, "fe_ltca")
    parser.add_argument("--out", required=True, metavar="MESH.nc", help="output NetCDF file")
    parser.set_defaults(handler=run_ltca, contact_model="line")


def run_ltca(args):
    """Handler of ``lsbg ltca`` [exit code]."""
    from lsbg.cli.cases import cases_from_args
    from lsbg.dynamics import SimulationSettings

    check_output(args.out, "--out")
    (simulation,) = read_study_sections(args.config, "simulation")
    load = args.load_torque
    if load is None:
        try:
            load = SimulationSettings.from_config(simulation).load_torque
        except ValueError as err:
            raise CommandError(str(err)) from None
    params = contact_from_args(args)
    flanks = flanks_from_args(args)  # checks the flank sections before any work
    cases = cases_from_args(args, "fe_ltca", args.case_out)
    compliance = positions = None
    if params.compliance == "fe":
        from lsbg.cli.tooth import compliance_from_args
        from lsbg.solid.directory import read_design
        from lsbg.gear.geometry import GearPair

        pair = GearPair(read_design(args.geometry))
        compliance, positions = compliance_from_args(args, pair, args.compliance_file)
    if args.envelope:
        _run_envelope(args, params, load, compliance, positions)
    else:
        _write_ltca(args, params, load, flanks, compliance, positions, args.out)
    for name, case_params, case_flanks, path in cases:
        print(f"lsbg ltca: case {name}")
        _write_ltca(args, case_params.replace(compliance=params.compliance), load, case_flanks,
                    compliance, positions, path, case=name)
    return 0


def _write_ltca(args, params, load, flanks, compliance, positions, path, case=None):
    """One loaded TCA of ``lsbg ltca`` (uniform bed, or the FE ``compliance``) -> ``path``
    (``case``: the sensitivity case's name, recorded)."""
    from lsbg.tca.loaded import ltca_for_geometry
    from lsbg.files import write_dataset

    try:
        if compliance is not None:
            from lsbg.tooth.analysis import fe_ltca_for_geometry

            ds = fe_ltca_for_geometry(args.geometry, load, params, compliance,
                                      phases=args.phases or positions, flanks=flanks)
        else:
            ds = ltca_for_geometry(args.geometry, load, params, phases=args.phases or 256,
                                   flanks=flanks)
    except ValueError as err:
        raise CommandError(str(err)) from None
    ds.attrs["history"] += f"; {' '.join(['lsbg', *sys.argv[1:]])}"
    if case:
        ds.attrs["sensitivity_case"] = case
    write_dataset(ds, path)
    if compliance is not None:
        print(f"lsbg ltca: FE compliance, max contact pressure "
              f"{ds.attrs['max_contact_pressure_MPa']:.4g} MPa, max root stress pinion / gear "
              f"{ds.attrs['max_root_stress_pinion_MPa']:.4g} / "
              f"{ds.attrs['max_root_stress_gear_MPa']:.4g} MPa")
    print(f"lsbg ltca: {ds.attrs['phases']} phases, transmission error "
          f"{ds.attrs['transmission_error_peak_to_peak_urad']:.4g} urad peak to peak, mesh "
          f"stiffness {ds.attrs['mesh_stiffness_per_face_width_N_per_mm_um']:.4g} N/(mm um) "
          f"-> {path}")


def _run_envelope(args, params, load, compliance, positions):
    """``lsbg ltca --envelope``: the FE loaded TCA at the envelope's corners -> ``--out``."""
    from lsbg.cli.options import flank_sections_from_args
    from lsbg.solid.directory import read_design
    from lsbg.gear.geometry import GearPair
    from lsbg.files import write_dataset
    from lsbg.tooth.analysis import fe_envelope

    if compliance is None:
        raise CommandError("--envelope: needs the FE compliance (--compliance fe)")
    modification, misalignment = flank_sections_from_args(args)
    (vh,) = read_study_sections(args.config, "misalignment_map")
    axes, half_range = vh.get("axes") or ["E", "P"], vh.get("range") or 0.1
    pair = GearPair(read_design(args.geometry))
    try:
        ds = fe_envelope(pair, params, compliance, load, args.phases or positions, modification,
                         misalignment, axes, half_range)
    except ValueError as err:
        raise CommandError(str(err)) from None
    ds.attrs["history"] = " ".join(["lsbg", *sys.argv[1:]])
    write_dataset(ds, args.out)
    worst = ds["max_contact_pressure"].max("mesh_phase")
    print(f"lsbg ltca --envelope: {ds.sizes['corner']} corners of {', '.join(axes)} at "
          f"+-{half_range:g}; largest contact pressure {float(worst.max()):.4g} MPa at "
          f"{str(worst.idxmax().values)} -> {args.out}")


# ---------------------------------------------------------------- combine
def add_combine_parser(subparsers):
    """``lsbg combine``: the run files of a sweep -> one NetCDF dataset."""
    parser = subparsers.add_parser(
        "combine", help="combine the runs of a sweep into one dataset",
        description="Stack run files (lsbg simulate) of one engine and one time axis into a "
                    "dataset with dims (contact_model, trace, spiral_angle, time) and "
                    "per-point variables such as contact_ratio(trace, spiral_angle) and, from "
                    "loaded TCAs (lsbg ltca), the static transmission error and mesh "
                    "stiffness; from unloaded TCAs (lsbg tca) the transmission error, bearing "
                    "pattern, edge contact and backlash; from V-H maps (lsbg "
                    "misalignment-map) the maps on the union of their grids and their "
                    "sensitivities per 0.1 mm (0.1 deg); missing points are NaN (NetCDF, "
                    "CF-1.11).")
    parser.add_argument("--runs", nargs="+", required=True, metavar="RUN.nc",
                        help="run files, one per contact model and design point")
    parser.add_argument("--meshes", nargs="+", default=[], metavar="MESH.nc",
                        help="loaded-TCA files (lsbg ltca), one per design point")
    parser.add_argument("--tca", nargs="+", default=[], metavar="TCA.nc",
                        help="unloaded-TCA files (lsbg tca, lsbg misalignment-map --tca-out), "
                             "one per design point")
    parser.add_argument("--vh", nargs="+", default=[], metavar="MAP.nc",
                        help="V-H maps (lsbg misalignment-map) on one pair of axes, one per "
                             "design point")
    parser.add_argument("--out", required=True, metavar="SWEEP.nc", help="output NetCDF file")
    parser.set_defaults(handler=run_combine)


def run_combine(args):
    """Handler of ``lsbg combine`` [exit code]."""
    from lsbg.files import write_dataset
    from lsbg.aggregate.combine import combine_runs

    check_output(args.out, "--out")
    try:
        ds = combine_runs(args.runs, meshes=args.meshes, tca=args.tca, vh_maps=args.vh)
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
                    "harmonics) and the mesh stiffness; for every unloaded TCA its "
                    "transmission error (engine 'tca'), and for every V-H map the pattern's "
                    "movement toe-heel and root-tip and the change of the unloaded and loaded "
                    "transmission error per 0.1 mm (0.1 deg) of each axis. Settings from the "
                    "'statistics' section of --config, overridden by the options.")
    parser.add_argument("--runs", nargs="+", required=True, metavar="RUN.nc", help="run files")
    parser.add_argument("--meshes", nargs="+", default=[], metavar="MESH.nc",
                        help="loaded-TCA files (lsbg ltca): two rows each, the static "
                             "transmission error and the mesh stiffness")
    parser.add_argument("--tca", nargs="+", default=[], metavar="TCA.nc",
                        help="unloaded-TCA files (lsbg tca): one row each, the unloaded "
                             "transmission error")
    parser.add_argument("--vh", nargs="+", default=[], metavar="MAP.nc",
                        help="V-H maps (lsbg misalignment-map): four rows per axis, the "
                             "sensitivities per 0.1 mm (0.1 deg)")
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
    from lsbg.files import write_atomically
    from lsbg.aggregate.summary import statistics_options, summary_table

    check_output(args.out, "--out")
    (section,) = read_study_sections(args.config, "statistics")
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
        table = summary_table(args.runs, meshes=args.meshes, tca=args.tca, vh_maps=args.vh,
                              **options)
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

    check_output(args.out, "--out")
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
    except ReportError as err:  # the failing cell and its error, in one line: exit 2
        raise CommandError(str(err).splitlines()[0] if str(err) else repr(err)) from None
    print(f"lsbg report: {args.name} -> {out}")
    return 0


