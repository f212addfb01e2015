"""Contact state: ``lsbg tca`` and ``lsbg misalignment-map``."""

from __future__ import annotations

from lsbg.cli.options import (CommandError, add_case_options, add_config_options,
                              add_geometry_input, add_output, check_output, checked, command_line,
                              contact_of, flanks_of, load_torque_of)

__all__ = ["add_tca_parser", "add_misalignment_map_parser"]

#: The sections of the contact state's flanks and its unloaded TCA.
TCA_SECTIONS = ("flank_modification", "misalignment", "tca")


def _design_pair(geometry):
    from lsbg.gear.geometry import GearPair
    from lsbg.solid.directory import read_design

    return GearPair(read_design(geometry))


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
                    "CF-1.11), at tca.positions positions and tca.marking_compound_um. The flank "
                    "modification and the displacements come from the 'flank_modification' and "
                    "'misalignment' sections; without them the pair is the conjugate, aligned "
                    "one.")
    add_geometry_input(parser)
    add_config_options(parser, TCA_SECTIONS)
    add_output(parser, metavar="TCA.nc")
    parser.set_defaults(handler=run_tca)


def run_tca(args):
    """Handler of ``lsbg tca``: its summary line."""
    from lsbg.files import write_dataset

    flanks = flanks_of(args.settings)
    ds = _tca(args.settings, _design_pair(args.geometry), flanks)
    write_dataset(ds, args.out)
    return _tca_line(ds, args.out)


def _tca(settings, pair, flanks):
    """The unloaded TCA of the ``tca`` section."""
    from lsbg.tca.analysis import tooth_contact_analysis

    section = settings["tca"]
    ds = checked(lambda: tooth_contact_analysis(pair, flanks.modification, flanks.misalignment,
                                                section["positions"],
                                                float(section["marking_compound_um"]) * 1e-6))
    ds.attrs["history"] = command_line()
    return ds


def _tca_line(ds, path):
    a = ds.attrs
    return (f"{a['positions']} positions, transmission error "
            f"{a['transmission_error_peak_to_peak_urad']:.4g} urad "
            f"({a['transmission_error_peak_to_peak_arcsec']:.3g} arcsec) peak to peak, pattern "
            f"{a['pattern_toe_mm']:.4g}-{a['pattern_heel_mm']:.4g} mm from the apex, edge "
            f"contact at {100 * a['edge_contact_share']:.3g} % of positions -> {path}")


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
                    "Settings from the 'misalignment_map' section (axes, range, steps, "
                    "positions, load_torque_N_m; the cases' maps take sweep_steps); the grid is "
                    "added to the 'misalignment' section's displacements.")
    add_geometry_input(parser)
    add_config_options(parser, ("simulation", "contact", *TCA_SECTIONS, "misalignment_map"))
    add_output(parser, metavar="MAP.nc", required=True)
    parser.add_argument("--spiral-angles", type=float, nargs="+", metavar="DEG",
                        help="several design points in one process: --geometry, --out and "
                             "--tca-out are then templates with the field {spiral} (the angle "
                             "as in the workflow's file names, e.g. 37.5)")
    parser.add_argument("--tca-out", metavar="TCA.nc",
                        help="also write the unloaded TCA of the undisplaced cell at the "
                             "'tca' section's resolution (as 'lsbg tca --out'), in the same "
                             "process")
    add_case_options(parser, "contact_state")
    parser.set_defaults(handler=run_misalignment_map)


def run_misalignment_map(args):
    """Handler of ``lsbg misalignment-map``: a line per map."""
    from lsbg.cli.cases import sensitivity_cases
    from lsbg.files import fill_template, number_label, write_dataset
    from lsbg.tca.vh_map import axis_values, misalignment_map

    section = args.settings["misalignment_map"]
    load = section["load_torque_N_m"]
    load = load_torque_of(args.settings) if load is None else load
    values = checked(lambda: axis_values(section["range"], section["steps"]))
    # one design point, or several (file names are templates with {spiral})
    angles = [None] if args.spiral_angles is None else list(args.spiral_angles)
    points = checked(lambda: [
        {key: (fill_template(path, option, spiral=number_label(angle))
               if angle is not None and path else path)
         for key, path, option in (("geometry", args.geometry, "--geometry"),
                                   ("out", args.out, "--out"), ("tca", args.tca_out, "--tca-out"))}
        for angle in angles])
    names = [path for point in points for key, path in point.items() if key != "geometry" and path]
    if len(set(names)) < len(names):
        raise CommandError("--out, --tca-out: several design points would write the same file; "
                           "put {spiral} in every template")
    # The map's loaded TCAs stay on the uniform bed: the tooth's slice stiffness is
    # the secant of one assembly (docs/model.md, "The tooth itself").
    params = contact_of(args.settings, model="line", compliance="uniform")
    flanks = flanks_of(args.settings)
    cases = sensitivity_cases(args, "contact_state", args.case_out)
    if cases and len(points) > 1:
        raise CommandError("--case: one design point only (not with --spiral-angles)")
    try:
        case_values = axis_values(section["range"], section["sweep_steps"])
    except ValueError as err:  # (the cases' maps take sweep_steps: name it)
        raise CommandError(str(err).replace("misalignment_map.steps",
                                            "misalignment_map.sweep_steps")) from None
    pairs = [_design_pair(point["geometry"]) for point in points]
    for point in points:
        check_output(point["out"], "--out")
        if point["tca"]:
            check_output(point["tca"], "--tca-out")
    lines = []
    # the unloaded TCAs of the design point's map, reused by its cases' maps where their
    # flanks and cells are the same (the line-stiffness cases, the cells of a coarser map)
    unloaded = {}
    for pair, point in zip(pairs, points):
        unloaded.clear()
        ds = checked(lambda: misalignment_map(
            pair, flanks.modification, section["axes"], (values, values), load, params,
            base=flanks.misalignment, positions=section["positions"], unloaded=unloaded))
        ds.attrs["history"] = command_line()
        if point["tca"]:
            # the aligned TCA at the tca section's resolution
            tca = _tca(args.settings, pair, flanks)
            write_dataset(tca, point["tca"])
            lines.append(f"tca: {_tca_line(tca, point['tca'])}")
        write_dataset(ds, point["out"])
        first, second = section["axes"]
        a = ds.attrs
        lines.append(f"{len(values)} x {len(values)} cells, pattern moves "
                     f"{a[f'pattern_shift_lengthwise_per_0_1_{first}']:.3g} mm per 0.1 {first} "
                     f"and {a[f'pattern_shift_lengthwise_per_0_1_{second}']:.3g} mm per 0.1 "
                     f"{second} towards the heel -> {point['out']}")
    for name, case_params, case_flanks, path in cases:
        try:
            ds = misalignment_map(pairs[0], case_flanks.modification, section["axes"],
                                  (case_values, case_values), load,
                                  case_params.replace(compliance="uniform"),
                                  base=case_flanks.misalignment, positions=section["positions"],
                                  unloaded=unloaded)
        except ValueError as err:
            raise CommandError(f"case {name}: {err}") from None
        ds.attrs["history"] = command_line()
        ds.attrs["sensitivity_case"] = name
        write_dataset(ds, path)
        lines.append(f"case {name}, {len(case_values)} x {len(case_values)} cells -> {path}")
    return lines
