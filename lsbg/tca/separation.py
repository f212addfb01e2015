"""The separation field of real flanks on the conjugate contact lines.

The line model (:mod:`lsbg.contact`) loads slices of the conjugate contact
lines; on real flanks each point of a line starts apart from its mate by the
*separation* s: the relief of the modification plus what the displacements
open or close there. Measured in the normal approach x = l eps of the
slices, a slice then carries k_l (l eps - s) (Simon, J. Mech. Des. 129(2),
2007; Kolivand & Kahraman, Mech. Mach. Theory 44, 2009, load the potential
contact lines with the ease-off the same way). :func:`separation_field`
gives s from the exact surfaces (:func:`lsbg.tca.surface.point_separations`);
:class:`lsbg.contact.MeshContact` tabulates it over the lines' turns.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from lsbg.tca import surface
from lsbg.tca.analysis import SurfacePair
from lsbg.tca.misalignment import Misalignment
from lsbg.tca.modification import FlankModification, flank_attributes, relieved_flank


@dataclass(frozen=True)
class RealFlanks:
    """The flanks a line-model analysis runs on: modification and displacements.

    Passed as ``flanks=`` to :func:`lsbg.dynamics.load_model`,
    :func:`lsbg.dynamics.simulate` and :func:`lsbg.tca.loaded.ltca_for_geometry`,
    which build the pair first and then ask for its separation field.

    Parameters
    ----------
    modification : FlankModification
    misalignment : Misalignment
    """

    modification: FlankModification = field(default_factory=FlankModification)
    misalignment: Misalignment = field(default_factory=Misalignment)

    @classmethod
    def from_config(cls, modification=None, misalignment=None, base=None):
        """From the ``flank_modification:`` and ``misalignment:`` sections.

        Raises
        ------
        ValueError
            Naming the key and value.
        """
        return cls(FlankModification.from_config(modification, base),
                   Misalignment.from_config(misalignment))

    @property
    def is_conjugate(self):
        """True for unmodified flanks on an aligned pair."""
        return self.modification.is_zero and self.misalignment.is_zero

    def separation(self, pair):
        """The separation field on ``pair`` (:func:`separation_field`), or None."""
        return separation_field(pair, self.modification, self.misalignment)

    @property
    def attrs(self):
        """Dataset attributes: the two sections' keys, prefixed."""
        return flank_attributes(self.modification, self.misalignment)


class SeparationField:
    """The initial separation on the conjugate contact lines of one pair.

    Call it as ``field(turn, cone_distance)`` [m] for contact lines of turn
    Psi [rad] at distances rho from the apex [m] (drive side, arrays
    broadcast); ``attrs`` names the modification and displacements.

    Notes
    -----
    The gear's flank is continued analytically beyond its face and active
    profile, so the line model keeps the nominal field of contact; the edges
    of a displaced member are the surface TCA's to find
    (:func:`lsbg.tca.analysis.tooth_contact_analysis`).
    """

    def __init__(self, pair, modification, misalignment):
        self.pair, self.modification, self.misalignment = pair, modification, misalignment
        self.attrs = flank_attributes(modification, misalignment)
        constants = SurfacePair.build(pair, modification, misalignment, face_points=2,
                                      profile_points=2).constants.copy()
        constants[surface.G_THETA_LO2], constants[surface.G_THETA_HI2] = 0.0, math.pi
        constants[surface.G_R_IN], constants[surface.G_R_OUT] = 0.0, math.inf
        self._constants = constants

    def __call__(self, turn, cone_distance):
        pair = self.pair
        turn, rho = np.broadcast_arrays(np.asarray(turn, float), np.asarray(cone_distance, float))
        psi = turn + pair.planes["drive"].curve.polar_angle(rho)
        points, normals, _ = relieved_flank(pair, self.modification, rho, psi)
        # tooth 0 carries the line of turn Psi at pinion rotation Psi / s1
        angles = np.ascontiguousarray((turn / pair.axis_normal_component(1, "drive")).ravel())
        gap = surface.point_separations(angles, np.ascontiguousarray(points.reshape(-1, 3)),
                                        np.ascontiguousarray(normals.reshape(-1, 3)),
                                        self._constants)
        return gap.reshape(turn.shape)


def separation_field(pair, modification=None, misalignment=None):
    """The initial separation on the conjugate contact lines, or None.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    modification : FlankModification, optional
    misalignment : Misalignment, optional

    Returns
    -------
    SeparationField or None
        None for conjugate flanks on an aligned pair, so that the line model
        runs exactly as before.
    """
    modification = (modification or FlankModification()).load()
    misalignment = misalignment or Misalignment()
    if modification.is_zero and misalignment.is_zero:
        return None
    return SeparationField(pair, modification, misalignment)
