"""Design points: ``lsbg geometry`` and ``lsbg points``."""

from __future__ import annotations

import math

from lsbg.cli.options import add_design_options, add_flank_options, check_output, design_from_args

__all__ = ["add_geometry_parser", "add_points_parser"]


# --------------------------------------------------------------- geometry
def add_geometry_parser(subparsers):
    """``lsbg geometry``: design.json, flanks, meshes, URDF and picture of one design."""
    parser = subparsers.add_parser(
        "geometry", help="write the geometry of one design point",
        description="Write design.json, flanks.nc, pinion/gear STL, the exact solids as "
                    "STEP (pinion.step, gear.step), pair.urdf and pair.png of one design "
                    "point into --out (replaced atomically).")
    add_design_options(parser)
    parser.add_argument("--out", required=True, metavar="DIR", help="output directory")
    parser.add_argument("--no-step", dest="step", action="store_false",
                        help="leave out the STEP solids (a few seconds per design point)")
    parser.add_argument("--config", metavar="FILE.yaml",
                        help="study configuration; its 'flank_modification' section relieves "
                             "the pinion's STEP solid (the other files keep the conjugate "
                             "flanks)")
    add_flank_options(parser)
    parser.set_defaults(handler=run_geometry)


def run_geometry(args):
    """Handler of ``lsbg geometry`` [exit code]."""
    from lsbg.solid.export import STAGES, write_geometry

    design = design_from_args(args)
    relief = _step_relief(args, design)
    check_output(args.out, "--out", directory=True)
    result = write_geometry(design, args.out, step=args.step, relief=relief)
    times = ", ".join(f"{stage} {result.timings[stage]:.2f}" for stage in (*STAGES, "step")
                      if stage in result.timings)
    print(f"lsbg geometry: {design.trace}, spiral angle {math.degrees(design.spiral_angle):g} deg "
          f"-> {result.directory} ({times}; total {result.timings['total']:.2f} s)")
    return 0




def _step_relief(args, design):
    """The pinion's flank modification as the STEP solid takes it, or None."""
    from lsbg.cli.options import flanks_from_args
    from lsbg.gear.geometry import GearPair
    from lsbg.tca.modification import pinion_relief

    modification = flanks_from_args(args).modification
    if modification.is_zero:
        return None
    pair = GearPair(design)
    return lambda rho, polar: pinion_relief(pair, modification, rho, polar)


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
    add_design_options(parser)
    parser.add_argument("--spiral-angles", type=float, nargs="+", metavar="DEG",
                        help="spiral angles of the design points [deg] (default: the design's)")
    parser.add_argument("--config", metavar="FILE.yaml",
                        help="study configuration; its 'simulation', 'contact', "
                             "'flank_modification' and 'misalignment' sections are used")
    parser.add_argument("--engine", choices=("pybullet", "scipy", "compiled"), default="compiled",
                        help="integrator of the runs (default: compiled)")
    parser.add_argument("--geometry-out", required=True, metavar="DIR",
                        help="geometry directory template (as 'lsbg geometry --out')")
    parser.add_argument("--mesh-out", metavar="MESH.nc",
                        help="loaded tooth contact analysis template (as 'lsbg ltca --out')")
    parser.add_argument("--phases", type=int, default=256, metavar="N",
                        help="mesh positions of the loaded TCA (default 256)")
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
    add_flank_options(parser)
    from lsbg.cli.tooth import add_tooth_options

    add_tooth_options(parser, compliance_file=False)
    parser.set_defaults(handler=run_points)


def run_points(args):
    """Handler of ``lsbg points`` [exit code]."""
    import sys

    from lsbg.cli.options import CommandError, flanks_from_args, read_study_sections
    from lsbg.contact import ContactParameters
    from lsbg.gear.design import GearPairDesign
    from lsbg.dynamics import SimulationError, SimulationSettings, simulate
    from lsbg.solid.export import write_geometry
    from lsbg.files import fill_template, number_label
    from lsbg.gear.geometry import GearPair
    from lsbg.contact.slices import SliceStiffness
    from lsbg.tca.loaded import ltca_for_geometry
    from lsbg.files import write_dataset
    from lsbg.tooth.analysis import fe_ltca_for_geometry
    from lsbg.tooth.config import compliance_for_design

    base = design_from_args(args)
    angles = args.spiral_angles or [math.degrees(base.spiral_angle)]
    # every design point checked (GearPair raises DesignError) before any file
    designs = [GearPairDesign.from_config({**base.to_config(), "spiral_angle_deg": angle})
               for angle in angles]
    for design in designs:
        GearPair(design)
    simulation, contact = read_study_sections(args.config, "simulation", "contact")
    flanks = flanks_from_args(args)
    runs = {}
    for text in args.run:
        model, sep, path = text.partition("=")
        if not sep or model not in ("point", "line") or not path:
            raise CommandError(f"--run {text!r}: must be MODEL=RUN.nc with MODEL point or line")
        runs[model] = path
    try:
        settings = SimulationSettings.from_config(simulation, engine=args.engine)
        params = {model: ContactParameters.from_config({**contact, "model": model})
                  for model in ("point", "line")}
        files = [{"geometry": fill_template(args.geometry_out, "--geometry-out", spiral=label),
                  "mesh": (fill_template(args.mesh_out, "--mesh-out", spiral=label)
                           if args.mesh_out else None),
                  "compliance": (fill_template(args.compliance_out, "--compliance-out",
                                               spiral=label) if args.compliance_out else None),
                  **{model: fill_template(path, "--run", spiral=label)
                     for model, path in runs.items()}}
                 for label in map(number_label, angles)]
    except ValueError as err:
        raise CommandError(str(err)) from None
    names = [name for point in files for name in point.values() if name]
    if len(angles) > 1 and len(set(names)) < len(names):
        raise CommandError("--geometry-out, --mesh-out, --run: several design points would "
                           "write the same file; put {spiral} in every template")
    own = params["line"].compliance == "fe"
    if own:
        # the tooth's compliance: every setting checked before the first file
        from lsbg.cli.tooth import tooth_from_args

        material, tooth_mesh, positions = tooth_from_args(args)
        if not (args.compliance_out and args.mesh_out):
            raise CommandError("contact.compliance = 'fe': lsbg points needs --compliance-out "
                               "and --mesh-out (the FE compliance and the loaded TCA whose "
                               "slice stiffness the line-model runs take)")
    options = {"geometry": "--geometry-out", "mesh": "--mesh-out", "point": "--run",
               "line": "--run", "compliance": "--compliance-out"}
    for point in files:
        for key, path in point.items():
            if path:
                check_output(path, options[key], directory=key == "geometry")
    command = " ".join(["lsbg", *sys.argv[1:]])
    for design, point in zip(designs, files):
        write_geometry(design, point["geometry"], step=args.step,
                       relief=_step_relief(args, design) if args.step else None)
        slices = None
        if point["mesh"]:
            try:
                if own:
                    compliance, _ = compliance_for_design(GearPair(design), material,
                                                          tooth_mesh, point["compliance"])
                    mesh = fe_ltca_for_geometry(point["geometry"], settings.load_torque,
                                                params["line"], compliance, phases=positions,
                                                flanks=flanks)
                    slices = SliceStiffness.from_dataset(mesh)
                else:
                    mesh = ltca_for_geometry(point["geometry"], settings.load_torque,
                                             params["line"], phases=args.phases, flanks=flanks)
            except ValueError as err:
                raise CommandError(str(err)) from None
            mesh.attrs["history"] += f"; {command}"
            write_dataset(mesh, point["mesh"])
        for model in runs:
            try:
                ds = simulate(point["geometry"], settings, params[model], command=command,
                              flanks=flanks, slice_stiffness=slices if model == "line" else None)
            except SimulationError as err:
                print(f"lsbg points: {design.trace}, {math.degrees(design.spiral_angle):g} deg, "
                      f"{model} model: simulation stopped: {err}", file=sys.stderr)
                return 3
            write_dataset(ds, point[model])
        print(f"lsbg points: {design.trace}, spiral angle "
              f"{math.degrees(design.spiral_angle):g} deg -> "
              f"{', '.join(name for name in point.values() if name)}")
    return 0
