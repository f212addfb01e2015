"""Parameter sweeps on the command line: ``lsbg sweep-run`` and ``lsbg sweep-combine``.

``sweep-run`` runs a batch of sweep points (:mod:`lsbg.experiments.sweeps`) at one design
point in one process, so that a cluster pays its per-job start-up once per
batch; ``sweep-combine`` stacks a sweep's runs into one dataset with a
coordinate per swept key (:mod:`lsbg.aggregate.sweep_dataset`).
"""

from __future__ import annotations

from lsbg.cli.options import (CommandError, add_config_options, add_engine_option, add_output,
                              check_output, checked, command_line)

__all__ = ["add_sweep_run_parser", "add_sweep_combine_parser"]


def add_sweep_run_parser(subparsers):
    """``lsbg sweep-run``: several sweep points of one design point, one process."""
    parser = subparsers.add_parser(
        "sweep-run", help="run a batch of parameter-sweep points at one design point",
        description="For each --point RUN.nc KEY=VALUE ..., simulate the pair of --geometry "
                    "with the configuration's settings and the point's values (KEY is "
                    "section.key of the design, contact, simulation, flank_modification or "
                    "misalignment section, in the configuration's units) and write the run to "
                    "RUN.nc, its values recorded as attributes sweep_<section>_<key>. A point "
                    "that sets design keys builds its own geometry (in a temporary folder). "
                    "Every point is checked before the first run; a blow-up stops the batch "
                    "with exit code 3, the points before it written. Each run also records the "
                    "point's quasi-static contact as attributes static_<figure>: the loaded "
                    "TCA's transmission error and pattern (lsbg ltca, uniform bed) and the "
                    "unloaded TCA's bearing pattern (lsbg tca), at the tca section's "
                    "positions.")
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory of the design point (lsbg geometry)")
    add_config_options(parser, ("design", "contact", "simulation", "driveline",
                                "flank_modification", "misalignment", "tca"))
    add_engine_option(parser, default="compiled")
    parser.add_argument("--sweep", required=True, metavar="NAME",
                        help="the sweep's name, recorded in every run")
    parser.add_argument("--kind", choices=("values", "product", "combinations"),
                        default="values", help="how the sweep's points were made (recorded)")
    parser.add_argument("--point", action="append", nargs="+", required=True,
                        metavar="RUN.nc KEY=VALUE",
                        help="an output file and the point's values; repeatable")
    parser.set_defaults(handler=run_sweep_run)


def _point(words):
    """(output path, {section.key: value}) of a --point's words."""
    import yaml

    from lsbg.experiments.sweeps import SWEEPABLE_SECTIONS

    out, *assignments = words
    if "=" in out:
        raise CommandError(f"--point {' '.join(words)}: the output file comes first")
    values = {}
    for text in assignments:
        key, sep, value = text.partition("=")
        section = key.split(".", 1)[0]
        if not sep or "." not in key or section not in SWEEPABLE_SECTIONS:
            raise CommandError(f"--point {out} {text!r}: must be SECTION.KEY=VALUE with SECTION "
                               f"one of {', '.join(SWEEPABLE_SECTIONS)}")
        values[key] = yaml.safe_load(value)
    if not values:
        raise CommandError(f"--point {out}: no KEY=VALUE")
    return out, values


def _point_objects(args, sections, values, design_dir):
    """(settings, contact parameters, flanks, design or None) of one point."""
    from lsbg.contact import ContactParameters
    from lsbg.gear.design import GearPairDesign
    from lsbg.dynamics import SimulationSettings
    from lsbg.solid.directory import read_design
    from lsbg.tca.separation import RealFlanks

    settings = SimulationSettings.from_config(sections["simulation"], engine=args.engine)
    # (a sweep's runs take the uniform bed: the FE slice stiffness is the study's own
    # design points', at their load; lsbg.experiments.sweeps.FIXED_KEYS)
    params = ContactParameters.from_config({**sections["contact"], "compliance": "uniform"})
    flanks = RealFlanks.from_config(sections["flank_modification"], sections["misalignment"])
    design = None
    if any(k.startswith("design.") for k in values):
        base = read_design(design_dir)
        design = GearPairDesign.from_config({**base.to_config(), **sections["design"]})
    return settings, params, flanks, design


def run_sweep_run(args):
    """Handler of ``lsbg sweep-run``: a line per point."""
    import tempfile

    from lsbg.dynamics import SimulationError, simulate
    from lsbg.solid.directory import read_design
    from lsbg.files import write_dataset
    from lsbg.experiments.sweeps import contact_figures, point_sections, swept_attribute

    study = {section: args.settings[section] for section in args.sections}
    read_design(args.geometry)  # the design point exists and is whole
    points = []
    for words in args.point:
        out, values = _point(words)
        check_output(out, "--point")
        sections = point_sections(study, values)
        try:
            points.append((out, values, *_point_objects(args, sections, values, args.geometry)))
        except ValueError as err:
            raise CommandError(f"--point {out}: {err}") from None
    lines = []
    for out, values, settings, params, flanks, design in points:
        with tempfile.TemporaryDirectory(prefix="lsbg-sweep-") as scratch:
            geometry = args.geometry
            if design is not None:
                from lsbg.solid.export import write_geometry

                # the design point of this trace and angle with the point's design keys
                base = read_design(args.geometry)
                geometry = f"{scratch}/geometry"
                write_geometry(design.replace(trace=base.trace, spiral_angle=base.spiral_angle),
                               geometry)
            try:
                ds = simulate(geometry, settings, params, command=command_line(), flanks=flanks,
                              driveline=args.settings.get("driveline"))
            except SimulationError as err:
                raise SimulationError(f"{out}: {err}") from None
            static = checked(lambda: contact_figures(geometry, settings.load_torque, params,
                                                     flanks, args.settings["tca"]))
        ds.attrs.update({"sweep_name": args.sweep, "sweep_kind": args.kind,
                         "sweep_keys": " ".join(values)})
        ds.attrs.update({swept_attribute(k): v for k, v in values.items()})
        ds.attrs.update({f"static_{name}": value for name, value in static.items()})
        write_dataset(ds, out)
        lines.append(f"{', '.join(f'{k} = {v!r}' for k, v in values.items())} -> {out} "
                     f"({ds.attrs['wall_time_s']:.1f} s wall)")
    return lines


def add_sweep_combine_parser(subparsers):
    """``lsbg sweep-combine``: a sweep's runs -> one dataset and a summary table."""
    parser = subparsers.add_parser(
        "sweep-combine", help="combine a parameter sweep's runs into one dataset",
        description="Stack the runs of one sweep (lsbg sweep-run) into one NetCDF dataset "
                    "with a coordinate per swept key (its grid for a product sweep) beside "
                    "the trace and the spiral angle: per run, the mean, the output samples' std "
                    "and the full-rate std of each quantity and the dynamic factor. --csv "
                    "writes the summary rows (lsbg summary) with a column per swept key.")
    parser.add_argument("--runs", nargs="+", required=True, metavar="RUN.nc",
                        help="the sweep's runs")
    add_config_options(parser, ("statistics",))
    add_output(parser, metavar="SWEEP.nc")
    add_output(parser, "--csv", metavar="SWEEP.csv", help="also write the summary rows",
               required=False)
    parser.set_defaults(handler=run_sweep_combine)


def run_sweep_combine(args):
    """Handler of ``lsbg sweep-combine``: its summary line."""
    from lsbg.dynamics.dataset import open_run
    from lsbg.files import write_dataset
    from lsbg.aggregate.summary import statistics_options
    from lsbg.aggregate.sweep_dataset import sweep_dataset, sweep_rows

    options = checked(lambda: statistics_options(args.settings["statistics"]))
    runs = [open_run(path) for path in args.runs]
    try:
        table = sweep_rows(runs, **options)  # once: the dataset is built from these rows
        ds = sweep_dataset(runs, rows=table, **options)
    except ValueError as err:
        raise CommandError(str(err)) from None
    write_dataset(ds, args.out)
    if args.csv:
        from lsbg.files import write_atomically

        write_atomically(args.csv, lambda tmp: table.to_csv(tmp, index=False))
    return (f"{len(runs)} runs of {ds.attrs['sweep_name']} over "
            f"{', '.join(ds.attrs['sweep_keys'].split())} -> {args.out}")
