"""The loaded TCA of a design point with the tooth's own compliance, as the workflow writes it.

:func:`fe_ltca_for_geometry` runs the complementarity LTCA with the FE
compliance (:func:`lsbg.tooth.ltca.fe_loaded_tca`), turns its equilibria into
the line model's slice stiffness (:mod:`lsbg.tooth.slices`), and runs the
line model's own LTCA (:func:`lsbg.tca.loaded.loaded_tca`) on that stiffness. The
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

from lsbg.files import short_labels

__all__ = ["fe_ltca_for_geometry", "fe_ltca", "envelope_positions", "fe_envelope"]

#: Variables of the complementarity LTCA that replace or join the line model's.
_FE_VARIABLES = ("transmission_error", "mesh_stiffness", "max_contact_pressure",
                 "root_stress_pinion", "root_stress_gear", "contact_pressure", "slice_stiffness",
                 "max_flank_pressure", "edge_load_share", "edge_line_load",
                 "relief_start_load_share", "relief_start_line_load")


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
        :func:`lsbg.tca.loaded.loaded_tca`'s variables and attributes (contact
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
    from lsbg.tca.loaded import loaded_tca
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
               or key in ("compliance_inputs_hash", "tip_relief")}
    ds.attrs.update(summary)
    # the FE model behind the numbers (mesh, material) travels with them
    ds.attrs.update({key: value for key, value in compliance.attrs.items()
                     if key.startswith(("fe_", "material_"))})
    ds.attrs.update(
        compliance="fe",
        source=ds.attrs["source"] + "; lsbg.tooth.analysis.fe_ltca (FE compliance + Hertz, "
                                    "complementarity per position)",
        slice_table_transmission_error_difference_urad=float(difference.max()))
    return short_labels(ds)


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
    from lsbg.solid.directory import read_design
    from lsbg.gear.geometry import GearPair

    pair = GearPair(read_design(geometry_dir))
    separation = flanks.separation(pair) if flanks is not None else None
    params = contact_params.replace(model="line")
    return fe_ltca(MeshContact(pair, params, separation=separation), compliance, load_torque,
                   phases)


def envelope_positions(positions):
    """Mesh positions of each corner's FE loaded TCA: half the aligned one's, at least 8.

    Parameters
    ----------
    positions : int
        The aligned FE loaded TCA's (``tooth.ltca_positions``) [-].

    Returns
    -------
    int

    Notes
    -----
    Measured on the paper's pair (35 deg, both members, four corners): 100
    positions put the largest contact pressure and root stresses within 0.5 %
    (their medians over the cycle within 0.3 %) of 200 positions', in about
    60 % of the time.
    """
    return max(8, int(positions) // 2)


def fe_envelope(pair, contact_params, compliance, load_torque, phases, modification, misalignment,
                axes, half_range):
    """The FE loaded TCA's stresses at the corners of the assembly's displacement envelope.

    At each corner (every sign of each displacement of ``axes`` at
    ``half_range``, :func:`lsbg.tca.misalignment.envelope_corners`, added to
    ``misalignment``) the complementarity LTCA on the FE compliance
    (:func:`lsbg.tooth.ltca.fe_loaded_tca`) gives the largest Hertz pressure
    and the root stresses at each mesh position; the line model's LTCA on
    the slice table is not needed here.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    contact_params : lsbg.contact.ContactParameters
        The line model's bands (its model and compliance are set here).
    compliance : xarray.Dataset
        The design point's FE compliance.
    load_torque : float
        Torque on the gear [N m].
    phases : int
        Mesh positions over one base pitch [-].
    modification, misalignment : dict
        The ``flank_modification`` and ``misalignment`` sections (config units).
    axes : sequence of str
        The displacements of the corners (``misalignment_map.axes``, letters
        of ``E``, ``P``, ``G``, ``Sigma``).
    half_range : float
        The corners' displacement either way (``misalignment_map.range``)
        [mm; deg for Sigma].

    Returns
    -------
    xarray.Dataset
        ``max_contact_pressure``, ``root_stress_pinion``, ``root_stress_gear``
        over (corner, mesh_phase) [MPa]; ``displacement`` (corner, axis).

    Raises
    ------
    ValueError
        A corner whose displacement loses contact or closes the backlash,
        naming it.
    """
    import xarray as xr

    from lsbg.contact import MeshContact
    from lsbg.tca.misalignment import DISPLACEMENTS, envelope_corners
    from lsbg.tca.separation import RealFlanks
    from lsbg.tooth.ltca import fe_loaded_tca

    params = contact_params.replace(model="line")
    corners = envelope_corners(list(axes), float(half_range))
    pressure, roots = [], {"pinion": [], "gear": []}
    for label, values in corners.items():
        corner = dict(misalignment or {})
        for letter, value in values.items():
            key = DISPLACEMENTS[letter][1]
            corner[key] = float(corner.get(key) or 0.0) + value
        try:
            separation = RealFlanks.from_config(modification, corner).separation(pair)
            out = fe_loaded_tca(MeshContact(pair, params, separation=separation), compliance,
                                load_torque, phases=phases)
        except ValueError as err:
            raise ValueError(f"the displaced assembly {label}: {err}") from None
        pressure.append(out["max_contact_pressure"].values)
        for member in roots:
            roots[member].append(out[f"root_stress_{member}"].values)
    phase = out["mesh_phase"]
    dims = ("corner", "mesh_phase")
    return xr.Dataset(
        {"max_contact_pressure": (dims, np.array(pressure), {
            "units": "MPa", "long_name": "largest Hertz pressure at each mesh position"}),
         **{f"root_stress_{m}": (dims, np.array(v), {
             "units": "MPa", "long_name": f"largest root stress of the {m} at each position"})
            for m, v in roots.items()},
         "displacement": (("corner", "axis"),
                          np.array([[values[a] for a in axes] for values in corners.values()]),
                          {"units": "mm" if "Sigma" not in axes else "mm (deg for Sigma)",
                           "long_name": "assembly displacement added at each corner"})},
        coords={"corner": list(corners), "axis": list(axes), "mesh_phase": phase.values},
        attrs={"title": "FE loaded TCA at the corners of the displacement envelope",
               "load_torque_N_m": float(load_torque), "phases": int(phases),
               "envelope_half_range": float(half_range),
               **{f"design_{k}": v for k, v in pair.design.to_config().items()}})

