"""Design points: ``lsbg geometry`` and ``lsbg points``."""

from __future__ import annotations

import math

from lsbg.cli.options import (CommandError, add_config_options, add_engine_option, add_output,
                              check_output, checked, command_line, contact_of, design_of,
                              flanks_of, parse_pairs, simulation_of)

__all__ = ["add_geometry_parser", "add_points_parser"]

#: The sections ``lsbg geometry`` reads: the design, and the pinion's relief of its STEP solid.
GEOMETRY_SECTIONS = ("design", "flank_modification")


# --------------------------------------------------------------- geometry
def add_geometry_parser(subparsers):
    """``lsbg geometry``: design.json, flanks, meshes, URDF and picture of one design."""
    parser = subparsers.add_parser(
        "geometry", help="write the geometry of one design point",
        description="Write design.json, flanks.nc, pinion/gear STL, the exact solids as "
                    "STEP (pinion.step, gear.step), pair.urdf and pair.png of the design point "
                    "of the 'design' section into --out (replaced atomically), e.g. --set "
                    "design.trace=circular --set design.spiral_angle_deg=30. The "
                    "'flank_modification' section relieves the pinion's STEP solid (the other "
                    "files keep the conjugate flanks).")
    add_config_options(parser, GEOMETRY_SECTIONS)
    add_output(parser, metavar="DIR", help="output directory", directory=True)
    parser.add_argument("--no-step", dest="step", action="store_false",
                        help="leave out the STEP solids (a few seconds per design point)")
    parser.add_argument("--relieved", action="store_true",
                        help="relieve the pinion's STEP solid by the flank_modification section "
                             "(default: the conjugate flanks)")
    parser.set_defaults(handler=run_geometry)


def run_geometry(args):
    """Handler of ``lsbg geometry``: its summary line."""
    from lsbg.solid.export import STAGES, write_geometry

    design = design_of(args.settings)
    relief = _step_relief(args.settings, design) if args.relieved else None
    result = write_geometry(design, args.out, step=args.step, relief=relief)
    times = ", ".join(f"{stage} {result.timings[stage]:.2f}" for stage in (*STAGES, "step")
                      if stage in result.timings)
    return (f"{design.trace}, spiral angle {math.degrees(design.spiral_angle):g} deg "
            f"-> {result.directory} ({times}; total {result.timings['total']:.2f} s)")


def _step_relief(settings, design):
    """The pinion's flank modification as the STEP solid takes it, or None."""
    from lsbg.gear.geometry import GearPair
    from lsbg.tca.modification import pinion_relief

    modification = flanks_of(settings).modification
    if modification.is_zero:
        return None
    pair = GearPair(design)
    return lambda rho, polar: pinion_relief(pair, modification, rho, polar)


# ------------------------------------------------------------------ points
def add_points_parser(subparsers):
    """``lsbg points``: geometry, loaded TCA and runs of design points of one trace."""
    parser = subparsers.add_parser(
        "points", help="geometry, loaded TCA and simulations of design points of one trace",
        description="What 'lsbg geometry', 'lsbg ltca' and 'lsbg simulate' do, for each spiral "
                    "angle of --spiral-angles, in one process (one start-up: about 1.8 s of "
                    "imports and compiled-kernel loading saved per point). File names are "
                    "templates with the field {spiral} (the angle as in the workflow's file "
                    "names, e.g. 37.5). Every design and setting is checked before any file is "
                    "written; each file is written atomically.")
    add_config_options(parser, ("design", "simulation", "driveline", "contact",
                                "flank_modification", "misalignment", "tca", "tooth"))
    parser.add_argument("--spiral-angles", type=float, nargs="+", metavar="DEG",
                        help="spiral angles of the design points [deg] (default: "
                             "design.spiral_angle_deg)")
    add_engine_option(parser, default="compiled")
    parser.add_argument("--geometry-out", required=True, metavar="DIR",
                        help="geometry directory template (as 'lsbg geometry --out')")
    parser.add_argument("--mesh-out", metavar="MESH.nc",
                        help="loaded tooth contact analysis template (as 'lsbg ltca --out')")
    parser.add_argument("--run", action="append", default=[], metavar="MODEL=RUN.nc",
                        help="a run of contact model MODEL (point or line) to write, a "
                             "template; repeatable")
    parser.add_argument("--step", action="store_true",
                        help="also write the exact solids as STEP into each geometry directory "
                             "(as 'lsbg geometry' does; a few seconds per design point)")
    parser.add_argument("--compliance-out", metavar="COMPLIANCE.nc",
                        help="under contact.compliance: fe, the FE compliance template (as "
                             "'lsbg compliance --out'; kept where it holds the same inputs): "
                             "the loaded TCA and the line-model runs then use the tooth's own "
                             "compliance")
    parser.set_defaults(handler=run_points)


def _point_files(args, angles, runs):
    """Each design point's output files ``{kind: path}``, checked before any work."""
    from lsbg.files import fill_template, number_label

    options = {"geometry": "--geometry-out", "mesh": "--mesh-out", "point": "--run",
               "line": "--run", "compliance": "--compliance-out"}
    templates = {"geometry": args.geometry_out, "mesh": args.mesh_out,
                 "compliance": args.compliance_out, **runs}
    try:
        files = [{kind: fill_template(path, options[kind], spiral=number_label(angle))
                  for kind, path in templates.items() if path} for angle in angles]
    except ValueError as err:
        raise CommandError(str(err)) from None
    names = [name for point in files for name in point.values()]
    if len(angles) > 1 and len(set(names)) < len(names):
        raise CommandError("--geometry-out, --mesh-out, --run: several design points would "
                           "write the same file; put {spiral} in every template")
    for point in files:
        for kind, path in point.items():
            check_output(path, options[kind], directory=kind == "geometry")
    return files


def run_points(args):
    """Handler of ``lsbg points``: a summary line per design point."""
    from lsbg.contact.slices import SliceStiffness
    from lsbg.dynamics import SimulationError, simulate
    from lsbg.files import write_dataset
    from lsbg.gear.design import GearPairDesign
    from lsbg.gear.geometry import GearPair
    from lsbg.solid.export import write_geometry
    from lsbg.tca.loaded import ltca_for_geometry
    from lsbg.tooth.analysis import fe_ltca_for_geometry
    from lsbg.tooth.config import compliance_for_design, tooth_from_config

    settings = args.settings
    base = design_of(settings)
    angles = args.spiral_angles or [math.degrees(base.spiral_angle)]
    # every design point checked (GearPair raises DesignError) before any file
    designs = [GearPairDesign.from_config({**base.to_config(), "spiral_angle_deg": angle})
               for angle in angles]
    for design in designs:
        GearPair(design)
    runs = parse_pairs(args.run, "--run", keys=("point", "line"))
    simulation = simulation_of(settings, args.engine)
    params = {model: contact_of(settings, model=model) for model in ("point", "line")}
    flanks = flanks_of(settings)
    own = params["line"].compliance == "fe"
    if own:
        # the tooth's compliance: every setting checked before the first file
        material, tooth_mesh, positions = checked(lambda: tooth_from_config(settings["tooth"]))
        if not (args.compliance_out and args.mesh_out):
            raise CommandError("contact.compliance = 'fe': lsbg points needs --compliance-out "
                               "and --mesh-out (the FE compliance and the loaded TCA whose "
                               "slice stiffness the line-model runs take)")
    files = _point_files(args, angles, runs)
    command = command_line()
    lines = []
    for design, point in zip(designs, files):
        write_geometry(design, point["geometry"], step=args.step,
                       relief=_step_relief(settings, design) if args.step else None)
        slices = None
        if "mesh" in point:
            try:
                if own:
                    compliance, _ = compliance_for_design(GearPair(design), material,
                                                          tooth_mesh, point["compliance"])
                    mesh = fe_ltca_for_geometry(point["geometry"], simulation.load_torque,
                                                params["line"], compliance, phases=positions,
                                                flanks=flanks)
                    slices = SliceStiffness.from_dataset(mesh)
                else:
                    mesh = ltca_for_geometry(point["geometry"], simulation.load_torque,
                                             params["line"],
                                             phases=settings["tca"]["loaded_positions"],
                                             flanks=flanks)
            except ValueError as err:
                raise CommandError(str(err)) from None
            mesh.attrs["history"] += f"; {command}"
            write_dataset(mesh, point["mesh"])
        for model in runs:
            try:
                ds = simulate(point["geometry"], simulation, params[model], command=command,
                              flanks=flanks, slice_stiffness=slices if model == "line" else None,
                              driveline=settings.get("driveline"))
            except SimulationError as err:
                raise SimulationError(f"{design.trace}, {math.degrees(design.spiral_angle):g} "
                                      f"deg, {model} model: {err}") from None
            write_dataset(ds, point[model])
        lines.append(f"{design.trace}, spiral angle {math.degrees(design.spiral_angle):g} deg "
                     f"-> {', '.join(point.values())}")
    return lines

