"""The tooth's own compliance on the command line: ``lsbg compliance`` and the options
that bring it to ``lsbg ltca`` and ``points`` (``--set-tooth``, ``--compliance-file``).

The runs' option ``--fe-ltca`` (the slice stiffness of an FE loaded TCA) is in
:mod:`lsbg.cli.options`: a run reads a file, not the FE stage.
"""

from __future__ import annotations

import sys

from lsbg.cli.options import CommandError, _assignments, check_output, read_study_sections

__all__ = ["add_compliance_parser", "add_tooth_options", "tooth_from_args",
           "compliance_from_args"]


def add_tooth_options(parser, compliance_file=True):
    """Add ``--set-tooth`` (over the ``tooth`` section of ``--config``) and, with
    ``compliance_file``, ``--compliance-file``."""
    parser.add_argument("--set-tooth", action="append", default=[], metavar="KEY=VALUE",
                        help="override a key of the tooth section (E in GPa, sizes in mean "
                             "normal modules), e.g. element_size_module=0.45; repeatable")
    if compliance_file:
        parser.add_argument("--compliance-file", metavar="COMPLIANCE.nc",
                            help="the design point's FE compliance (lsbg compliance): read if "
                                 "it holds these inputs, else computed and written there; "
                                 "needed under contact.compliance: fe")


def tooth_from_args(args):
    """(material, mesh settings, LTCA positions) of ``--config``'s ``tooth`` section and
    ``--set-tooth``."""
    from lsbg.tooth.config import tooth_from_config

    (tooth,) = read_study_sections(getattr(args, "config", None), "tooth")
    tooth = {**tooth, **_assignments(getattr(args, "set_tooth", []), "--set-tooth")}
    try:
        return tooth_from_config(tooth)
    except ValueError as err:
        raise CommandError(str(err)) from None


def compliance_from_args(args, pair, path):
    """The FE compliance of ``pair`` at ``path`` (reused or computed) and the LTCA positions."""
    from lsbg.tooth.config import compliance_for_design

    material, settings, positions = tooth_from_args(args)
    if not path:
        raise CommandError("contact.compliance = 'fe' needs --compliance-file (where the "
                           "design point's FE compliance is, or goes)")
    compliance, _ = compliance_for_design(pair, material, settings, path)
    return compliance, positions


# ---------------------------------------------------------------- compliance
def add_compliance_parser(subparsers):
    """``lsbg compliance``: the FE compliance of one design point."""
    parser = subparsers.add_parser(
        "compliance", help="finite-element compliance of the teeth of one design point",
        description="Mesh a seven-tooth segment of each member of the pair in --geometry "
                    "(gmsh, root fillets), solve linear elasticity with quadratic tetrahedra "
                    "(scikit-fem) for unit normal loads over the field of contact, and write the "
                    "influence coefficients and the fillet stresses to --out (NetCDF) with the "
                    "hash of their inputs. An --out that already holds these inputs is kept. "
                    "Material and mesh come from the 'tooth' section of --config.")
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory written by 'lsbg geometry'")
    parser.add_argument("--config", metavar="FILE.yaml",
                        help="study configuration; its 'tooth' section is used")
    add_tooth_options(parser, compliance_file=False)
    parser.add_argument("--out", required=True, metavar="COMPLIANCE.nc",
                        help="output NetCDF file")
    parser.set_defaults(handler=run_compliance)


def run_compliance(args):
    """Handler of ``lsbg compliance`` [exit code]."""
    from lsbg.solid.directory import read_design
    from lsbg.gear.geometry import GearPair
    from lsbg.tooth.config import compliance_for_design

    material, settings, _ = tooth_from_args(args)
    check_output(args.out, "--out")
    pair = GearPair(read_design(args.geometry))
    ds, reused = compliance_for_design(pair, material, settings, args.out)
    what = "kept (same inputs)" if reused else "computed"
    dofs = ds.attrs.get("fe_dofs_pinion", 0) + ds.attrs.get("fe_dofs_gear", 0)
    print(f"lsbg compliance: {what}, {dofs} degrees of freedom, inputs hash "
          f"{ds.attrs['inputs_hash']} -> {args.out}", file=sys.stdout)
    return 0
