"""The URDF of the pair for PyBullet: two revolute joints, the meshes, the mass properties.

Contact in the simulation comes from lsbg's exact geometry (DESIGN.md §1), so
the links carry no collision shapes of their own that Bullet would use for
contact forces. Lengths in metres, masses in kilograms.
"""

from __future__ import annotations

import math
import os
from xml.etree import ElementTree

import numpy as np

from lsbg.gear.geometry import MEMBERS, MEMBER_NAMES

__all__ = ["write_urdf"]


# --------------------------------------------------------------------- URDF
def _rpy(rotation):
    """URDF roll, pitch, yaw of a rotation matrix R = Rz(yaw) Ry(pitch) Rx(roll) [rad]."""
    pitch = math.asin(-max(-1.0, min(1.0, rotation[2, 0])))
    roll = math.atan2(rotation[2, 1], rotation[2, 2])
    yaw = math.atan2(rotation[1, 0], rotation[0, 0])
    return roll, pitch, yaw


def _fmt(values):
    return " ".join(repr(float(v)) for v in np.atleast_1d(values))


def write_urdf(path, pair, props, mesh_files):
    """URDF of the assembled pair for PyBullet.

    A fixed base link ``frame`` (1 g, 1e-9 kg m^2) carries the links
    ``pinion`` and ``gear`` on revolute joints ``pinion_joint`` and
    ``gear_joint``. Both joints sit at the apex with ``axis`` = the forward
    rotation axis u_m; link frames equal the mesh frame at rotation 0, so a
    joint angle is the member's forward rotation. Each ``<inertial>`` is
    placed at the centre of mass and turned onto the principal axes (z along
    the gear axis) with ixy = ixz = iyz = 0, because PyBullet keeps only the
    diagonal of the URDF inertia in the inertial frame; izz is the axial
    moment. Limits: effort 1e9 N m, velocity 1e4 rad/s (PyBullet's own
    ``maxJointVelocity`` of 100 rad/s is separate; see DESIGN.md §3), no
    damping or friction. There is no ``<collision>`` element: contact forces
    come from :mod:`lsbg.gear.geometry`, never from Bullet (DESIGN.md §3).

    Parameters
    ----------
    path : str or os.PathLike
        URDF file to write.
    pair : lsbg.gear.geometry.GearPair
    props : dict
        ``{member: MassProperties}`` for members 1 and 2.
    mesh_files : dict
        ``{member: path}`` of the visual meshes (OBJ or STL, in metres),
        written relative to the URDF's directory.

    Returns
    -------
    str
        The path written.
    """
    path = os.fspath(path)
    base = os.path.dirname(os.path.abspath(path))
    robot = ElementTree.Element("robot", name=f"lsbg_{pair.design.trace}_pair")
    frame = ElementTree.SubElement(robot, "link", name="frame")
    inertial = ElementTree.SubElement(frame, "inertial")
    ElementTree.SubElement(inertial, "origin", xyz="0 0 0", rpy="0 0 0")
    ElementTree.SubElement(inertial, "mass", value="0.001")
    ElementTree.SubElement(inertial, "inertia", ixx="1e-09", ixy="0", ixz="0",
                           iyy="1e-09", iyz="0", izz="1e-09")
    colours = {1: "0.80 0.45 0.20 1", 2: "0.55 0.60 0.70 1"}
    for member in MEMBERS:
        name, p = MEMBER_NAMES[member], props[member]
        link = ElementTree.SubElement(robot, "link", name=name)
        inertial = ElementTree.SubElement(link, "inertial")
        ElementTree.SubElement(inertial, "origin", xyz=_fmt(p.centre_of_mass),
                               rpy=_fmt(_rpy(p.principal_axes)))
        ElementTree.SubElement(inertial, "mass", value=repr(p.mass))
        ixx, iyy, izz = p.principal_moments
        ElementTree.SubElement(inertial, "inertia", ixx=repr(float(ixx)), ixy="0", ixz="0",
                               iyy=repr(float(iyy)), iyz="0", izz=repr(float(izz)))
        visual = ElementTree.SubElement(link, "visual")
        ElementTree.SubElement(visual, "origin", xyz="0 0 0", rpy="0 0 0")
        geometry = ElementTree.SubElement(visual, "geometry")
        relative = os.path.relpath(os.path.abspath(os.fspath(mesh_files[member])), base)
        ElementTree.SubElement(geometry, "mesh", filename=relative.replace(os.sep, "/"),
                               scale="1 1 1")
        material = ElementTree.SubElement(visual, "material", name=f"{name}_colour")
        ElementTree.SubElement(material, "color", rgba=colours[member])
        joint = ElementTree.SubElement(robot, "joint", name=f"{name}_joint", type="revolute")
        ElementTree.SubElement(joint, "parent", link="frame")
        ElementTree.SubElement(joint, "child", link=name)
        ElementTree.SubElement(joint, "origin", xyz="0 0 0", rpy="0 0 0")
        ElementTree.SubElement(joint, "axis", xyz=_fmt(pair.rotation_axis[member]))
        # Revolute joints need limits; these never bind.
        ElementTree.SubElement(joint, "limit", lower="-1e9", upper="1e9",
                               effort="1e9", velocity="1e4")
        ElementTree.SubElement(joint, "dynamics", damping="0", friction="0")
    ElementTree.indent(robot)
    with open(path, "w", encoding="utf-8") as handle:
        handle.write('<?xml version="1.0"?>\n')
        handle.write(f"<!-- lsbg: {pair.design.trace} trace, spiral angle "
                     f"{math.degrees(pair.design.spiral_angle):g} deg; SI units; "
                     "mesh frame = world frame, apex at the origin -->\n")
        handle.write(ElementTree.tostring(robot, encoding="unicode"))
        handle.write("\n")
    return path
