"""Contact state: ``lsbg tca`` and ``lsbg misalignment-map``."""

from __future__ import annotations

import argparse
import sys

from lsbg.cli.options import (CommandError, add_case_options, add_contact_options,
                              add_flank_options, check_output, contact_from_args,
                              flanks_from_args, read_study_sections)

__all__ = ["add_tca_parser", "add_misalignment_map_parser"]

#: Defaults of the ``tca:`` and ``misalignment_map:`` sections (config units).
TCA_DEFAULTS = {"positions": 200, "marking_compound_um": 6.35}
MAP_DEFAULTS = {"axes": ["E", "P"], "range": 0.1, "steps": 9, "sweep_steps": 5, "positions": 100,
                "load_torque_N_m": None}


def _design_pair(geometry):
    from lsbg.solid.directory import read_design
    from lsbg.gear.geometry import GearPair

    return GearPair(read_design(geometry))


def _section(args, name, defaults):
    (section,) = read_study_sections(getattr(args, "config", None), name)
    unknown = sorted(set(section) - set(defaults))
    if unknown:
        raise CommandError(f"{name}.{unknown[0]} = {section[unknown[0]]!r}: unknown key "
                           f"(known: {sorted(defaults)})")
    return {**defaults, **{k: v for k, v in section.items() if v is not None}}


# -------------------------------------------------------------------- tca
def add_tca_parser(subparsers):
    """``lsbg tca``: unloaded tooth contact analysis from the flank surfaces."""
    parser = subparsers.add_parser(
        "tca", help="unloaded tooth contact analysis from the real flank surfaces",
        description="Turn the pinion through one mesh cycle and find, at each position, where "
                    "the modified pinion flank and the displaced gear flank first touch; write "
                    "the unloaded transmission error, the path of contact, the contact "
                    "ellipses at the marking-compound thickness, the bearing pattern on the "
                    "gear flank, the backlash and the edge-contact flags to --out (NetCDF, "
                    "CF-1.11). The flank modification and the displacements come from the "
                    "'flank_modification' and 'misalignment' sections of --config and the "
                    "options; without them the pair is the conjugate, aligned one.")
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory written by 'lsbg geometry'")
    parser.add_argument("--config", metavar="FILE.yaml",
                        help="study configuration; its 'flank_modification', 'misalignment' "
                             "and 'tca' sections are used")
    add_flank_options(parser)
    parser.add_argument("--positions", type=int, metavar="N",
                        help="pinion positions over one mesh cycle (default: tca.positions of "
                             "--config, else 200)")
    parser.add_argument("--marking-um", type=float, metavar="UM",
                        help="marking-compound thickness [um] (default: "
                             "tca.marking_compound_um, else 6.35)")
    parser.add_argument("--out", required=True, metavar="TCA.nc", help="output NetCDF file")
    parser.set_defaults(handler=run_tca)


def run_tca(args):
    """Handler of ``lsbg tca`` [exit code]."""
    from lsbg.files import write_dataset

    flanks = flanks_from_args(args)
    pair = _design_pair(args.geometry)
    check_output(args.out, "--out")
    ds = _tca(args, pair, flanks)
    write_dataset(ds, args.out)
    _report_tca(ds, args.out)
    return 0


def _tca(args, pair, flanks):
    """The unloaded TCA of the options and the ``tca`` section."""
    from lsbg.tca.analysis import tooth_contact_analysis

    section = _section(args, "tca", TCA_DEFAULTS)
    positions, marking = getattr(args, "positions", None), getattr(args, "marking_um", None)
    positions = section["positions"] if positions is None else positions
    marking = section["marking_compound_um"] if marking is None else marking
    try:
        ds = tooth_contact_analysis(pair, flanks.modification, flanks.misalignment, positions,
                                    float(marking) * 1e-6)
    except ValueError as err:
        raise CommandError(str(err)) from None
    ds.attrs["history"] = " ".join(["lsbg", *sys.argv[1:]])
    return ds


def _report_tca(ds, path):
    a = ds.attrs
    print(f"lsbg tca: {a['positions']} positions, transmission error "
          f"{a['transmission_error_peak_to_peak_urad']:.4g} urad "
          f"({a['transmission_error_peak_to_peak_arcsec']:.3g} arcsec) peak to peak, pattern "
          f"{a['pattern_toe_mm']:.4g}-{a['pattern_heel_mm']:.4g} mm from the apex, edge contact "
          f"at {100 * a['edge_contact_share']:.3g} % of positions -> {path}")


# -------------------------------------------------------- misalignment map
def add_misalignment_map_parser(subparsers):
    """``lsbg misalignment-map``: V-H map of a design point."""
    parser = subparsers.add_parser(
        "misalignment-map", help="V-H map: the contact under a grid of two displacements",
        description="On a grid of two assembly displacements (E, P, G [mm] or Sigma [deg]), "
                    "run the unloaded tooth contact analysis from the surfaces and the loaded "
                    "TCA of the line model on the same separation field, and write the "
                    "transmission error (unloaded and loaded, peak to peak), the bearing "
                    "pattern's centre and its movement, and the edge-contact shares to --out "
                    "(NetCDF), with the sensitivities per 0.1 mm (0.1 deg) as attributes. "
                    "Settings from the 'misalignment_map' section of --config and the options; "
                    "the grid is added to the 'misalignment' section's displacements.")
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory written by 'lsbg geometry'")
    add_contact_options(parser, model=False)
    parser.add_argument("--axes", nargs=2, choices=("E", "P", "G", "Sigma"), metavar="AXIS",
                        help="the two displacements (default: misalignment_map.axes, else E P)")
    parser.add_argument("--range", type=float, metavar="MM",
                        help="largest displacement either way [mm, deg for Sigma] (default: "
                             "misalignment_map.range, else 0.1)")
    parser.add_argument("--steps", type=int, metavar="N",
                        help="values per axis, odd (default: misalignment_map.steps, else 9; "
                             "the workflow passes sweep_steps at the sweep's other spiral angles)")
    parser.add_argument("--positions", type=int, metavar="N",
                        help="positions of each unloaded TCA (default: "
                             "misalignment_map.positions, else 100)")
    parser.add_argument("--load-torque", type=float, metavar="N_M",
                        help="torque on the gear of the loaded TCA [N m] (default: "
                             "misalignment_map.load_torque_N_m, else simulation.load_torque_N_m)")
    parser.add_argument("--out", required=True, metavar="MAP.nc", help="output NetCDF file")
    parser.add_argument("--spiral-angles", type=float, nargs="+", metavar="DEG",
                        help="several design points in one process: --geometry, --out and "
                             "--tca-out are then templates with the field {spiral} (the angle "
                             "as in the workflow's file names, e.g. 37.5)")
    parser.add_argument("--tca-out", metavar="TCA.nc",
                        help="also write the unloaded TCA of the undisplaced cell at the "
                             "'tca' section's resolution (as 'lsbg tca --out'), in the same "
                             "process")
    add_case_options(parser, "contact_state")
    parser.add_argument("--case-steps", type=int, metavar="N",
                        help="values per axis of each case's map, odd (default: --steps)")
    parser.set_defaults(handler=run_misalignment_map, contact_model="line")


def run_misalignment_map(args):
    """Handler of ``lsbg misalignment-map`` [exit code]."""
    from lsbg.cli.cases import cases_from_args
    from lsbg.dynamics import SimulationSettings
    from lsbg.files import fill_template, number_label
    from lsbg.files import write_dataset
    from lsbg.tca.vh_map import axis_values, misalignment_map

    section = _section(args, "misalignment_map", MAP_DEFAULTS)
    for key in ("axes", "range", "steps", "positions"):
        if getattr(args, key) is not None:
            section[key] = getattr(args, key)
    load = args.load_torque if args.load_torque is not None else section["load_torque_N_m"]
    (simulation,) = read_study_sections(args.config, "simulation")
    try:
        if load is None:
            load = SimulationSettings.from_config(simulation).load_torque
        values = axis_values(section["range"], section["steps"])
        # one design point, or several (file names are templates with {spiral})
        angles = [None] if args.spiral_angles is None else list(args.spiral_angles)
        points = [{key: (fill_template(path, option, spiral=number_label(angle))
                         if angle is not None and path else path)
                   for key, path, option in (("geometry", args.geometry, "--geometry"),
                                             ("out", args.out, "--out"),
                                             ("tca", args.tca_out, "--tca-out"))}
                  for angle in angles]
    except ValueError as err:
        raise CommandError(str(err)) from None
    names = [path for point in points for key, path in point.items() if key != "geometry" and path]
    if len(set(names)) < len(names):
        raise CommandError("--out, --tca-out: several design points would write the same file; "
                           "put {spiral} in every template")
    # The map's loaded TCAs stay on the uniform bed: the tooth's slice stiffness is
    # the secant of one assembly (docs/model.md, "The tooth itself").
    params = contact_from_args(args).replace(compliance="uniform")
    flanks = flanks_from_args(args)
    cases = cases_from_args(args, "contact_state", args.case_out)
    if cases and len(points) > 1:
        raise CommandError("--case: one design point only (not with --spiral-angles)")
    try:
        case_values = axis_values(section["range"], args.case_steps or section["steps"])
    except ValueError as err:
        raise CommandError(f"--case-steps {args.case_steps}: {err}") from None
    pairs = [_design_pair(point["geometry"]) for point in points]
    for point in points:
        check_output(point["out"], "--out")
        if point["tca"]:
            check_output(point["tca"], "--tca-out")
    # the unloaded TCAs of the design point's map, reused by its cases' maps where their
    # flanks and cells are the same (the line-stiffness cases, the cells of a coarser map)
    unloaded = {}
    for pair, point in zip(pairs, points):
        unloaded.clear()
        try:
            ds = misalignment_map(pair, flanks.modification, section["axes"], (values, values),
                                  load, params, base=flanks.misalignment,
                                  positions=section["positions"], unloaded=unloaded)
        except ValueError as err:
            raise CommandError(str(err)) from None
        ds.attrs["history"] = " ".join(["lsbg", *sys.argv[1:]])
        if point["tca"]:
            # the aligned TCA at the tca section's resolution
            tca = _tca(argparse.Namespace(config=args.config, positions=None, marking_um=None),
                       pair, flanks)
            write_dataset(tca, point["tca"])
            _report_tca(tca, point["tca"])
        write_dataset(ds, point["out"])
        first, second = section["axes"]
        a = ds.attrs
        print(f"lsbg misalignment-map: {len(values)} x {len(values)} cells, pattern moves "
              f"{a[f'pattern_shift_lengthwise_per_0_1_{first}']:.3g} mm per 0.1 {first} and "
              f"{a[f'pattern_shift_lengthwise_per_0_1_{second}']:.3g} mm per 0.1 {second} "
              f"towards the heel -> {point['out']}")
    for name, case_params, case_flanks, path in cases:
        try:
            ds = misalignment_map(pairs[0], case_flanks.modification, section["axes"],
                                  (case_values, case_values), load,
                                  case_params.replace(compliance="uniform"),
                                  base=case_flanks.misalignment, positions=section["positions"],
                                  unloaded=unloaded)
        except ValueError as err:
            raise CommandError(f"case {name}: {err}") from None
        ds.attrs["history"] = " ".join(["lsbg", *sys.argv[1:]])
        ds.attrs["sensitivity_case"] = name
        write_dataset(ds, path)
        print(f"lsbg misalignment-map: case {name}, {len(case_values)} x {len(case_values)} "
              f"cells -> {path}")
    return 0
