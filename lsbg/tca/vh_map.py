"""V-H maps: how the contact moves when the assembly is displaced.

A gear lab's V-H check (Gleason's, after the vertical and horizontal
displacements of the pinion on the test machine) shifts the members and
watches the bearing pattern and the transmission error. :func:`misalignment_map`
does it on a grid of two of the displacements E, P, G, Sigma
(:mod:`lsbg.tca.misalignment`): at each cell the unloaded TCA from the
surfaces (:func:`lsbg.tca.analysis.tooth_contact_summary`) and the loaded TCA
of the line model on the same separation field (:func:`lsbg.tca.loaded.loaded_tca`).
The pattern's movement per 0.1 mm (or 0.1 degree) of each displacement is the
sensitivity a designer reads off it: the less the pattern and the
transmission error move, the more tolerant the pair is of its assembly.
"""

from __future__ import annotations

import math

import numpy as np

from lsbg.files import short_labels
from lsbg.contact import ContactParameters, MeshContact
from lsbg.tca.loaded import loaded_tca
from lsbg.tca.analysis import MARKING_COMPOUND, tooth_contact_summary
from lsbg.tca.misalignment import DISPLACEMENTS, Misalignment
from lsbg.tca.modification import FlankModification, flank_attributes
from lsbg.tca.separation import separation_field

#: Default axes of a map (Gleason's V and H: offset and pinion axial) and
#: their half-range in configuration units (mm, deg). G into mesh closes the
#: paper pair's 0.1 mm backlash at about -0.09 mm.
DEFAULT_AXES = ("E", "P")
DEFAULT_RANGE = 0.1
DEFAULT_STEPS = 9
#: Mesh positions of each cell's loaded TCA over one base pitch.
LOADED_PHASES = 64
#: Each cell's unloaded TCA: positions over a mesh cycle and the pinion grid.
#: The first contact is refined between grid points, so this coarser grid
#: gives the default's TE to about 1 % and the pattern's centre to 0.1 mm at
#: a fifth of its cost.
MAP_POSITIONS = 100
MAP_GRID = (61, 121)

#: Long names of the axes, for the datasets and the figures.
AXIS_NAMES = {"E": "offset E", "P": "pinion axial P", "G": "gear axial G",
              "Sigma": "shaft-angle error Σ"}

_VARIABLES = {
    "transmission_error_unloaded_pp": ("urad", "unloaded transmission error, peak to peak"),
    "transmission_error_loaded_pp": ("urad", "loaded transmission error, peak to peak"),
    "pattern_cone_distance": ("mm", "bearing pattern's centre: distance from the apex"),
    "pattern_height": ("mm", "bearing pattern's centre: height above the gear's root cone"),
    "pattern_shift_lengthwise": ("mm", "movement of the pattern's centre towards the heel"),
    "pattern_shift_profile": ("mm", "movement of the pattern's centre towards the gear's tip"),
    "pattern_length": ("mm", "bearing pattern's length along the face"),
    "edge_contact_share": ("1", "share of mesh positions whose contact ellipse reaches an edge"),
    "edge_load_share": ("1", "share of the load at the flank's edges (loaded TCA)"),
}


def axis_values(half_range, steps):
    """Evenly spaced displacements from -half_range to +half_range, 0 included.

    Parameters
    ----------
    half_range : float
        Largest displacement [config unit: mm or deg], > 0.
    steps : int
        Number of values, odd and at least 3 [-].
    """
    if isinstance(steps, bool) or int(steps) != steps or steps < 3 or steps % 2 == 0:
        raise ValueError(f"misalignment_map.steps = {steps!r}: must be an odd whole number >= 3")
    if not (math.isfinite(half_range) and half_range > 0):
        raise ValueError(f"misalignment_map.range = {half_range!r}: must be a number > 0")
    return np.linspace(-half_range, half_range, int(steps))


def misalignment_map(pair, modification=None, axes=DEFAULT_AXES, values=None, load_torque=0.0,
                     contact_params=None, base=None, positions=MAP_POSITIONS,
                     marking=MARKING_COMPOUND, phases=LOADED_PHASES, grid=MAP_GRID,
                     unloaded=None):
    """Unloaded and loaded TCA on a grid of two assembly displacements.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    modification : lsbg.tca.FlankModification, optional
    axes : (str, str)
        Two of "E", "P", "G", "Sigma" (default E and P).
    values : (array_like, array_like), optional
        Displacements along each axis in configuration units [mm, or deg for
        Sigma]; default +-0.1 in 9 steps each. Each must contain 0.
    load_torque : float
        Torque on the gear for the loaded TCA [N m].
    contact_params : lsbg.contact.ContactParameters, optional
        The line model's settings (stiffness, slices).
    base : Misalignment, optional
        Displacements the grid is added to (default: the aligned pair).
    positions : int
        Positions of each unloaded TCA over a mesh cycle [-].
    marking : float
        Marking-compound thickness [m].
    phases : int
        Positions of each loaded TCA over a base pitch [-].
    grid : (int, int)
        Pinion flank grid of each unloaded TCA [-].
    unloaded : dict, optional
        A cache of the unloaded TCAs of ``pair``, shared by maps of the same
        pair in one process: a map that differs only in the loaded TCA's
        settings (a line-stiffness sensitivity case) or whose cells are a
        subset of another's reuses their unloaded TCAs instead of recomputing
        them (each costs about 40 ms; the loaded TCA about 13 ms).

    Returns
    -------
    xarray.Dataset
        Variables (see ``_VARIABLES``) on the two axes' dimensions (named
        by their letters, coordinates in mm or degrees); attributes: the
        movement of the pattern and the change of TE per 0.1 mm (0.1 deg) of
        each axis through the aligned cell, the modification and the load.
    """
    import xarray as xr

    import lsbg

    axes = tuple(axes)
    if len(axes) != 2 or len(set(axes)) != 2 or not set(axes) <= set(DISPLACEMENTS):
        raise ValueError(f"misalignment_map.axes = {list(axes)!r}: two different of "
                         f"{sorted(DISPLACEMENTS)}")
    if values is None:
        values = (axis_values(DEFAULT_RANGE, DEFAULT_STEPS),) * 2
    values = [np.asarray(v, dtype=float) for v in values]
    for letter, v in zip(axes, values):
        if not np.any(v == 0.0):
            raise ValueError(f"misalignment_map: the values of {letter} must include 0")
    base = base or Misalignment()
    params = (contact_params or ContactParameters()).replace(model="line")
    shape = tuple(v.size for v in values)
    result = {name: np.full(shape, np.nan) for name in _VARIABLES}
    for i, a in enumerate(values[0]):
        for j, b in enumerate(values[1]):
            shifted = base.shifted(**{axes[0]: a * DISPLACEMENTS[axes[0]][2],
                                      axes[1]: b * DISPLACEMENTS[axes[1]][2]})
            key = (modification, shifted, positions, marking, tuple(grid))
            try:
                tca = unloaded.get(key) if unloaded is not None else None
                if tca is None:
                    tca = tooth_contact_summary(pair, modification, shifted, positions, marking,
                                                grid)
                if unloaded is not None:
                    unloaded[key] = tca
            except ValueError as err:
                raise ValueError(f"misalignment_map: {axes[0]} = {a:g}, {axes[1]} = {b:g}: "
                                 f"{err}") from None
            contact = MeshContact(pair, params,
                                  separation=separation_field(pair, modification, shifted))
            loaded = loaded_tca(contact, load_torque, phases)
            result["transmission_error_unloaded_pp"][i, j] = \
                tca["transmission_error_peak_to_peak_urad"]
            result["transmission_error_loaded_pp"][i, j] = \
                loaded.attrs["transmission_error_peak_to_peak_urad"]
            result["pattern_cone_distance"][i, j] = tca["pattern_centre_cone_distance_mm"]
            result["pattern_height"][i, j] = tca["pattern_centre_height_mm"]
            result["pattern_length"][i, j] = tca["pattern_length_mm"]
            result["edge_contact_share"][i, j] = tca["edge_contact_share"]
            result["edge_load_share"][i, j] = loaded.attrs["edge_load_share"]
    centre = tuple(int(np.flatnonzero(v == 0.0)[0]) for v in values)
    result["pattern_shift_lengthwise"] = (result["pattern_cone_distance"]
                                          - result["pattern_cone_distance"][centre])
    result["pattern_shift_profile"] = result["pattern_height"] - result["pattern_height"][centre]
    attrs = {
        "Conventions": "CF-1.11",
        "title": f"V-H map ({', '.join(AXIS_NAMES[a] for a in axes)}) of a "
                 f"{pair.design.trace} spiral bevel gear pair",
        "source": f"lsbg {lsbg.__version__} (lsbg.tca.vh_map.misalignment_map)",
        "lsbg_version": lsbg.__version__,
        "axes": " ".join(axes),
        "positions": int(positions),
        "grid_points": f"{grid[0]} x {grid[1]}",
        "load_torque_N_m": float(load_torque),
        "marking_compound_um": marking * 1e6,
        **sensitivities(result, axes, values, centre),
        **flank_attributes(modification or FlankModification(), base),
        **{f"design_{k}": v for k, v in pair.design.to_config().items()},
    }
    dims = tuple(axes)
    coords = {a: (a, v, {"units": "degree" if a == "Sigma" else "mm", "long_name": AXIS_NAMES[a]})
              for a, v in zip(axes, values)}
    return short_labels(xr.Dataset(
        {name: (dims, result[name], {"units": units, "long_name": text})
         for name, (units, text) in _VARIABLES.items()}, coords=coords, attrs=attrs))


#: Quantities whose change per 0.1 unit of each displacement is summarised.
SENSITIVITY_QUANTITIES = ("pattern_shift_lengthwise", "pattern_shift_profile",
                          "transmission_error_unloaded_pp", "transmission_error_loaded_pp")


def sensitivities(result, axes, values, centre):
    """Change per 0.1 mm (0.1 deg) of each axis through the aligned cell.

    The least-squares slope along the row (or column) through the aligned
    cell, times 0.1.

    Returns
    -------
    dict
        ``{quantity}_per_0_1_{axis}`` [units of the quantity per 0.1 unit].
    """
    out = {}
    for k, letter in enumerate(axes):
        line = [slice(None), slice(None)]
        line[1 - k] = centre[1 - k]
        x = values[k]
        for name in SENSITIVITY_QUANTITIES:
            y = np.asarray(result[name])[tuple(line)]
            ok = np.isfinite(y)
            slope = np.polyfit(x[ok], y[ok], 1)[0] if ok.sum() >= 2 else math.nan
            out[f"{name}_per_0_1_{letter}"] = float(0.1 * slope)
    return out
