"""``lsbg rate``: a design point's ISO 10300 rating beside its FE stresses."""

from __future__ import annotations

import math
import sys

from lsbg.cli.options import CommandError, _assignments, check_output, read_study_sections

__all__ = ["add_rate_parser"]


def add_rate_parser(subparsers):
    """``lsbg rate``: ISO 10300 method B1 of one design point."""
    parser = subparsers.add_parser(
        "rate", help="ISO 10300 rating of one design point (stresses, safety, rated torque)",
        description="Rate the pair in --geometry by ISO 10300:2023 method B1 (contact and "
                    "root stress of both members, permissible stresses, safety factors, the "
                    "gear torques at which they reach 1) at the study's load and speed "
                    "(simulation section of --config) with the factors of its 'rating' "
                    "section, and write them to --out (NetCDF) beside the largest contact "
                    "pressure and root stresses of --fe-ltca (the FE loaded TCA).")
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory written by 'lsbg geometry'")
    parser.add_argument("--config", metavar="FILE.yaml",
                        help="study configuration: its rating, tooth, simulation and "
                             "statistics sections are used")
    parser.add_argument("--set-rating", action="append", default=[], metavar="KEY=VALUE",
                        help="override a key of the rating section, e.g. "
                             "application_factor=1.25; repeatable")
    parser.add_argument("--run", metavar="RUN.nc",
                        help="the design point's line-model run: its dynamic factor is K_v "
                             "where rating.dynamic_factor is 'lsbg' (without it, K_v = 1)")
    parser.add_argument("--fe-ltca", metavar="LTCA.nc",
                        help="the design point's loaded TCA with the FE compliance (lsbg ltca "
                             "--compliance fe) at the same load")
    parser.add_argument("--compliance-file", metavar="COMPLIANCE.nc",
                        help="the design point's FE compliance (lsbg compliance): with it, the "
                             "FE loaded TCA is also solved at each corner of the assembly's "
                             "displacement envelope (misalignment_map.axes at "
                             "+-misalignment_map.range of --config, on top of its misalignment "
                             "section) and the largest stresses there written beside")
    parser.add_argument("--out", required=True, metavar="RATING.nc", help="output NetCDF file")
    parser.set_defaults(handler=run_rate)


def run_rate(args):
    """Handler of ``lsbg rate`` [exit code]."""
    from lsbg.files import read_design
    from lsbg.rating.config import rating_from_config
    from lsbg.rating.dataset import rating_dataset
    from lsbg.rating.iso10300 import rate
    from lsbg.rating.virtual import rating_geometry
    from lsbg.results import open_dataset, open_run, write_dataset
    from lsbg.summary import run_dynamic_factor, statistics_options

    rating, tooth, simulation, statistics = read_study_sections(
        args.config, "rating", "tooth", "simulation", "statistics")
    rating = {**rating, **_assignments(args.set_rating, "--set-rating")}
    check_output(args.out, "--out")
    design = read_design(args.geometry)
    kv, source = None, "K_v = 1: no run given"
    if rating.get("dynamic_factor", "lsbg") == "lsbg":
        if args.run:
            run = open_run(args.run)
            if design.attrs_difference(run.attrs) is not None:
                key, stored, value = design.attrs_difference(run.attrs)
                raise CommandError(f"--run {args.run}: design {key} = {stored!r}, the "
                                   f"geometry's {value!r}")
            try:
                after = statistics_options(statistics).get("steady_state_after", 0.2)
            except ValueError as err:
                raise CommandError(str(err)) from None
            kv, source = run_dynamic_factor(run, after), f"the run {args.run}"
    else:
        source = "rating.dynamic_factor"
    try:
        material, conditions = rating_from_config(rating, tooth, kv)
    except ValueError as err:
        raise CommandError(str(err)) from None
    load = float(simulation.get("load_torque_N_m", 1964.99))
    speed = math.radians(float(simulation.get("pinion_speed_deg_s", 7703)))
    geometry = rating_geometry(design, effective_face_width=conditions.effective_face_width,
                               **({"tool_edge_radius": tooth["fillet_radius_module"]}
                                  if tooth.get("fillet_radius_module") else {}))
    try:
        result = rate(geometry, load * design.pinion_teeth / design.gear_teeth, speed, material,
                      conditions)
    except ValueError as err:
        raise CommandError(f"{args.geometry}: {err}") from None
    fe = None
    if args.fe_ltca:
        fe = open_dataset(args.fe_ltca, "FE loaded TCA", ("max_contact_pressure",
                                                          "root_stress_pinion",
                                                          "root_stress_gear"),
                          ("load_torque_N_m",), "--fe-ltca")
        if not math.isclose(float(fe.attrs["load_torque_N_m"]), load, rel_tol=1e-9):
            raise CommandError(f"--fe-ltca {args.fe_ltca}: computed at "
                               f"{fe.attrs['load_torque_N_m']!r} N m, the rating's load is "
                               f"{load!r} N m")
        if design.attrs_difference(fe.attrs) is not None:
            key, stored, value = design.attrs_difference(fe.attrs)
            raise CommandError(f"--fe-ltca {args.fe_ltca}: design {key} = {stored!r}, the "
                               f"geometry's {value!r}")
    displaced = _envelope_ltcas(args, design, load) if args.compliance_file else None
    ds = rating_dataset(result, design, material, conditions, source, fe, displaced)
    write_dataset(ds, args.out)
    ratio = design.gear_teeth / design.pinion_teeth
    print(f"lsbg rate: sigma_H {result.contact_stress / 1e6:.0f} MPa (S_H "
          f"{min(result.contact_safety):.2f}), sigma_F {result.root_stress[0] / 1e6:.0f} / "
          f"{result.root_stress[1] / 1e6:.0f} MPa (S_F {result.bending_safety[0]:.2f} / "
          f"{result.bending_safety[1]:.2f}); rated gear torque "
          f"{result.rated_pinion_torque_contact * ratio:.0f} N m (pitting), "
          f"{result.rated_pinion_torque_bending * ratio:.0f} N m (root) against {load:g} N m "
          f"-> {args.out}", file=sys.stdout)
    return 0


def _envelope_ltcas(args, design, load):
    """{corner: (displacements, FE loaded TCA)} at the corners of the V-H envelope."""
    from lsbg.cli.options import contact_from_args
    from lsbg.geometry import GearPair
    from lsbg.rating.dataset import envelope_corners
    from lsbg.tca.misalignment import DISPLACEMENTS
    from lsbg.tca.separation import RealFlanks
    from lsbg.tooth.analysis import fe_ltca_for_geometry
    from lsbg.tooth.config import compliance_for_design, tooth_from_config

    contact, tooth, modification, misalignment, vh = read_study_sections(
        args.config, "contact", "tooth", "flank_modification", "misalignment",
        "misalignment_map")
    try:
        material, settings, positions = tooth_from_config(tooth)
    except ValueError as err:
        raise CommandError(str(err)) from None
    axes = vh.get("axes") or ["E", "P"]
    half_range = float(vh.get("range") or 0.1)
    pair = GearPair(design)
    compliance, _ = compliance_for_design(pair, material, settings, args.compliance_file)
    args.contact_model, args.compliance = "line", "fe"
    params = contact_from_args(args)
    out = {}
    for label, values in envelope_corners(axes, half_range).items():
        corner = dict(misalignment)
        for letter, value in values.items():
            key = DISPLACEMENTS[letter][1]
            corner[key] = float(corner.get(key) or 0.0) + value
        try:
            flanks = RealFlanks.from_config(modification, corner)
            ltca = fe_ltca_for_geometry(args.geometry, load, params, compliance,
                                        phases=positions, flanks=flanks)
        except ValueError as err:
            raise CommandError(f"the displaced assembly {label}: {err}") from None
        out[label] = (values, ltca)
    return out
