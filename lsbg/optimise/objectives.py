"""What one ease-off design is worth: objectives and constraints on a gear pair.

:class:`Evaluator` evaluates a :class:`lsbg.tca.modification.FlankModification`
on a :class:`lsbg.gear.geometry.GearPair` with the uniform-bed line model's
loaded TCA (:func:`lsbg.optimise.loaded.loaded_points`, the equilibrium of
:func:`lsbg.tca.loaded.loaded_tca`) and the unloaded TCA from the surfaces
(:func:`lsbg.tca.analysis.tooth_contact_summary`) at the aligned assembly and
at the corners of the displacement envelope (:func:`lsbg.tca.checks.map_corners`'
V-H envelope, added to the ``misalignment`` section's displacements). Every
quantity of :data:`QUANTITIES` comes out of one evaluation; the objectives
(:data:`OBJECTIVES`, all minimised, any of them selected by name) and the
constraints (:data:`CONSTRAINTS`, feasible at <= 0) are among them:

* ``transmission_error``: the largest loaded TE peak to peak over the load
  range (the rated torque times each load factor), aligned [urad];
* ``transmission_error_harmonic``: the largest first mesh harmonic of it [urad];
* ``envelope_transmission_error``: the largest loaded TE peak to peak at the
  rated torque over the aligned pair and the envelope's corners [urad];
* ``pattern_movement``: the largest movement of the bearing pattern's centre
  (unloaded, at the marking-compound thickness) from the aligned pair's over
  the envelope's corners, in the flank chart (cone distance, height) [mm];
* ``contact_pressure``: the largest Hertz peak pressure p0 = sqrt(q E*/(pi R))
  over the cycle at the rated torque, aligned, off the edges and the reliefs'
  starts (as :class:`lsbg.tooth.ltca.EdgeLoads`' ``max_flank_pressure``) [MPa];
* ``mesh_loss``: the sliding power loss at the rated torque and the pinion's
  speed over the power put in, 100 (1 - efficiency) [%]
  (:mod:`lsbg.optimise.friction`).

Constraints, what "edge" means in lsbg (:class:`lsbg.tooth.ltca.EdgeLoads`,
:attr:`lsbg.tooth.contact_points.ContactPoints.edge`, the unloaded TCA's
``edge_contact``):

* ``edge_contact``: no edge contact at any corner of the envelope, the V-H
  check at light load: at the aligned pair and every corner, no contact
  ellipse at the marking-compound thickness reaches the toe, the heel, the tip
  or the root of the gear's active flank (the unloaded TCA's edge flags; the
  largest share of positions with one);
* ``edge_load``: under the rated torque, aligned, the edges of the active
  flank carry at most ``edge_load_tolerance`` of the load (the loaded points
  at an end of the active profile, where the generated flanks start or a tip
  runs, and in the toe's and the heel's bands:
  :meth:`lsbg.optimise.loaded.MeshPoints.at_edge`); the share less the
  tolerance. (At the envelope's corners under the full rated load no ease-off
  within the backlash keeps every edge unloaded on the paper's pair: the
  share there, ``edge_load_share``, is reported, not constrained.)
* ``pattern_margin``: the bearing pattern inside the face, its ends at least
  ``pattern_margin`` of the face width from the toe and the heel in every
  state [mm];
* ``relief_backlash``: the largest relief within the normal backlash [um], as
  :func:`lsbg.tca.checks.modification_problems` requires;
* ``contact_lost``: contact and backlash kept in every state (the states
  whose unloaded TCA finds the flanks losing contact or interfering).

SI inside; the quantities are in the units of :data:`QUANTITIES`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from lsbg.optimise.friction import (Lubricant, friction_coefficients, mesh_efficiency,
                                    mesh_power_loss, nominal_values)
from lsbg.optimise.kinematics import CurvatureTable, contact_speeds
from lsbg.optimise.loaded import SeparationCache, loaded_points, mesh_points, mesh_positions

__all__ = ["OBJECTIVES", "CONSTRAINTS", "QUANTITIES", "DEFAULT_OBJECTIVES", "PHASES",
           "EvaluationSettings", "Evaluator"]

#: Objectives: name -> (unit, long name).
OBJECTIVES = {
    "transmission_error": ("urad", "largest loaded transmission error peak to peak over "
                                   "the load range"),
    "transmission_error_harmonic": ("urad", "largest first mesh harmonic of the loaded "
                                            "transmission error over the load range"),
    "envelope_transmission_error": ("urad", "largest loaded transmission error peak to "
                                            "peak at the rated torque over the envelope"),
    "pattern_movement": ("mm", "largest movement of the bearing pattern's centre over the "
                               "envelope's corners"),
    "contact_pressure": ("MPa", "largest Hertz pressure off the edges at the rated torque"),
    "mesh_loss": ("%", "mesh power loss at the rated torque, 100 (1 - efficiency)"),
}
#: The objectives optimised unless the configuration names others.
DEFAULT_OBJECTIVES = ("transmission_error", "pattern_movement", "contact_pressure", "mesh_loss")
#: Constraints, feasible at <= 0: name -> (unit, long name).
CONSTRAINTS = {
    "edge_contact": ("1", "largest share of positions whose unloaded contact ellipse reaches "
                          "an edge of the active flank, over the envelope"),
    "edge_load": ("1", "share of the load at the flank's edges at the rated torque, aligned, "
                       "less its tolerance"),
    "pattern_margin": ("mm", "largest shortfall of the bearing pattern's distance from the "
                             "toe or the heel below the margin over the envelope"),
    "relief_backlash": ("um", "largest relief less the normal backlash"),
    "contact_lost": ("1", "states of the envelope whose flanks lose contact or interfere"),
}
#: Further figures of an evaluation: name -> (unit, long name).
EXTRAS = {
    "efficiency": ("%", "mesh efficiency at the rated torque"),
    "friction_coefficient": ("1", "load-weighted mean coefficient of friction at the rated "
                                  "torque"),
    "unloaded_transmission_error": ("urad", "unloaded transmission error peak to peak, "
                                            "aligned (surface TCA)"),
    "edge_load_share": ("1", "largest share of the load at the flank's edges at the rated "
                             "torque over the envelope"),
    "edge_approach": ("um", "largest approach l eps - s at an edge of the active flank at the "
                            "rated torque over the envelope (> 0: loaded)"),
    "aligned_edge_load_share": ("1", "share of the load at the flank's edges at the rated "
                                     "torque, aligned"),
    "least_backlash": ("urad", "least free play of the gear over the envelope"),
    "rated_transmission_error": ("urad", "loaded transmission error peak to peak at the "
                                         "rated torque, aligned"),
}
#: Every quantity of an evaluation.
QUANTITIES = {**OBJECTIVES, **CONSTRAINTS, **EXTRAS}

#: Mesh positions of each loaded TCA over one base pitch (docs/optimise.md: 24 keep the
#: transmission error's peak to peak within 2 % of 256's).
PHASES = 24
#: Each state's unloaded TCA: positions over a mesh cycle and the pinion flank's grid
#: (lsbg.tca.checks' quick TCA; the pattern's centre within about 0.1 mm of the V-H map's).
TCA_POSITIONS = 16
TCA_GRID = (31, 61)


@dataclass(frozen=True)
class EvaluationSettings:
    """How a design is evaluated, in SI units.

    Parameters
    ----------
    rated_torque : float
        The design's rated gear torque T_2 [N m], > 0.
    load_factors : tuple of float
        The load range as multiples of the rated torque [-].
    phases : int
        Positions of each loaded TCA over a base pitch [-].
    base : lsbg.tca.misalignment.Misalignment
        The assembly's displacements the envelope is taken about.
    corners : tuple
        The envelope's corners: ``(label, {letter: SI value})`` added to ``base``.
    pinion_speed : float
        omega_1 [rad/s], > 0.
    friction_law : str
        A key of :data:`lsbg.optimise.friction.FRICTION_LAWS`.
    lubricant : lsbg.optimise.friction.Lubricant
    young_modulus, poisson_ratio : float
        Both members' E [Pa] and nu [-].
    pattern_margin : float
        Least distance of the bearing pattern from the toe and the heel, over
        the face width [-].
    edge_load_tolerance : float
        Share of the load the edges of the active flank may carry at the rated
        torque, aligned [-].
    marking : float
        Marking-compound thickness of the bearing pattern [m].
    contact : lsbg.contact.ContactParameters, optional
        The line model's stiffness and slices (default: lsbg's).
    tca_positions : int
    tca_grid : (int, int)
        Each unloaded TCA's positions over a mesh cycle and pinion grid [-].
    check_positions : int
    check_grid : (int, int)
        The finer unloaded TCA that checks a chosen design for edge contact
        (:meth:`Evaluator.edge_contact`; the V-H map's resolution) [-].
    edge_radius : float
        Edge radius of the generating rack [m], which places the generated
        flanks' starts, the active profile's ends (:func:`lsbg.tooth.field.active_field`;
        lsbg's FE segment's root fillet, ``tooth.fillet_radius_module`` m_mn
        cos(beta_m)); None: the field of contact's own ends.
    """

    rated_torque: float
    load_factors: tuple = (0.5, 1.0, 1.5)
    phases: int = PHASES
    base: object = None
    corners: tuple = ()
    pinion_speed: float = math.radians(7703.0)
    friction_law: str = "iso_tr_14179_2"
    lubricant: Lubricant = field(default_factory=Lubricant)
    young_modulus: float = 206e9
    poisson_ratio: float = 0.3
    pattern_margin: float = 0.02
    edge_load_tolerance: float = 0.02
    marking: float = 6.35e-6
    contact: object = None
    tca_positions: int = TCA_POSITIONS
    tca_grid: tuple = TCA_GRID
    check_positions: int = 100
    check_grid: tuple = (61, 121)
    edge_radius: float = None

    @property
    def torques(self):
        """The load range's gear torques, and the rated one, increasing [N m]."""
        return np.array(sorted({float(f) * self.rated_torque for f in self.load_factors}
                               | {float(self.rated_torque)}))


class Evaluator:
    """Objectives, constraints and further figures of ease-off designs on one pair.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    settings : EvaluationSettings

    Notes
    -----
    What does not depend on the design is built once: the separation
    fields' flank (:class:`lsbg.optimise.loaded.SeparationCache`), the line
    model's conjugate bands (:meth:`lsbg.contact.MeshContact.with_separation`)
    and mesh points (``layout`` of :func:`lsbg.optimise.loaded.loaded_points`),
    the relative curvature's table, ISO/TR 14179-2's nominal values.
    """

    def __init__(self, pair, settings):
        from lsbg.contact import ContactParameters, MeshContact
        from lsbg.tca.checks import normal_backlash
        from lsbg.tca.misalignment import Misalignment

        self.pair, self.settings = pair, settings
        self.params = (settings.contact or ContactParameters()).replace(model="line",
                                                                        compliance="uniform")
        base = settings.base or Misalignment()
        self.states = [("aligned", base)] + [(label, base.shifted(**shift))
                                             for label, shift in settings.corners]
        self.cache = SeparationCache(pair)
        # the conjugate bands and the mesh points are the same for every design and
        # displacement: each contact takes them from these (bit for bit)
        self._conjugate = MeshContact(pair, self.params)
        self._layout = mesh_points(self._conjugate, mesh_positions(pair, settings.phases))
        design = pair.design
        edges = np.linspace(design.inner_cone_distance, design.outer_cone_distance,
                            self.params.slices + 1)
        centres = 0.5 * (edges[1:] + edges[:-1])
        self.curvature = CurvatureTable(pair, np.concatenate([edges[:1], centres, edges[-1:]]))
        #: the active profile's ends per band [rad]
        self.active = (None, None)
        if settings.edge_radius is not None:
            from lsbg.tooth.field import active_field

            self.active = active_field(pair, settings.edge_radius, centres)
        self.nominal = nominal_values(pair, settings.rated_torque, settings.pinion_speed,
                                      self.curvature)
        self.normal_backlash = normal_backlash(design)
        z1, z2 = design.teeth
        self.gear_speed = settings.pinion_speed * z1 / z2
        # the largest movement a pattern can make: across the face and the tooth's depth
        self.movement_cap = math.hypot(design.face_width, design.addendum + design.dedendum)

    def contact(self, modification, misalignment):
        """The line model on the flanks of a design and a displacement."""
        return self._conjugate.with_separation(self.cache.field(modification, misalignment))

    def evaluate(self, modification):
        """Every quantity of :data:`QUANTITIES` for one design, in their units.

        Parameters
        ----------
        modification : lsbg.tca.modification.FlankModification

        Returns
        -------
        dict
        """
        return {**self.loaded(modification), **self._unloaded(modification)}

    def loaded(self, modification):
        """The quantities of :meth:`evaluate` that the loaded TCA gives (the ones its
        positions, ``settings.phases``, change): every one but the unloaded TCA's
        (``pattern_movement``, ``pattern_margin``, ``contact_lost``,
        ``unloaded_transmission_error``, ``edge_contact``, ``least_backlash``).

        Parameters
        ----------
        modification : lsbg.tca.modification.FlankModification

        Returns
        -------
        dict
        """
        s = self.settings
        torques = s.torques
        rated = int(np.flatnonzero(torques == s.rated_torque)[0])
        loads = [f * s.rated_torque for f in s.load_factors]
        out = {"relief_backlash": (modification.largest_relief() - self.normal_backlash) * 1e6}
        edge, edge_share, envelope_te = [], [], []
        for k, (_, misalignment) in enumerate(self.states):
            state = loaded_points(self.contact(modification, misalignment),
                                  torques if k == 0 else [s.rated_torque], s.phases,
                                  self._layout)
            at = rated if k == 0 else 0
            at_edge = state.points.at_edge(*self.active)
            approach = state.approach[at][at_edge]
            edge.append(approach.max() if approach.size else -math.inf)
            force = state.force[at]
            edge_share.append(force[at_edge].sum() / force.sum())
            envelope_te.append(np.ptp(state.transmission_error[at]) * 1e6)
            if k == 0:
                out.update(self._aligned(state, modification, torques, loads, rated))
        out["edge_approach"] = float(max(edge) * 1e6)
        out["edge_load_share"] = float(max(edge_share))
        out["aligned_edge_load_share"] = float(edge_share[0])
        out["edge_load"] = float(edge_share[0] - s.edge_load_tolerance)
        out["envelope_transmission_error"] = float(max(envelope_te))
        return out

    def edge_contact(self, modification):
        """The ``edge_contact`` constraint at the finer unloaded TCA of the settings'
        ``check_positions`` and ``check_grid`` (the V-H map's): the largest share of
        positions whose contact ellipse reaches an edge over the envelope's states [-],
        1 where a state loses contact. The search's quick TCA (16 positions) can miss
        an edge touched between its positions; a chosen design is checked with this."""
        from lsbg.tca.analysis import tooth_contact_summary

        s, worst = self.settings, 0.0
        for _, misalignment in self.states:
            try:
                tca = tooth_contact_summary(self.pair, modification, misalignment,
                                            s.check_positions, s.marking, s.check_grid)
            except ValueError:
                return 1.0
            worst = max(worst, tca["edge_contact_share"])
        return float(worst)

    def _aligned(self, state, modification, torques, loads, rated):
        """TE over the load range, pressure and friction at the rated torque."""
        from lsbg.tca.loaded import harmonic_amplitudes
        from lsbg.tca.modification import pinion_tip_end
        from lsbg.tooth.local import peak_pressure

        s = self.settings
        te = state.transmission_error * 1e6
        in_range = np.isin(torques, loads)
        points = state.points
        q = state.line_load[rated]
        # Hertz off the edges and the tip reliefs' starts (lsbg.tooth.ltca.EdgeLoads)
        plane = self.pair.planes["drive"]
        centre = 0.5 * (plane.field[0] + plane.field[1])
        half = 0.5 * (plane.field[1] - plane.field[0])
        flank = points.inside & ~points.profile_edge(*self.active)
        for v in modification.relief_starts(pinion_tip_end(self.pair)).values():
            psi = centre + v * half
            flank &= ~((points.psi_from < psi) & (psi < points.psi_to))
        loaded = q > 0
        curvature = self.curvature(points.rho[loaded], points.psi[loaded])
        pressure = np.zeros(q.shape)
        pressure[loaded] = peak_pressure(q[loaded], curvature, s.young_modulus, s.poisson_ratio)
        flank_pressure = pressure[flank & loaded]
        # sliding friction at the pinion's speed
        sliding, rolling = contact_speeds(self.pair, points.rho[loaded], points.psi[loaded],
                                          s.pinion_speed)
        mu = friction_coefficients(s.friction_law, q[loaded], sliding, rolling, s.lubricant,
                                   self.nominal, self.pair.design.face_width)
        force = state.force[rated][loaded]
        loss = mesh_power_loss(force, sliding, mu) / points.pinion_angle.size
        efficiency = mesh_efficiency(loss, s.rated_torque, self.gear_speed)
        return {
            "transmission_error": float(np.ptp(te[in_range], axis=1).max()),
            "transmission_error_harmonic": float(max(harmonic_amplitudes(row, 1)[0]
                                                     for row in te[in_range])),
            "rated_transmission_error": float(np.ptp(te[rated])),
            "contact_pressure": float(flank_pressure.max() * 1e-6 if flank_pressure.size else 0.0),
            "mesh_loss": float(100 * (1 - efficiency)),
            "efficiency": float(100 * efficiency),
            "friction_coefficient": float(np.sum(mu * force) / np.sum(force)),
        }

    def _unloaded(self, modification):
        """The bearing pattern's movement and margin, backlash and contact kept."""
        from lsbg.tca.analysis import tooth_contact_summary

        s, design = self.settings, self.pair.design
        lost, centres, margins, plays, shares = 0, [], [], [], []
        unloaded_te = math.nan
        for k, (_, misalignment) in enumerate(self.states):
            try:
                tca = tooth_contact_summary(self.pair, modification, misalignment,
                                            s.tca_positions, s.marking, s.tca_grid)
            except ValueError:  # contact lost or backlash closed
                lost += 1
                centres.append((math.nan, math.nan))
                continue
            if k == 0:
                unloaded_te = tca["transmission_error_peak_to_peak_urad"]
            centres.append((tca["pattern_centre_cone_distance_mm"],
                            tca["pattern_centre_height_mm"]))
            toe = tca["pattern_toe_mm"] - design.inner_cone_distance * 1e3
            heel = design.outer_cone_distance * 1e3 - tca["pattern_heel_mm"]
            margins.append(s.pattern_margin * design.face_width * 1e3 - min(toe, heel))
            plays.append(tca["backlash_min_urad"])
            shares.append(tca["edge_contact_share"])
        centres = np.array(centres)
        moves = np.hypot(*(centres[1:] - centres[0]).T) if len(centres) > 1 else np.zeros(1)
        cap = self.movement_cap * 1e3
        movement = float(np.nanmax(moves)) if np.all(np.isfinite(moves)) else cap
        margins = np.asarray(margins, float)
        return {"pattern_movement": min(movement, cap),
                "pattern_margin": float(np.max(np.where(np.isfinite(margins), margins, cap)))
                if margins.size else cap,
                "contact_lost": float(lost),
                "unloaded_transmission_error": float(unloaded_te),
                "edge_contact": float(max(shares)) if shares else 1.0,
                "least_backlash": float(min(plays)) if plays else 0.0}
