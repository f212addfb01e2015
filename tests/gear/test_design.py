"""Design parameters and closed-form bevel gear quantities (paper Table 1)."""

import functools
import math

import pytest

from lsbg.gear.design import DesignError, GearPairDesign


@pytest.fixture(scope="module")
def paper():
    return GearPairDesign()


def test_pitch_angles_match_closed_form(paper):
    # tan(delta_1) = sin(Sigma) / (z2/z1 + cos(Sigma)); for Sigma = 90 deg: atan(9/37).
    assert math.degrees(paper.pitch_angle(1)) == pytest.approx(13.6713, abs=5e-5)
    assert math.degrees(paper.pitch_angle(2)) == pytest.approx(76.3287, abs=5e-5)
    assert paper.pitch_angle(1) == pytest.approx(math.atan(9 / 37), rel=1e-14)


def test_cone_distances_and_pitch_diameters(paper):
    assert paper.outer_cone_distance * 1e3 == pytest.approx(85.677, abs=5e-4)
    # R_e = sqrt(d1^2 + d2^2) / 2 for a right-angle pair.
    assert paper.outer_cone_distance == pytest.approx(math.hypot(40.5e-3, 166.5e-3) / 2, rel=1e-13)
    assert paper.pitch_diameter(1) == pytest.approx(40.5e-3)
    assert paper.pitch_diameter(2) == pytest.approx(166.5e-3)
    assert paper.mean_cone_distance == pytest.approx(paper.outer_cone_distance - 12.5e-3)


def test_base_cones_share_one_constant(paper):
    c = paper.base_cone_constant
    for member in (1, 2):
        assert math.sin(paper.base_cone_angle(member)) == pytest.approx(c * math.sin(paper.pitch_angle(member)))
    # Contact lines repeat with the same pitch on both members.
    assert 2 * math.pi * math.sin(paper.base_cone_angle(2)) / 37 == pytest.approx(paper.base_pitch_angle)


def test_involute_rule_is_the_helical_gear_relation(paper):
    # gamma plays the transverse pressure angle and beta_p the base helix angle:
    # tan(alpha_t) = tan(alpha_n)/cos(beta), sin(beta_b) = sin(beta) cos(alpha_n).
    an, b = math.radians(20), math.radians(35)
    assert paper.plane_of_action_tilt == pytest.approx(math.atan(math.tan(an) / math.cos(b)))
    assert paper.plane_spiral_angle == pytest.approx(math.asin(math.sin(b) * math.cos(an)))
    assert math.degrees(paper.mean_normal_pressure_angle) == pytest.approx(20.0, abs=1e-12)


def test_paper_base_cone_rule_is_eq6():
    d = GearPairDesign.__new__(GearPairDesign)  # skip validation: only the closed forms
    object.__setattr__(d, "base_cone_rule", "paper")
    for name in ("pinion_teeth", "gear_teeth", "shaft_angle", "spiral_angle", "normal_pressure_angle"):
        object.__setattr__(d, name, getattr(GearPairDesign, name))
    for member in (1, 2):
        assert math.sin(d.base_cone_angle(member)) == pytest.approx(
            math.sin(d.spiral_angle) * math.sin(d.pitch_angle(member)))
    # Effective pressure angle at the mean point is far above 20 deg.
    assert math.degrees(d.mean_normal_pressure_angle) > 45


def test_config_round_trip_in_paper_units(paper):
    cfg = paper.to_config()
    assert cfg["module_mm"] == pytest.approx(4.5)
    assert cfg["spiral_angle_deg"] == pytest.approx(35)
    assert GearPairDesign.from_config(cfg) == paper
    assert GearPairDesign.from_config({"spiral_angle_deg": 40}).spiral_angle == pytest.approx(math.radians(40))


@pytest.mark.parametrize("changes, key", [
    (dict(module=0.0), "module"),
    (dict(module=-1e-3), "module"),
    (dict(pinion_teeth=0), "pinion_teeth"),
    (dict(gear_teeth=-3), "gear_teeth"),
    (dict(pinion_teeth=9.5), "pinion_teeth"),
    (dict(pinion_teeth=40), "pinion_teeth"),
    (dict(spiral_angle=0.0), "spiral_angle"),
    (dict(spiral_angle=math.radians(61)), "spiral_angle"),
    (dict(face_width=45e-3), "face_width"),
    (dict(addendum=6e-3), "addendum"),
    (dict(dedendum=3.0e-3), "dedendum"),
    (dict(dedendum=8e-3), "dedendum"),
    (dict(trace="helical"), "trace"),
    (dict(base_cone_rule="other"), "base_cone_rule"),
    (dict(pinion_hand="up"), "pinion_hand"),
    (dict(backlash=-1e-4), "backlash"),
    (dict(gear_bore=0.2), "gear_bore"),
    (dict(trace="circular", cutter_radius=10e-3), "cutter_radius"),
])
def test_invalid_parameters_are_named(changes, key):
    with pytest.raises(DesignError, match=rf"^{key} = "):
        GearPairDesign(**changes)


def test_unknown_or_non_numeric_config_keys_are_named():
    with pytest.raises(DesignError, match="module = "):
        GearPairDesign.from_config({"module": 4.5})  # a length without its unit
    with pytest.raises(DesignError, match="spiral_angle_deg = 'steep'"):
        GearPairDesign.from_config({"spiral_angle_deg": "steep"})


@pytest.mark.parametrize("angle", [36.2, 25.1, 44.7, 17.3, 59.9])
def test_config_round_trip_is_exact_for_awkward_angles(angle):
    design = GearPairDesign.from_config({"spiral_angle_deg": angle, "normal_pressure_angle_deg": 22.3})
    assert GearPairDesign.from_config(design.to_config()) == design


@pytest.mark.parametrize("field, value, hint", [
    ("module", 4.5, "4.5 mm is 0.0045 m"), ("face_width", 25, "from_units(face_width_mm=25)"),
    ("cutter_radius", 76.2, "0.0762 m"), ("density", 7.85, "kg/m^3"),
    ("spiral_angle", 35, "math.radians(35)"), ("normal_pressure_angle", 20, "radians")])
def test_values_in_paper_units_are_refused_with_the_conversion(field, value, hint):
    """SI inside: GearPairDesign(module=4.5) is a 4.5-metre module, refused with its cure."""
    with pytest.raises(DesignError, match=rf"^{field} = {value}: ") as error:
        GearPairDesign(**{field: value})
    assert hint in str(error.value)


def test_from_units_takes_the_paper_units():
    assert GearPairDesign.from_units(module_mm=4.5, spiral_angle_deg=35) == GearPairDesign()
    design = GearPairDesign.from_units(face_width_mm=30, trace="circular")
    assert design.face_width == pytest.approx(0.030) and design.trace == "circular"


def test_derived_quantities_are_memoised_bit_for_bit():
    design = GearPairDesign.from_units(module_mm=4.5, spiral_angle_deg=30, trace="circular",
                                       profile_shift=0.3)
    first = design.derived()
    assert design.derived() == first
    cls = type(design)
    properties = [name for name, attribute in vars(cls).items()
                  if isinstance(attribute, functools.cached_property)]
    assert {"outer_cone_distance", "base_pitch_angle", "teeth"} <= set(properties)
    for name in properties:
        assert getattr(design, name) == vars(cls)[name].func(design), name
    for name in ("pitch_angle", "pitch_diameter", "mean_pitch_radius", "outer_shift",
                 "outer_addendum", "outer_dedendum", "mean_tooth_thickness",
                 "mean_normal_tooth_thickness", "member_addendum_angle",
                 "member_dedendum_angle", "tip_angle", "root_angle", "base_cone_angle"):
        for member in (1, 2):
            value = getattr(design, name)(member)
            assert f"_{name}_memo" in vars(design), name
            computed = getattr(cls, name).__wrapped__(design, member)
            assert float(value).hex() == float(computed).hex(), (name, member)
    config = design.to_config()
    config["module_mm"] = 1.0  # a copy: the memo keeps the design's
    assert design.to_config()["module_mm"] == 4.5
    assert GearPairDesign.from_config(design.to_config()) == design


def test_a_depth_taper_refuses_no_dedendum_at_the_toe_naming_its_key():
    from lsbg.gear.depth import toe_depth

    with pytest.raises(DesignError, match=r"^dedendum_angles = .*: leaves the pinion no "
                                          r"dedendum at the toe \(dedendum -"):
        GearPairDesign.from_units(depth_taper="given_dedendum_angles", dedendum_angles_deg=[18, 2])
    # a uniform depth keeps the mean depths at the toe and heel
    uniform = GearPairDesign(depth_taper="uniform")
    for member in (1, 2):
        assert uniform.outer_dedendum(member) == toe_depth(uniform, member, "dedendum") == \
            pytest.approx(GearPairDesign().outer_dedendum(member) * uniform.mean_cone_distance
                          / uniform.outer_cone_distance, rel=1e-12)
    with pytest.raises(DesignError, match=r"^dedendum_angles = None: must be the two"):
        GearPairDesign(depth_taper="given_dedendum_angles")
    with pytest.raises(DesignError, match=r"^depth_taper = 'parallel': must be one of"):
        GearPairDesign(depth_taper="parallel")
    with pytest.raises(DesignError, match=r"^dedendum_angles_deg = \['a', 2\]: must be two"):
        GearPairDesign.from_units(depth_taper="given_dedendum_angles", dedendum_angles_deg=["a", 2])


@pytest.mark.parametrize("angles, member", [([0, -4], "pinion"), ([-12, 0], "gear")])
def test_a_depth_taper_that_points_the_teeth_is_refused_naming_its_key(angles, member):
    from lsbg.gear.geometry import GearPair

    design = GearPairDesign.from_units(depth_taper="given_dedendum_angles",
                                       dedendum_angles_deg=angles)
    with pytest.raises(DesignError, match=rf"^dedendum_angles = .*: the {member} teeth come "
                                          r"out pointed \(top land -"):
        GearPair(design)
