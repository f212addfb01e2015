"""Subcommands after the runs: ``lsbg ltca``, ``combine``, ``summary``, ``report``."""

from __future__ import annotations

from lsbg.cli.options import (
    CommandError,
    add_case_options,
    add_config_options,
    add_geometry_input,
    add_output,
    add_result_inputs,
    checked,
    command_line,
    contact_of,
    fe_compliance_of,
    flank_sections_of,
    flanks_of,
    load_torque_of,
    read_results,
)

__all__ = ["add_ltca_parser", "add_combine_parser", "add_summary_parser", "add_report_parser",
           "add_notebook_kernel_parser"]


# ------------------------------------------------------------------- ltca
def add_ltca_parser(subparsers):
    """``lsbg ltca``: quasi-static loaded tooth contact analysis of the line model."""
    parser = subparsers.add_parser(
        "ltca", help="loaded tooth contact analysis (line model) of one design point",
        description="Solve the static equilibrium of the line contact model under "
                    "simulation.load_torque_N_m at tca.loaded_positions mesh positions over one "
                    "base pitch and write the transmission error, mesh stiffness, contact "
                    "length, tooth-pair loads and contact pattern to --out (NetCDF, CF-1.11). "
                    "The line model's stiffness and slices come from the 'contact' section; "
                    "the flank modification and the assembly displacements from the "
                    "'flank_modification' and 'misalignment' sections (without them: the "
                    "conjugate, aligned pair). Under contact.compliance: fe the teeth's own "
                    "compliance replaces the uniform bed: the contact problem is solved at "
                    "tooth.ltca_positions with the FE influence coefficients of "
                    "--compliance-file and Hertz's local contact, and --out gains the contact "
                    "pressure, the root stresses and the slice stiffness that line-model runs "
                    "take (--fe-ltca).")
    add_geometry_input(parser)
    add_config_options(parser, ("simulation", "contact", "flank_modification", "misalignment",
                                "tca", "tooth", "misalignment_map"))
    parser.add_argument("--compliance-file", metavar="COMPLIANCE.nc",
                        help="the design point's FE compliance (lsbg compliance): read if it "
                             "holds these inputs, else computed and written there; needed "
                             "under contact.compliance: fe")
    parser.add_argument("--envelope", action="store_true",
                        help="with the FE compliance: solve the contact at each corner of the "
                             "assembly's displacement envelope instead (misalignment_map.axes "
                             "at +-misalignment_map.range, added to the misalignment section) "
                             "at half of tooth.ltca_positions, and write the largest contact "
                             "pressure and root stresses at each corner and mesh position")
    add_case_options(parser, "fe_ltca")
    add_output(parser, metavar="MESH.nc")
    parser.set_defaults(handler=run_ltca)


def run_ltca(args):
    """Handler of ``lsbg ltca``: its summary lines."""
    from lsbg.cli.cases import sensitivity_cases

    settings = args.settings
    load = load_torque_of(settings)
    params = contact_of(settings, model="line")
    flanks = flanks_of(settings)  # checks the flank sections before any work
    cases = sensitivity_cases(args, "fe_ltca", args.case_out)
    compliance, positions = None, settings["tca"]["loaded_positions"]
    if params.compliance == "fe":
        compliance, positions = fe_compliance_of(args)
    if args.envelope:  # (its cases at the envelope's positions too: one job, one resolution)
        from lsbg.tooth.analysis import envelope_positions

        positions = envelope_positions(positions)
        lines = [_run_envelope(args, params, load, compliance, positions)]
    else:
        lines = _write_ltca(args, params, load, flanks, compliance, positions, args.out)
    for name, case_params, case_flanks, path in cases:
        lines.append(f"case {name}")
        lines += _write_ltca(args, case_params.replace(compliance=params.compliance), load,
                             case_flanks, compliance, positions, path, case=name)
    return lines


def _write_ltca(args, params, load, flanks, compliance, positions, path, case=None):
    """One loaded TCA of ``lsbg ltca`` (uniform bed, or the FE ``compliance``) -> ``path``
    (``case``: the sensitivity case's name, recorded); its summary lines."""
    from lsbg.files import write_dataset
    from lsbg.tca.loaded import ltca_for_geometry

    if compliance is not None:
        from lsbg.tooth.analysis import fe_ltca_for_geometry

        ds = checked(lambda: fe_ltca_for_geometry(args.geometry, load, params, compliance,
                                                  phases=positions, flanks=flanks))
    else:
        ds = checked(lambda: ltca_for_geometry(args.geometry, load, params, phases=positions,
                                               flanks=flanks))
    ds.attrs["history"] += f"; {command_line()}"
    if case:
        ds.attrs["sensitivity_case"] = case
    write_dataset(ds, path)
    lines = []
    if compliance is not None:
        lines.append(f"FE compliance, max contact pressure "
                     f"{ds.attrs['max_contact_pressure_MPa']:.4g} MPa, max root stress pinion / "
                     f"gear {ds.attrs['max_root_stress_pinion_MPa']:.4g} / "
                     f"{ds.attrs['max_root_stress_gear_MPa']:.4g} MPa")
    lines.append(f"{ds.attrs['phases']} phases, transmission error "
                 f"{ds.attrs['transmission_error_peak_to_peak_urad']:.4g} urad peak to peak, "
                 f"mesh stiffness {ds.attrs['mesh_stiffness_per_face_width_N_per_mm_um']:.4g} "
                 f"N/(mm um) -> {path}")
    return lines


def _run_envelope(args, params, load, compliance, positions):
    """``lsbg ltca --envelope``: the FE loaded TCA at the envelope's corners -> ``--out``."""
    from lsbg.files import write_dataset
    from lsbg.gear.geometry import GearPair
    from lsbg.solid.directory import read_design
    from lsbg.tooth.analysis import fe_envelope

    if compliance is None:
        raise CommandError("--envelope: needs the FE compliance (--set contact.compliance=fe)")
    modification, misalignment = flank_sections_of(args.settings)
    section = args.settings["misalignment_map"]
    axes, half_range = section["axes"], section["range"]
    pair = GearPair(read_design(args.geometry))
    ds = checked(lambda: fe_envelope(pair, params, compliance, load, positions, modification,
                                     misalignment, axes, half_range))
    ds.attrs["history"] = command_line()
    write_dataset(ds, args.out)
    worst = ds["max_contact_pressure"].max("mesh_phase")
    return (f"envelope: {ds.sizes['corner']} corners of {', '.join(axes)} at "
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
    add_result_inputs(
        parser, runs="run files, one per contact model and design point",
        meshes="loaded-TCA files (lsbg ltca), one per design point",
        tca="unloaded-TCA files (lsbg tca, lsbg misalignment-map --tca-out), one per design "
            "point",
        vh="V-H maps (lsbg misalignment-map) on one pair of axes, one per design point")
    add_output(parser, metavar="SWEEP.nc")
    parser.set_defaults(handler=run_combine)


def run_combine(args):
    """Handler of ``lsbg combine``: its summary line."""
    from lsbg.aggregate.combine import combine_runs
    from lsbg.files import write_dataset

    ds = read_results(combine_runs, args)
    write_dataset(ds, args.out)
    return (f"{len(args.runs)} runs ({ds.attrs['solver_engine']}), traces "
            f"{', '.join(map(str, ds.trace.values))}, spiral angles "
            f"{', '.join(f'{a:g}' for a in ds.spiral_angle.values)} deg -> {args.out}")


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
                    "transmission error per 0.1 mm (0.1 deg) of each axis. Windows and "
                    "subgroups from the 'statistics' section.")
    add_result_inputs(
        parser, runs="run files",
        meshes="loaded-TCA files (lsbg ltca): two rows each, the static transmission error "
               "and the mesh stiffness",
        tca="unloaded-TCA files (lsbg tca): one row each, the unloaded transmission error",
        vh="V-H maps (lsbg misalignment-map): four rows per axis, the sensitivities per 0.1 "
           "mm (0.1 deg)")
    add_config_options(parser, ("statistics",))
    add_output(parser, metavar="SUMMARY.csv", help="output CSV file")
    parser.set_defaults(handler=run_summary)


def run_summary(args):
    """Handler of ``lsbg summary``: its summary line."""
    from lsbg.aggregate.summary import statistics_options, summary_table
    from lsbg.files import write_atomically

    options = checked(lambda: statistics_options(args.settings["statistics"]))
    table = read_results(lambda runs, **files: summary_table(runs, **files, **options), args)
    write_atomically(args.out, lambda tmp: table.to_csv(tmp, index=False))
    return f"{len(args.runs)} runs, {len(table)} rows -> {args.out}"


# ----------------------------------------------------------------- report
def add_report_parser(subparsers):
    """``lsbg report``: execute a report notebook and render it as HTML."""
    parser = subparsers.add_parser(
        "report", help="render a report notebook to a self-contained HTML file",
        description="Execute lsbg/notebooks/NAME.ipynb with papermill (parameters from "
                    "--param, relative paths resolved against the current directory) and "
                    "convert it with nbconvert to one HTML file without code, figures "
                    "embedded. Exit code 1 if the notebook fails (nothing written), 2 on bad "
                    "input.")
    parser.add_argument("name", metavar="NAME", help="report name: paper, sweep, verification")
    add_output(parser, metavar="REPORT.html", help="output HTML file")
    parser.add_argument("--param", action="extend", nargs="+", default=[], metavar="KEY=VALUE",
                        help="notebook parameter; VALUE is read as YAML ([a.nc, b.nc] is a "
                             "list, an empty VALUE is the empty string)")
    parser.add_argument("--notebook-dir", metavar="DIR",
                        help="folder of the notebooks (default: the notebooks of the "
                             "lsbg package)")
    parser.add_argument("--timeout", type=float, metavar="S", help="time limit per cell [s]")
    parser.set_defaults(handler=run_report)


def run_report(args):
    """Handler of ``lsbg report``: its summary line."""
    from lsbg.cli.job_server import forked_kernel_manager
    from lsbg.reports import ReportError, parse_parameter, render_report

    parameters = dict(checked(lambda: parse_parameter(text)) for text in args.param)
    try:
        out = checked(lambda: render_report(args.name, args.out, parameters,
                                            notebook_dir=args.notebook_dir,
                                            timeout=args.timeout,
                                            kernel_manager=forked_kernel_manager()))
    except ReportError as err:  # the failing cell and its error, in one line: exit 2
        raise CommandError(str(err).splitlines()[0] if str(err) else repr(err)) from None
    return f"{args.name} -> {out}"


def add_notebook_kernel_parser(subparsers):
    """``lsbg notebook-kernel``: the reports' Jupyter kernel."""
    parser = subparsers.add_parser(
        "notebook-kernel",
        help="the Jupyter kernel of lsbg's reports (started by lsbg report)",
        description="An IPython kernel (ipykernel's IPKernelApp) on a connection file. "
                    "`lsbg report` starts its notebook's kernel this way under a local "
                    "Snakemake run, so that the workflow's job server forks it with the "
                    "reports' imports done (lsbg.cli.job_server.forked_kernel_manager).")
    parser.add_argument("--connection-file", required=True, metavar="FILE",
                        help="the kernel's connection file (Jupyter's -f)")
    parser.add_argument("--kernel-option", action="append", default=[], metavar="OPTION",
                        help="an option of the kernel itself, e.g. "
                             "--kernel-option=--IPKernelApp.log_level=CRITICAL")
    parser.set_defaults(handler=run_notebook_kernel)


def run_notebook_kernel(args):
    """Handler of ``lsbg notebook-kernel``: runs the kernel until it is shut down."""
    from ipykernel.kernelapp import IPKernelApp

    IPKernelApp.launch_instance(argv=["-f", args.connection_file, *args.kernel_option])
    return 0
