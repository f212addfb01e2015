"""Mass properties of the solid gears, twice: from the triangle mesh and by quadrature.

:func:`mass_properties` integrates over the closed mesh of :mod:`lsbg.solid.solids`
(divergence theorem, :mod:`lsbg.solid.polyhedra`); :func:`quadrature_mass_properties`
integrates independently over the section outlines in spherical coordinates.
The tests compare the two. Lengths in metres, masses in kilograms, inertias in
kg·m².
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lsbg.solid.polyhedra import mesh_mass_properties
from lsbg.solid.outline import flank_azimuth, side_order, wrap_angle

__all__ = [
    "MassProperties", "principal_frame", "mass_properties", "section_integrals",
    "QuadratureMassProperties", "quadrature_mass_properties"
]


# --------------------------------------------------------- mass properties
@dataclass(frozen=True)
class MassProperties:
    """Mass properties of one gear.

    Attributes
    ----------
    member : int
    volume : float
        [m^3]
    mass : float
        [kg]
    centre_of_mass : numpy.ndarray, shape (3,)
        In the mesh frame [m].
    inertia : numpy.ndarray, shape (3, 3)
        Inertia tensor about the centre of mass, mesh-frame axes [kg m^2].
    axial_inertia : float
        Moment of inertia about the rotation axis (through the apex) [kg m^2].
    principal_axes : numpy.ndarray, shape (3, 3)
        Columns x, y, z of the principal frame (:func:`principal_frame`); z is
        the rotation axis u [-].
    principal_moments : numpy.ndarray, shape (3,)
        Diagonal of the inertia tensor in that frame [kg m^2]; the last is
        the axial moment about the centre of mass.
    """

    member: int
    volume: float
    mass: float
    centre_of_mass: np.ndarray
    inertia: np.ndarray
    axial_inertia: float
    principal_axes: np.ndarray
    principal_moments: np.ndarray


def principal_frame(pair, member):
    """Principal axes of a gear: columns x, y, z with z = rotation axis [-].

    The gear has z-fold symmetry (z >= 3) about its axis, so its inertia
    ellipsoid is one of revolution and any pair of axes normal to the rotation
    axis is principal. y is the mesh frame's z axis (normal to both gear
    axes) and x = y x z lies in the axial plane, which keeps the URDF's
    roll-pitch-yaw away from gimbal lock (pitch = 0).

    Returns
    -------
    numpy.ndarray, shape (3, 3)
    """
    z_axis = pair.rotation_axis[member]
    y_axis = np.array([0.0, 0.0, 1.0])
    return np.column_stack([np.cross(y_axis, z_axis), y_axis, z_axis])


def mass_properties(mesh, pair, member, density=None):
    """Mass properties of a gear mesh.

    Parameters
    ----------
    mesh : lsbg.solid.polyhedra.TriangleMesh
        Watertight gear mesh from :func:`gear_mesh` [m].
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    density : float, optional
        [kg/m^3]; default ``pair.design.density``.

    Returns
    -------
    MassProperties
    """
    rho = pair.design.density if density is None else float(density)
    props = mesh_mass_properties(mesh.triangles, density=rho)
    com = np.asarray(props.center_mass, dtype=float)
    inertia = np.asarray(props.inertia, dtype=float)
    u = pair.rotation_axis[member]
    # Parallel-axis term for the tiny offset of the mesh's centre from the axis.
    offset = com - (com @ u) * u
    axial = float(u @ inertia @ u + props.mass * (offset @ offset))
    axes = principal_frame(pair, member)
    return MassProperties(member, float(props.volume), float(props.mass), com, inertia, axial,
                          axes, np.diag(axes.T @ inertia @ axes).copy())


# The section integrals: F(theta) with dF/dtheta = f(theta) and the power of R
# in the volume element R^2 sin(theta) dtheta dphi dR times the integrand.
_INTEGRANDS = {
    # volume: f = sin
    "volume": (lambda t: -np.cos(t), lambda t: np.sin(t), 2),
    # axial moment, r_perp^2 = R^2 sin^2: f = sin^3
    "axial": (lambda t: -np.cos(t) + np.cos(t) ** 3 / 3, lambda t: np.sin(t) ** 3, 4),
    # first moment along the axis, R cos: f = cos sin
    "first": (lambda t: -np.cos(t) ** 2 / 2, lambda t: np.cos(t) * np.sin(t), 3),
    # moment about a line normal to the axis through the apex: z^2 + r_perp^2 / 2
    "transverse": (lambda t: -np.cos(t) / 2 - np.cos(t) ** 3 / 6,
                   lambda t: (0.5 + np.cos(t) ** 2 / 2) * np.sin(t), 4),
}


def section_integrals(pair, member, cone_distance, n_profile=48):
    """Integrals over the gear's section on the unit sphere, without a mesh.

    The section at cone distance R is the region between the bore circle
    (theta_b = asin(r_bore / R)) and the tooth outline theta_out(phi). By Green's
    theorem, for any f = F', int int f(theta) dtheta dphi = oint F(theta_out) dphi
    - 2 pi F(theta_b), the loop taken in increasing azimuth. Root arcs and top
    lands (constant theta) contribute F times their angular width; a flank
    contributes F(tip) dphi - int (phi - phi_start) f dtheta (by parts),
    evaluated by Gauss-Legendre in t with theta = start + (tip - start) t^2, in
    which the involute's azimuth is smooth; the radial continuation below the
    base cone adds nothing (dphi = 0).

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    cone_distance : array_like
        Sphere radii R [m], 1-D.
    n_profile : int
        Gauss points per flank [-].

    Returns
    -------
    dict of numpy.ndarray, shape (n,)
        ``volume``: int int sin(theta); ``axial``: sin^3; ``first``:
        cos sin; ``transverse``: (cos^2 + sin^2 / 2) sin [sr].
    """
    d = pair.design
    radius = np.atleast_1d(np.asarray(cone_distance, dtype=float))
    z = d.teeth[member - 1]
    root, tip = d.root_angle(member), d.tip_angle(member)
    start = pair.flank_polar_range(member)[0]
    bore = (d.pinion_bore if member == 1 else d.gear_bore) / 2
    theta_bore = np.arcsin(bore / radius)
    nodes, weights = np.polynomial.legendre.leggauss(n_profile)
    t = (nodes + 1) / 2
    polar = start + (tip - start) * t**2
    dpolar = 2 * (tip - start) * t * weights / 2   # dtheta/dt times the weights on [0, 1]
    ends = np.array([start, tip])
    low, high = side_order(pair, member)
    phi = {}
    for side in (low, high):
        at_ends = flank_azimuth(pair, member, side, radius, ends)
        inside = flank_azimuth(pair, member, side, radius, polar)
        phi[side] = (at_ends[:, 0], wrap_angle(at_ends[:, 1] - at_ends[:, 0]),
                     wrap_angle(inside - at_ends[:, :1]))
    # Angular widths at the root (tooth) and of the top land, from the flank ends.
    base_width = wrap_angle(phi[high][0] - phi[low][0])
    top_width = base_width + phi[high][1] - phi[low][1]
    root_width = 2 * np.pi / z - base_width
    out = {}
    for name, (big_f, small_f, _) in _INTEGRANDS.items():
        def flank(side):
            _, rise, inner = phi[side]
            return big_f(tip) * rise - inner @ (small_f(polar) * dpolar)
        tooth = flank(low) + big_f(tip) * top_width - flank(high) + big_f(root) * root_width
        out[name] = z * tooth - 2 * np.pi * big_f(theta_bore)
    return out


@dataclass(frozen=True)
class QuadratureMassProperties:
    """Mass properties of a gear by quadrature over its sections (no mesh).

    Attributes
    ----------
    volume : float
        Of the gear's solid, teeth included [m^3].
    mass : float
        The volume times the density [kg].
    axial_inertia : float
        About the gear axis [kg m^2].
    centre_of_mass_distance : float
        Distance of the centre of mass from the apex, along the axis [m].
    transverse_inertia : float
        About a line through the centre of mass normal to the axis [kg m^2].
    """

    volume: float
    mass: float
    axial_inertia: float
    centre_of_mass_distance: float
    transverse_inertia: float


def quadrature_mass_properties(pair, member, density=None, n_radial=16, n_profile=48):
    """Mass properties from :func:`section_integrals`, Gauss-Legendre over R.

    V = int R^2 S_vol(R) dR and I = rho int R^4 S_axial(R) dR, where S are the
    section integrals on the unit sphere; independent of the triangle mesh.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    density : float, optional
        [kg/m^3]; default ``pair.design.density``.
    n_radial, n_profile : int
        Gauss points across the face width and per flank [-].

    Returns
    -------
    QuadratureMassProperties
    """
    d = pair.design
    rho = d.density if density is None else float(density)
    nodes, weights = np.polynomial.legendre.leggauss(n_radial)
    r_in, r_out = d.inner_cone_distance, d.outer_cone_distance
    radius = r_in + (r_out - r_in) * (nodes + 1) / 2
    weights = weights * (r_out - r_in) / 2
    sections = section_integrals(pair, member, radius, n_profile)
    total = {name: float(np.sum(weights * radius**_INTEGRANDS[name][2] * sections[name]))
             for name in _INTEGRANDS}
    volume = total["volume"]
    com = total["first"] / volume
    return QuadratureMassProperties(
        volume=volume, mass=rho * volume, axial_inertia=rho * total["axial"],
        centre_of_mass_distance=com,
        transverse_inertia=rho * (total["transverse"] - volume * com**2))
