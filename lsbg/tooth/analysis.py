"""The loaded TCA of a design point with the tooth's own compliance, as the workflow writes it.

:func:`fe_ltca_for_geometry` runs the complementarity LTCA with the FE
compliance (:func:`lsbg.tooth.ltca.fe_loaded_tca`), turns its equilibria into
the line model's slice stiffness (:mod:`lsbg.tooth.slices`), and runs the
line model's own LTCA (:func:`lsbg.ltca.loaded_tca`) on that stiffness. The
file it returns has every variable of today's loaded TCA, so the sweep
dataset, the summary and the reports read it as they read the uniform bed's,
with the complementarity solution's transmission error and mesh stiffness in
their place, and beside them the contact pressure, the root stresses and the
slice-stiffness table that the dynamic runs under ``compliance: fe`` take
(:class:`lsbg.contact.slices.SliceStiffness`).

The line model on the slice stiffness must reproduce the complementarity
solution's transmission error (the table is its secant stiffness): the
largest difference is kept as an attribute and checked by the tests.
"""

from __future__ import annotations

import numpy as np

__all__ = ["fe_ltca_for_geometry", "fe_ltca"]

#: Variables of the complementarity LTCA that replace or join the line model's.
_FE_VARIABLES = ("transmission_error", "mesh_stiffness", "max_contact_pressure",
                 "root_stress_pinion", "root_stress_gear", "contact_pressure", "slice_stiffness")


def fe_ltca(contact, compliance, load_torque, phases):
    """The LTCA with the FE compliance and the line model on its slice stiffness, merged.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        Line model of the pair (bands, separation of real flanks; its own
        compliance setting is not read).
    compliance : xarray.Dataset
        :func:`lsbg.tooth.compliance.tooth_compliance` of the same design.
    load_torque : float
        Gear torque [N m], > 0.
    phases : int
        Mesh positions over one base pitch [-].

    Returns
    -------
    xarray.Dataset
        :func:`lsbg.ltca.loaded_tca`'s variables and attributes (contact
        length, pattern, tooth-pair loads from the line model on the slice
        stiffness), with ``transmission_error`` and ``mesh_stiffness`` and the
        summary attributes of the complementarity solution;
        ``transmission_error_slices`` [urad] (the line model's), and the FE
        outputs ``max_contact_pressure``, ``root_stress_pinion``,
        ``root_stress_gear`` [MPa], ``contact_pressure`` (cone_distance,
        pressure_profile_angle) [MPa] and ``slice_stiffness`` (line_turn,
        cone_distance) [N/(mm um)].
    """
    from lsbg.contact import MeshContact
    from lsbg.contact.slices import SliceStiffness
    from lsbg.ltca import loaded_tca
    from lsbg.tooth.ltca import fe_loaded_tca

    fe = fe_loaded_tca(contact, compliance, load_torque, phases)
    table = SliceStiffness.from_dataset(fe)
    params = contact.params.replace(model="line", compliance="fe")
    on_slices = MeshContact(contact.pair, params, separation=contact.separation,
                            slice_stiffness=table)
    ds = loaded_tca(on_slices, load_torque, phases)
    ds = ds.rename({"transmission_error": "transmission_error_slices"})
    ds["transmission_error_slices"].attrs["long_name"] = (
        "loaded static transmission error of the line model on the slice stiffness")
    fe = fe.rename({"profile_angle": "pressure_profile_angle"})
    for name in _FE_VARIABLES:
        ds[name] = fe[name]
    difference = np.abs(ds["transmission_error_slices"].values - fe["transmission_error"].values)
    summary = {key: value for key, value in fe.attrs.items()
               if key.startswith(("transmission_error_", "mesh_stiffness_", "max_"))
               or key in ("compliance_inputs_hash",)}
    ds.attrs.update(summary)
    # the FE model behind the numbers (mesh, material) travels with them
    ds.attrs.update({key: value for key, value in compliance.attrs.items()
                     if key.startswith(("fe_", "material_"))})
    ds.attrs.update(
        compliance="fe",
        source=ds.attrs["source"] + "; lsbg.tooth.analysis.fe_ltca (FE compliance + Hertz, "
                                    "complementarity per position)",
        slice_table_transmission_error_difference_urad=float(difference.max()))
    return ds


def fe_ltca_for_geometry(geometry_dir, load_torque, contact_params, compliance, phases=200,
                         flanks=None):
    """:func:`fe_ltca` of a geometry directory (``lsbg geometry``).

    Parameters
    ----------
    geometry_dir : str or pathlib.Path
    load_torque : float
        Torque on the gear [N m], > 0.
    contact_params : lsbg.contact.ContactParameters
        Its line-model fields are used.
    compliance : xarray.Dataset
        The design point's FE compliance
        (:func:`lsbg.tooth.config.compliance_for_design`).
    phases : int
        Mesh positions over one base pitch [-].
    flanks : lsbg.tca.separation.RealFlanks, optional
        Flank modification and assembly displacements.

    Returns
    -------
    xarray.Dataset
    """
    from lsbg.contact import MeshContact
    from lsbg.files import read_design
    from lsbg.geometry import GearPair

    pair = GearPair(read_design(geometry_dir))
    separation = flanks.separation(pair) if flanks is not None else None
    params = contact_params.replace(model="line")
    return fe_ltca(MeshContact(pair, params, separation=separation), compliance, load_torque,
                   phases)
