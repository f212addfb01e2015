"""The tooth's own compliance on the command line: ``lsbg compliance``.

A loaded TCA under ``contact.compliance: fe`` reads (or writes) the same file
through ``lsbg ltca --compliance-file``; a run reads the slice stiffness of an
FE loaded TCA (``--fe-ltca``, :mod:`lsbg.cli.options`), not the FE stage.
"""

from __future__ import annotations

from lsbg.cli.options import add_config_options, add_geometry_input, add_output, checked

__all__ = ["add_compliance_parser"]


def add_compliance_parser(subparsers):
    """``lsbg compliance``: the FE compliance of one design point."""
    parser = subparsers.add_parser(
        "compliance", help="finite-element compliance of the teeth of one design point",
        description="Mesh a seven-tooth segment of each member of the pair in --geometry "
                    "(gmsh, root fillets), solve linear elasticity with quadratic tetrahedra "
                    "(scikit-fem) for unit normal loads over the field of contact, and write the "
                    "influence coefficients and the fillet stresses to --out (NetCDF) with the "
                    "hash of their inputs. An --out that already holds these inputs is kept. "
                    "Material and mesh come from the 'tooth' section.")
    add_geometry_input(parser)
    add_config_options(parser, ("tooth",))
    add_output(parser, metavar="COMPLIANCE.nc")
    parser.set_defaults(handler=run_compliance)


def run_compliance(args):
    """Handler of ``lsbg compliance``: its summary line."""
    from lsbg.gear.geometry import GearPair
    from lsbg.solid.directory import read_design
    from lsbg.tooth.config import compliance_for_design, tooth_from_config

    material, settings, _ = checked(lambda: tooth_from_config(args.settings["tooth"]))
    pair = GearPair(read_design(args.geometry))
    ds, reused = compliance_for_design(pair, material, settings, args.out)
    what = "kept (same inputs)" if reused else "computed"
    dofs = ds.attrs.get("fe_dofs_pinion", 0) + ds.attrs.get("fe_dofs_gear", 0)
    return (f"{what}, {dofs} degrees of freedom, inputs hash {ds.attrs['inputs_hash']} "
            f"-> {args.out}")
