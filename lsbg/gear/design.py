"""Design parameters of a bevel gear pair and the quantities derived from them.

The defaults are the paper's Table 1: a 9:37 pair, outer transverse module
4.5 mm, shaft angle 90 deg, normal pressure angle 20 deg, mean spiral angle
35 deg, left-hand pinion. All lengths are in metres and all angles in radians
inside; :meth:`GearPairDesign.from_config` reads the paper's units (``*_mm``,
``*_deg``) used by the workflow configuration.

Every derived quantity here is closed form (standard bevel gear geometry, the depth's
taper in :mod:`lsbg.gear.depth`); the flanks on these numbers: :mod:`lsbg.gear.geometry`.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from lsbg.gear import depth
from lsbg.gear.plane import GeneratingCurve
from lsbg.memo import per_member

TRACES = ("logarithmic", "circular", "face_milled")
#: Tooth trace -> the paper's name of the gear type (both circular traces are SBGs).
TRACE_LABELS = {"logarithmic": "LSBG", "circular": "SBG", "face_milled": "SBG"}
#: Tooth trace -> the gear type and which construction made it.
TRACE_NAMES = {"logarithmic": "LSBG", "circular": "SBG, paper's arc",
               "face_milled": "SBG, ISO 23509 face-milled"}
BASE_CONE_RULES = ("involute", "paper")
HANDS = ("left", "right")
UNDERCUT = ("accept", "refuse")

#: Density of steel [kg/m^3], used for the mass properties of the solids.
STEEL_DENSITY = 7850.0


class DesignError(ValueError):
    """A design parameter is invalid, or the design gives unusable teeth.

    The message always names the offending parameter and its value.
    """


#: Plausible ranges of the SI fields: ``(low, high, unit)``. A value outside is almost
#: surely in other units (mm for m): refused with the conversion.
PLAUSIBLE = {"module": (1e-4, 0.1, "m"), "face_width": (1e-4, 1.0, "m"),
             "addendum": (1e-5, 0.2, "m"), "dedendum": (1e-5, 0.2, "m"),
             "cutter_radius": (1e-3, 5.0, "m"), "pinion_bore": (1e-4, 2.0, "m"),
             "gear_bore": (1e-4, 5.0, "m"), "density": (500.0, 30000.0, "kg/m^3")}


def _hint(name, value):
    """How to give ``value`` of field ``name`` that was (probably) in the paper's units."""
    if name == "density":
        return f"{value:g} kg/m^3 is outside what gears are made of"
    return (f"{value:g} mm is {value * 1e-3:g} m (GearPairDesign.from_units({name}_mm="
            f"{value:g}))")


@dataclass(frozen=True)
class GearPairDesign:
    """Design parameters of a spiral bevel gear pair (pinion = member 1).

    Parameters
    ----------
    pinion_teeth, gear_teeth : int
        Numbers of teeth z1 and z2 [-]; the pinion is the smaller member.
    module : float
        Outer transverse module m [m].
    shaft_angle : float
        Angle between the two axes, Sigma [rad].
    normal_pressure_angle : float
        Normal pressure angle at the mean point, alpha_n [rad].
    spiral_angle : float
        Mean spiral angle on the pitch cone, beta_m [rad].
    pinion_hand : {"left", "right"}
        Hand of spiral of the pinion; the gear has the other hand.
    addendum, dedendum : float
        Outer addendum h_a and dedendum h_f, equal for both members [m].
    trace : {"logarithmic", "circular", "face_milled"}
        Generating curve in the plane of action (:class:`lsbg.gear.plane.GeneratingCurve`):
        a plane logarithmic spiral (LSBG); the face-mill cutter's circular arc drawn
        in the plane of action (the paper's SBG); or the SBG of ISO 23509 and AGMA
        929, whose cutter circle lies in the generating crown gear's pitch plane
        (its spiral angle at every cone distance the standard's).
    face_width : float
        Face width b along the pitch cone generator [m].
    cutter_radius : float
        Cutter radius r_c0 of the SBGs (``trace="circular"`` or ``"face_milled"``) [m].
    base_cone_rule : {"involute", "paper"}
        How the base cones are chosen: ``"involute"`` gives the normal pressure
        angle ``normal_pressure_angle`` at the mean point; ``"paper"`` is the
        paper's Eq. 6, sin(delta_b) = sin(beta) sin(delta).
    backlash : float
        Circumferential backlash on the mean pitch circle [m], split equally
        between the two members' tooth thicknesses.
    density : float
        Density of both gears [kg/m^3].
    pinion_bore, gear_bore : float
        Bore diameters of the pinion and gear hubs [m].
    profile_shift : float
        Mean profile shift coefficient of the pinion x_hm1 (ISO 23509), the gear's
        x_hm2 = -x_hm1 [-]: the basic crown gear moved x_hm1 m_mn towards the
        pinion's tip. It moves depth from the gear's addendum to the pinion's
        (and back at the roots) and thickens the pinion's tooth by
        2 x_hm1 m_mn tan(alpha_n) in the normal section, on the same flank
        surfaces (the rolling plane is the same: only where the teeth are cut
        and how far apart their flanks stand change).
    thickness_modification : float
        Thickness modification coefficient of the pinion x_smn1 (ISO 23509), the
        gear's -x_smn1 [-]: the pinion's mean normal tooth thickness grows by
        2 x_smn1 m_mn, the gear's shrinks by as much.
    undercut : {"accept", "refuse"}
        Whether a pinion or gear whose root cone cuts into the path of contact
        (undercut, :attr:`lsbg.gear.geometry.GearPair.undercut`) is a design
        lsbg builds. The paper's pair is undercut at 35 deg and below (its
        9-tooth pinion is unshifted), so its design accepts it; a practice
        design refuses it.
    depth_taper : {"apex", "given_dedendum_angles", "standard", "uniform"}
        The depth's taper along the face, all cones to the apex or ISO 23509's
        (:mod:`lsbg.gear.depth`); ``dedendum_angles`` (theta_f1, theta_f2) [rad] the given.
    """

    pinion_teeth: int = 9
    gear_teeth: int = 37
    module: float = 4.5e-3
    shaft_angle: float = math.radians(90.0)
    normal_pressure_angle: float = math.radians(20.0)
    spiral_angle: float = math.radians(35.0)
    pinion_hand: str = "left"
    addendum: float = 3.825e-3
    dedendum: float = 4.671e-3
    trace: str = "logarithmic"
    face_width: float = 25e-3
    cutter_radius: float = 76.2e-3
    base_cone_rule: str = "involute"
    backlash: float = 0.1e-3
    density: float = STEEL_DENSITY
    pinion_bore: float = 12e-3
    gear_bore: float = 60e-3
    profile_shift: float = 0.0
    thickness_modification: float = 0.0
    undercut: str = "accept"
    depth_taper: str = "apex"
    dedendum_angles: tuple | None = None

    def __post_init__(self):
        self._validate()

    # ------------------------------------------------------------------ input
    def _validate(self):
        def fail(name, value, why):
            raise DesignError(f"{name} = {value!r}: {why}")

        for name in ("pinion_teeth", "gear_teeth"):
            z = getattr(self, name)
            if isinstance(z, bool) or not float(z).is_integer() or z < 1:
                fail(name, z, "must be a positive whole number of teeth")
        if self.pinion_teeth < 5:
            fail("pinion_teeth", self.pinion_teeth, "a bevel pinion needs at least 5 teeth")
        if self.pinion_teeth > self.gear_teeth:
            fail("pinion_teeth", self.pinion_teeth,
                 f"the pinion is the smaller member, but gear_teeth = {self.gear_teeth}")
        for name in ("module", "face_width", "addendum", "dedendum", "cutter_radius",
                     "density", "pinion_bore", "gear_bore"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v > 0):
                fail(name, v, "must be a positive, finite number")
        # SI inside: a length given in mm (a module of 4.5 "m") is refused here, not meshed
        for name, (low, high, unit) in PLAUSIBLE.items():
            v = getattr(self, name)
            if not low <= v <= high:
                fail(name, v, f"is not a plausible {name.replace('_', ' ')} in {unit} "
                              f"({low:g}-{high:g} {unit}); lsbg takes SI units: "
                              f"{_hint(name, v)}")
        for name in ("shaft_angle", "spiral_angle", "normal_pressure_angle"):
            if abs(getattr(self, name)) > math.pi:
                fail(name, getattr(self, name), f"is not an angle in radians; lsbg takes SI "
                     f"units: math.radians({getattr(self, name):g}), or "
                     f"GearPairDesign.from_units({name}_deg={getattr(self, name):g})")
        if not (0 < self.shaft_angle < math.pi):
            fail("shaft_angle", math.degrees(self.shaft_angle), "must lie in (0, 180) deg")
        if not (0 < self.spiral_angle < math.radians(60)):
            fail("spiral_angle", math.degrees(self.spiral_angle), "must lie in (0, 60) deg")
        if not (math.radians(10) <= self.normal_pressure_angle <= math.radians(30)):
            fail("normal_pressure_angle", math.degrees(self.normal_pressure_angle),
                 "must lie in [10, 30] deg")
        if self.trace not in TRACES:
            fail("trace", self.trace, f"must be one of {TRACES}")
        if self.base_cone_rule not in BASE_CONE_RULES:
            fail("base_cone_rule", self.base_cone_rule, f"must be one of {BASE_CONE_RULES}")
        if self.pinion_hand not in HANDS:
            fail("pinion_hand", self.pinion_hand, f"must be one of {HANDS}")
        if self.face_width > self.outer_cone_distance / 2:
            fail("face_width", self.face_width,
                 f"exceeds half the outer cone distance R_e/2 = {self.outer_cone_distance / 2:.6g} m")
        for name in ("profile_shift", "thickness_modification"):
            value = getattr(self, name)
            if isinstance(value, bool) or not (np.isfinite(value) and abs(value) < 1.5):
                fail(name, value, "must be a number of mean normal modules in (-1.5, 1.5)")
        if self.undercut not in UNDERCUT:
            fail("undercut", self.undercut, f"must be one of {UNDERCUT}")
        if (problem := depth.taper_problem(self)) is not None:
            fail(*problem)
        if self.addendum > 1.25 * self.module:
            fail("addendum", self.addendum, f"exceeds 1.25 module = {1.25 * self.module:.6g} m")
        for member in (1, 2):
            name = "pinion" if member == 1 else "gear"
            if self.outer_dedendum(member) <= 0 or self.outer_addendum(member) <= 0:
                fail("profile_shift", self.profile_shift,
                     f"leaves the {name} no addendum or dedendum (outer addendum "
                     f"{self.outer_addendum(member):.6g} m, dedendum "
                     f"{self.outer_dedendum(member):.6g} m)")
        if self.dedendum <= self.addendum:
            fail("dedendum", self.dedendum,
                 f"must exceed the addendum {self.addendum:.6g} m to leave tip clearance")
        if self.dedendum > 1.6 * self.module:
            fail("dedendum", self.dedendum, f"exceeds 1.6 module = {1.6 * self.module:.6g} m")
        if not (0 <= self.backlash < 0.1 * self.mean_circular_pitch):
            fail("backlash", self.backlash,
                 f"must lie in [0, 0.1 mean circular pitch = {0.1 * self.mean_circular_pitch:.6g} m)")
        for member, bore in ((1, self.pinion_bore), (2, self.gear_bore)):
            root_radius = self.inner_cone_distance * math.sin(self.root_angle(member))
            if bore / 2 >= 0.9 * root_radius:
                name = "pinion_bore" if member == 1 else "gear_bore"
                fail(name, bore, f"leaves no hub under the teeth (inner root radius "
                     f"{root_radius:.6g} m)")
        if self.trace != "logarithmic":
            # The circle must not turn radial inside the face (its angle to the ray
            # reaches 90 deg where sin = 1; |sin| is largest at the toe or the heel).
            ends = np.array([self.inner_cone_distance, self.outer_cone_distance])
            sines = GeneratingCurve(self.trace, self.plane_spiral_angle, self.mean_cone_distance,
                                    self.cutter_radius, self.plane_of_action_tilt
                                    ).circle_sin_angle(ends)
            if np.max(np.abs(sines)) >= 0.98:
                fail("cutter_radius", self.cutter_radius,
                     f"is too small: the cutter {'circle' if self.trace == 'face_milled' else 'arc'}"
                     f" turns nearly radial within the face width (sin of its angle to the "
                     f"ray {sines[0]:.4g} at the toe, {sines[1]:.4g} at the heel; at most 0.98)")

    @classmethod
    def from_units(cls, **keys) -> "GearPairDesign":
        """A design from keyword arguments in the paper's units, the unit in each name.

        ``GearPairDesign.from_units(module_mm=4.5, spiral_angle_deg=30, trace="circular")``;
        the keys of :data:`CONFIG_KEYS` (as in the configuration's ``design``
        section), the others the paper's Table 1.

        Returns
        -------
        GearPairDesign
        """
        return cls.from_config(keys)

    @classmethod
    def from_config(cls, config: dict) -> "GearPairDesign":
        """Build a design from configuration keys in the paper's units.

        Parameters
        ----------
        config : dict
            Keys as written in the workflow configuration and ``design.json``:
            ``pinion_teeth``, ``gear_teeth``, ``module_mm``, ``shaft_angle_deg``,
            ``normal_pressure_angle_deg``, ``spiral_angle_deg``, ``pinion_hand``,
            ``addendum_mm``, ``dedendum_mm``, ``trace``, ``face_width_mm``,
            ``cutter_radius_mm``, ``base_cone_rule``, ``backlash_mm``,
            ``density_kg_m3``, ``pinion_bore_mm``, ``gear_bore_mm``. Missing
            keys take the paper's values. Unknown keys are an error.

        Returns
        -------
        GearPairDesign
        """
        kwargs = {}
        for key, value in config.items():
            name, scale = _config_key(key)
            if key not in CONFIG_KEYS and key not in depth.TAPER_DEFAULTS:
                raise DesignError(f"{key} = {value!r}: unknown design parameter "
                                  f"(known: {sorted({*CONFIG_KEYS, *depth.TAPER_DEFAULTS})})")
            if key == "dedendum_angles_deg":
                value = depth.angles_from_config(value, DesignError)
            elif scale is not None:
                try:
                    value = scale[0](float(value))
                except (TypeError, ValueError):
                    raise DesignError(f"{key} = {value!r}: must be a number") from None
            kwargs[name] = value
        return cls(**kwargs)

    def to_config(self) -> dict:
        """The design parameters as configuration keys in the paper's units.

        ``GearPairDesign.from_config(design.to_config()) == design`` holds bit
        for bit: a converted value that does not come back to the same float
        (about one angle in twenty) is moved by a few units in the last place.
        Converted once per design (a copy each call).
        """
        return dict(self._config)

    @cached_property
    def _config(self) -> dict:
        out = {}
        for key in (*CONFIG_KEYS, *depth.TAPER_DEFAULTS):
            name, scale = _config_key(key)
            value = getattr(self, name)
            if key in depth.TAPER_DEFAULTS:  # left out at the apex taper (records as they were)
                if self.depth_taper != "apex":
                    out[key] = depth.angles_to_config(value, scale, _exact_inverse)
                continue
            out[key] = _exact_inverse(value, *scale) if scale is not None else value
        return out

    def attrs_difference(self, attrs):
        """The first design key on which a dataset's ``design_*`` attributes differ.

        Parameters
        ----------
        attrs : dict
            A dataset's attributes, the design written as ``design_<key>``
            (:meth:`to_config`'s keys and units).

        Returns
        -------
        tuple or None
            ``(key, stored value, this design's value)``, or None where every
            key agrees (numbers to 1e-12 relative).
        """
        for key, value in self.to_config().items():
            stored = attrs.get(f"design_{key}")
            same = stored is not None and (
                stored == value if isinstance(value, str)
                else np.allclose(np.asarray(stored, float), value, rtol=1e-12) if isinstance(value, list)
                else math.isclose(float(stored), float(value), rel_tol=1e-12))
            if not same:
                return key, stored, value
        return None

    def replace(self, **changes) -> "GearPairDesign":
        """A copy with some parameters changed (SI units), validated again."""
        return dataclasses.replace(self, **changes)

    # --------------------------------------------------------------- derived
    @cached_property
    def teeth(self) -> tuple[int, int]:
        """(z1, z2) [-]."""
        return int(self.pinion_teeth), int(self.gear_teeth)

    @per_member
    def pitch_angle(self, member: int) -> float:
        """Pitch cone angle delta_i of member 1 (pinion) or 2 (gear) [rad].

        tan(delta_1) = sin(Sigma) / (z2/z1 + cos(Sigma)), delta_2 = Sigma - delta_1.
        """
        z1, z2 = self.teeth
        d1 = math.atan2(math.sin(self.shaft_angle), z2 / z1 + math.cos(self.shaft_angle))
        return d1 if member == 1 else self.shaft_angle - d1

    @per_member
    def pitch_diameter(self, member: int) -> float:
        """Outer pitch diameter d_i = m z_i [m]."""
        return self.module * self.teeth[member - 1]

    @cached_property
    def outer_cone_distance(self) -> float:
        """Outer cone distance R_e = d1 / (2 sin delta_1) [m]."""
        return self.pitch_diameter(1) / (2 * math.sin(self.pitch_angle(1)))

    @cached_property
    def mean_cone_distance(self) -> float:
        """Mean cone distance R_m = R_e - b/2 [m]."""
        return self.outer_cone_distance - self.face_width / 2

    @cached_property
    def inner_cone_distance(self) -> float:
        """Inner cone distance R_i = R_e - b [m]."""
        return self.outer_cone_distance - self.face_width

    @cached_property
    def mean_module(self) -> float:
        """Mean transverse module m_m = m R_m / R_e [m]."""
        return self.module * self.mean_cone_distance / self.outer_cone_distance

    @cached_property
    def mean_circular_pitch(self) -> float:
        """Circular pitch on the mean pitch circle, pi m_m [m]."""
        return math.pi * self.mean_module

    @per_member
    def mean_pitch_radius(self, member: int) -> float:
        """Mean pitch radius r_m,i = R_m sin delta_i [m]."""
        return self.mean_cone_distance * math.sin(self.pitch_angle(member))

    @cached_property
    def mean_normal_module(self) -> float:
        """Mean normal module m_mn = m_m cos(beta_m) [m] (ISO 23509's unit of a shift)."""
        return self.mean_module * math.cos(self.spiral_angle)

    def _shift_sign(self, member):
        return 1.0 if member == 1 else -1.0

    @per_member
    def outer_shift(self, member: int) -> float:
        """The profile shift's depth at the outer cone distance, +-x_hm1 m_mn R_e/R_m [m].

        The teeth taper to the apex (their depth is proportional to the cone
        distance), so the shift x_hm1 m_mn at the mean point is
        x_hm1 m_mn R_e / R_m = x_hm1 m cos(beta_m) at the heel.
        """
        return (self._shift_sign(member) * self.profile_shift * self.mean_normal_module
                * self.outer_cone_distance / self.mean_cone_distance)

    @per_member
    def outer_addendum(self, member: int) -> float:
        """Outer addendum of a member, h_a +- the profile shift [m] (other tapers:
        :func:`lsbg.gear.depth.heel_depth`; the mean and toe depths: :mod:`lsbg.gear.depth`)."""
        if self.depth_taper != "apex":
            return depth.heel_depth(self, member, "addendum")
        return self.addendum + self.outer_shift(member)

    @per_member
    def outer_dedendum(self, member: int) -> float:
        """Outer dedendum of a member, h_f -+ the profile shift [m] (other tapers as above)."""
        if self.depth_taper != "apex":
            return depth.heel_depth(self, member, "dedendum")
        return self.dedendum - self.outer_shift(member)

    @per_member
    def mean_tooth_thickness(self, member: int) -> float:
        """Circular tooth thickness on the mean pitch circle [m].

        (pi m_m - j)/2, with the backlash j split between the two members,
        +- 2 m_mn (x_hm1 tan(alpha_n) + x_smn1) / cos(beta_m): the profile shift
        and the thickness modification in the normal section (ISO 23509),
        carried to the transverse circle at the mean point.
        """
        change = (2 * self.mean_normal_module * (self.profile_shift
                                                 * math.tan(self.normal_pressure_angle)
                                                 + self.thickness_modification)
                  / math.cos(self.spiral_angle))
        return (self.mean_circular_pitch - self.backlash) / 2 + self._shift_sign(member) * change

    @per_member
    def mean_normal_tooth_thickness(self, member: int) -> float:
        """Normal tooth thickness at the mean point, s_m cos(beta_m) [m] (ISO 23509's
        s_mn, less half the backlash's normal share)."""
        return self.mean_tooth_thickness(member) * math.cos(self.spiral_angle)

    @cached_property
    def addendum_angle(self) -> float:
        """Addendum angle of the unshifted teeth, atan(h_a / R_e) [rad] (depth tapers
        to the apex); a member's own: :meth:`member_addendum_angle`."""
        return math.atan(self.addendum / self.outer_cone_distance)

    @cached_property
    def dedendum_angle(self) -> float:
        """Dedendum angle of the unshifted teeth, atan(h_f / R_e) [rad]."""
        return math.atan(self.dedendum / self.outer_cone_distance)

    @per_member
    def member_addendum_angle(self, member: int) -> float:
        """Addendum angle theta_a,i = atan(h_a,i / R_e) of a member [rad] (or the taper's)."""
        if self.depth_taper != "apex":
            return depth.addendum_angles(self)[member - 1]
        return math.atan(self.outer_addendum(member) / self.outer_cone_distance)

    @per_member
    def member_dedendum_angle(self, member: int) -> float:
        """Dedendum angle theta_f,i = atan(h_f,i / R_e) of a member [rad] (or the taper's)."""
        if self.depth_taper != "apex":
            return depth.dedendum_angles(self)[member - 1]
        return math.atan(self.outer_dedendum(member) / self.outer_cone_distance)

    @per_member
    def tip_angle(self, member: int) -> float:
        """Face (tip) cone angle delta_a,i = delta_i + theta_a,i [rad]."""
        return self.pitch_angle(member) + self.member_addendum_angle(member)

    @per_member
    def root_angle(self, member: int) -> float:
        """Root cone angle delta_f,i = delta_i - theta_f,i [rad]."""
        return self.pitch_angle(member) - self.member_dedendum_angle(member)

    @cached_property
    def plane_of_action_tilt(self) -> float:
        """Tilt gamma of the plane of action from the pitch-cone tangent plane [rad].

        Both base cones satisfy sin(delta_b,i) = c sin(delta_i) with c = cos(gamma).
        The "involute" rule is the helical-gear relation tan(gamma) =
        tan(alpha_n) / cos(beta_m) (gamma plays the transverse pressure angle);
        the "paper" rule (Eq. 6) is c = sin(beta_m), i.e. gamma = 90 deg - beta_m.
        """
        if self.base_cone_rule == "paper":
            return math.pi / 2 - self.spiral_angle
        return math.atan(math.tan(self.normal_pressure_angle) / math.cos(self.spiral_angle))

    @cached_property
    def base_cone_constant(self) -> float:
        """c = sin(delta_b,i) / sin(delta_i), the same for both members [-]."""
        return math.cos(self.plane_of_action_tilt)

    @per_member
    def base_cone_angle(self, member: int) -> float:
        """Base cone angle delta_b,i = asin(c sin delta_i) [rad]."""
        return math.asin(self.base_cone_constant * math.sin(self.pitch_angle(member)))

    @cached_property
    def plane_spiral_angle(self) -> float:
        """Angle beta_p between the generating curve and the ray at the mean point [rad].

        The flank normal on the pitch line lies in the plane of action, so the
        pitch-cone spiral angle beta obeys tan(beta) = tan(beta_p) / cos(gamma)
        (as the base helix angle of a helical gear); solved here for beta_p
        so that beta = beta_m at the mean point.
        """
        return math.atan(math.tan(self.spiral_angle) * math.cos(self.plane_of_action_tilt))

    @cached_property
    def mean_normal_pressure_angle(self) -> float:
        """Normal pressure angle that the base-cone rule gives at the mean point [rad].

        sin(alpha_n) = cos(beta_p) sin(gamma); equals ``normal_pressure_angle``
        under the "involute" rule.
        """
        return math.asin(math.cos(self.plane_spiral_angle) * math.sin(self.plane_of_action_tilt))

    @cached_property
    def base_pitch_angle(self) -> float:
        """Angular pitch of the contact lines in the plane of action,
        Psi_p = 2 pi sin(delta_b,1) / z1 = 2 pi sin(delta_b,2) / z2 [rad]."""
        return 2 * math.pi * math.sin(self.base_cone_angle(1)) / self.pinion_teeth

    def derived(self) -> dict:
        """Every derived quantity, keys carrying their unit (paper's units).

        Returns
        -------
        dict
            e.g. ``pitch_angle_pinion_deg``, ``outer_cone_distance_mm``,
            ``base_cone_angle_gear_deg``, ``plane_of_action_tilt_deg``.
        """
        out = {}
        for member, name in ((1, "pinion"), (2, "gear")):
            out[f"pitch_angle_{name}_deg"] = math.degrees(self.pitch_angle(member))
            out[f"pitch_diameter_{name}_mm"] = 1e3 * self.pitch_diameter(member)
            out[f"mean_pitch_diameter_{name}_mm"] = 2e3 * self.mean_pitch_radius(member)
            out[f"base_cone_angle_{name}_deg"] = math.degrees(self.base_cone_angle(member))
            out[f"tip_angle_{name}_deg"] = math.degrees(self.tip_angle(member))
            out[f"root_angle_{name}_deg"] = math.degrees(self.root_angle(member))
            out[f"outer_tip_diameter_{name}_mm"] = depth.outer_tip_diameter(self, member, 1e3)
            out[f"mean_tooth_thickness_{name}_mm"] = 1e3 * self.mean_tooth_thickness(member)
            out[f"outer_addendum_{name}_mm"] = 1e3 * self.outer_addendum(member)
            out[f"outer_dedendum_{name}_mm"] = 1e3 * self.outer_dedendum(member)
            out[f"mean_normal_tooth_thickness_{name}_mm"] = (
                1e3 * self.mean_normal_tooth_thickness(member))
        out.update(
            outer_cone_distance_mm=1e3 * self.outer_cone_distance,
            mean_cone_distance_mm=1e3 * self.mean_cone_distance,
            inner_cone_distance_mm=1e3 * self.inner_cone_distance,
            mean_module_mm=1e3 * self.mean_module,
            mean_normal_module_mm=1e3 * self.mean_normal_module,
            addendum_angle_deg=math.degrees(self.addendum_angle),
            dedendum_angle_deg=math.degrees(self.dedendum_angle),
            base_cone_constant=self.base_cone_constant,
            plane_of_action_tilt_deg=math.degrees(self.plane_of_action_tilt),
            plane_spiral_angle_mean_deg=math.degrees(self.plane_spiral_angle),
            normal_pressure_angle_mean_deg=math.degrees(self.mean_normal_pressure_angle),
            base_pitch_angle_deg=math.degrees(self.base_pitch_angle),
            gear_ratio=self.gear_teeth / self.pinion_teeth,
        )
        return out


# Configuration key suffix (paper's units) -> (to SI, from SI).
_SCALES = {
    "_mm": (lambda v: v / 1000.0, lambda v: v * 1000.0),
    "_deg": (math.radians, math.degrees),
    "_kg_m3": (float, float),
}
CONFIG_KEYS = (
    "pinion_teeth", "gear_teeth", "module_mm", "shaft_angle_deg",
    "normal_pressure_angle_deg", "spiral_angle_deg", "pinion_hand", "addendum_mm",
    "dedendum_mm", "trace", "face_width_mm", "cutter_radius_mm", "base_cone_rule",
    "backlash_mm", "density_kg_m3", "pinion_bore_mm", "gear_bore_mm", "profile_shift",
    "thickness_modification", "undercut",
)


def _exact_inverse(value, to_si, from_si):
    """from_si(value), nudged in the last place until to_si gives ``value`` back."""
    guess = from_si(value)
    # Prefer the shortest decimal (30.0 rather than 29.999999999999996).
    candidates = [round(guess, digits) for digits in range(6, 16)] + [guess]
    up = down = guess
    for _ in range(16):
        up, down = math.nextafter(up, math.inf), math.nextafter(down, -math.inf)
        candidates += [up, down]
    return next((c for c in candidates if to_si(c) == value), guess)


def _config_key(key: str):
    for suffix, scale in _SCALES.items():
        if key.endswith(suffix):
            return key[: -len(suffix)], scale
    return key, None

