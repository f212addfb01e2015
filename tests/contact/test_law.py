"""Tests of the contact law (paper Eq. 8–11)."""

import dataclasses
import math

import numpy as np
import pytest

from lsbg.contact import (
    ContactParameters,
    friction_coefficient,
    friction_coefficient_scalar,
    hertz_approach,
    hertz_stiffness,
    impact_force,
    impact_force_scalar,
    implied_correction_coefficient,
    line_load,
    line_load_scalar,
    step,
)
from lsbg.contact.law import friction_integral_scalar

# Paper §3.1 data in SI: outer pitch radii, 45# steel.
R1 = 20.25e-3  # m
R2 = 83.25e-3  # m
E_STEEL = 2.07e11  # Pa (2.07e5 N/mm²)
NU_STEEL = 0.285
MATERIAL = (R1, R2, E_STEEL, E_STEEL, NU_STEEL, NU_STEEL)

# 1 N/mm^1.5 = 1000^1.5 N/m^1.5
N_PER_MM15 = 1000.0**1.5


@pytest.fixture
def params():
    return ContactParameters.paper()


# --- STEP (Eq. 10) -----------------------------------------------------------

def test_step_endpoints_and_saturation():
    x = np.array([-1.0, 2.0, 2.0 + 1e-12, 5.0, 5.0 + 1e-12, 9.0])
    np.testing.assert_allclose(step(x, 2.0, -3.0, 5.0, 7.0),
                               [-3.0, -3.0, -3.0, 7.0, 7.0, 7.0], atol=1e-9)


def test_step_midpoint_is_mean_of_levels():
    # (3 - 2Δ)Δ² = 1/2 at Δ = 1/2
    assert step(3.5, 2.0, -3.0, 5.0, 7.0) == pytest.approx(-3.0 + 10.0 / 2)
    assert step(0.5, 0.0, 0.0, 1.0, 1.0) == pytest.approx(0.5)


def test_step_interior_value():
    # Δ = 0.25: (3 - 0.5) * 0.0625 = 0.15625
    assert step(0.25, 0.0, 1.0, 1.0, 3.0) == pytest.approx(1.0 + 2.0 * 0.15625)


def test_step_is_c1_at_both_ends():
    h = 1e-7
    for x in (0.0, 1.0):
        slope = (step(x + h, 0.0, 0.0, 1.0, 1.0)
                 - step(x - h, 0.0, 0.0, 1.0, 1.0)) / (2 * h)
        assert abs(slope) < 1e-6
    # and the peak slope, 1.5 (h1 - h0) / (x1 - x0), sits at the midpoint
    mid = (step(0.5 + h, 0, 0, 1, 1) - step(0.5 - h, 0, 0, 1, 1)) / (2 * h)
    assert mid == pytest.approx(1.5, rel=1e-6)


def test_step_is_monotonic():
    x = np.linspace(-0.5, 1.5, 2001)
    rising = step(x, 0.0, 0.0, 1.0, 2.0)
    falling = step(x, 0.0, 2.0, 1.0, -1.0)
    assert np.all(np.diff(rising) >= 0.0)
    assert np.all(np.diff(falling) <= 0.0)


def test_step_broadcasts_and_keeps_scalars():
    assert np.shape(step(0.3, 0.0, 0.0, 1.0, 1.0)) == ()
    x1 = np.array([1.0, 2.0, 4.0])
    out = step(np.zeros((2, 3)) + 0.5, 0.0, 0.0, x1, 1.0)
    assert out.shape == (2, 3)
    np.testing.assert_allclose(out[0], [0.5, 0.15625, 0.04296875])


def test_step_rejects_empty_interval():
    with pytest.raises(ValueError, match="x1 > x0"):
        step(0.0, 1.0, 0.0, 1.0, 1.0)


# --- parameters --------------------------------------------------------------

def test_paper_parameters_in_si(params):
    assert params.k == pytest.approx(6.65e7 * N_PER_MM15, rel=1e-12)
    assert params.k == pytest.approx(2.1029146e12, rel=1e-7)
    assert params.e == 1.5
    assert params.c_max == pytest.approx(5e4)
    assert params.d == pytest.approx(1e-4)
    assert (params.mu_s, params.mu_d) == (0.08, 0.05)
    assert params.v_s == pytest.approx(1e-4)
    assert params.v_d == pytest.approx(1e-2)
    assert params == ContactParameters()


def test_from_paper_units_matches_defaults(params):
    converted = ContactParameters.from_paper_units(
        k=6.65e7, e=1.5, c_max=50.0, d=0.1, mu_s=0.08, mu_d=0.05,
        v_s=0.1, v_d=10.0)
    for field in dataclasses.fields(ContactParameters):
        assert getattr(converted, field.name) == pytest.approx(
            getattr(params, field.name), rel=1e-12), field.name


def test_from_paper_units_stiffness_follows_exponent():
    # k [N/m^e] = k [N/mm^e] * 1000^e: for e = 2, a factor 1e6
    p = ContactParameters.from_paper_units(
        k=3.0, e=2.0, c_max=1.0, d=0.1, mu_s=0.1, mu_d=0.1, v_s=0.1, v_d=1.0)
    assert p.k == pytest.approx(3e6)
    # the same force at 1 mm in either unit system
    assert impact_force(1e-3, 0.0, p) == pytest.approx(3.0 * 1.0**2)


def test_parameters_are_frozen_floats(params):
    with pytest.raises(dataclasses.FrozenInstanceError):
        params.k = 1.0
    p = ContactParameters(k=np.float64(1e12), e=np.int64(2))
    assert type(p.k) is float and type(p.e) is float


def test_to_dict_has_unit_carrying_keys(params):
    d = params.to_dict()
    assert d == {
        "contact_stiffness_N_per_m_e": params.k,
        "contact_force_exponent": 1.5,
        "contact_damping_N_s_per_m": 5e4,
        "penetration_depth_m": params.d,
        "static_friction_coefficient": 0.08,
        "dynamic_friction_coefficient": 0.05,
        "stiction_transition_velocity_m_per_s": params.v_s,
        "friction_transition_velocity_m_per_s": params.v_d,
        "model": "point",
        "line_stiffness_N_per_m2": 19.4e9,
        "mesh_damping_ratio": 0.05,
        "slices": 20,
        "line_approach_limit_m": 5e-4,
        "compliance": "uniform",
    }
    assert all(type(v) in (float, int, str) for v in d.values())
    # and back, also through the workflow's configuration keys
    assert ContactParameters.from_dict(d) == params
    line = params.replace(model="line", slices=37, damping_ratio=0.1)
    assert ContactParameters.from_dict(line.to_dict()) == line
    assert ContactParameters.from_config(line.to_config()) == line


@pytest.mark.parametrize("field, value", [
    ("k", 0.0), ("k", -1.0), ("k", float("nan")),
    ("e", 0.9),
    ("c_max", -1.0),
    ("d", 0.0), ("d", -1e-4),
    ("mu_s", -0.1), ("mu_s", 1.5),
    ("mu_d", -0.01), ("mu_d", 1.01),
    ("v_s", 0.0), ("v_s", -1e-4),
    ("v_d", 1e-4), ("v_d", 5e-5),
    ("model", "lines"), ("line_stiffness", 0.0), ("line_stiffness", -1e9),
    ("damping_ratio", -0.01), ("damping_ratio", float("nan")), ("slices", 1),
    ("slices", 2.5), ("approach_limit", 0.0),
])
def test_validation_names_field_and_value(field, value):
    with pytest.raises(ValueError, match=rf"{field}.*{field}={value!r}"):
        ContactParameters(**{field: value})


@pytest.mark.parametrize("key, value", [
    ("slices", 1), ("slices", 0), ("mesh_damping_ratio", -0.1), ("line_stiffness_N_per_mm_um", -3),
    ("line_stiffness_N_per_mm_um", 0), ("model", "spline"), ("line_approach_limit_mm", -1),
])
def test_config_errors_name_the_key_in_paper_units(key, value):
    with pytest.raises(ValueError, match=rf"^contact\.{key} = {value!r}: "):
        ContactParameters.from_config({key: value})


def test_config_reads_paper_units():
    p = ContactParameters.from_config({"model": "line", "line_stiffness_N_per_mm_um": 14.0,
                                       "slices": 12, "line_approach_limit_mm": 0.2,
                                       "stiffness_N_per_mm1_5": 3.0, "exponent": 2.0})
    assert p.model == "line" and p.slices == 12 and type(p.slices) is int
    assert p.line_stiffness == pytest.approx(14e9)  # N/(mm um) -> N/m^2
    assert p.approach_limit == pytest.approx(2e-4)
    assert p.k == pytest.approx(3e6)  # N/mm^2 -> N/m^2 with the configured exponent


def test_v_s_not_below_v_d_is_rejected():
    with pytest.raises(ValueError, match="v_d"):
        ContactParameters(v_s=0.02, v_d=0.01)


def test_zero_damping_and_friction_are_valid():
    p = ContactParameters(c_max=0.0, mu_s=0.0, mu_d=0.0)
    assert impact_force(1e-5, -10.0, p) == pytest.approx(p.k * 1e-5**1.5)


# --- normal force (Eq. 8) ----------------------------------------------------

def test_force_is_zero_without_penetration(params):
    x = np.array([-1e-3, -1e-9, 0.0])
    np.testing.assert_array_equal(impact_force(x, 5.0, params), 0.0)
    np.testing.assert_array_equal(impact_force(x, -5.0, params), 0.0)


def test_elastic_term_without_rate(params):
    x = np.array([1e-6, 5e-6, 1e-4, 3e-4])
    np.testing.assert_allclose(impact_force(x, 0.0, params), params.k * x**1.5,
                               rtol=1e-14)
    # 5 µm, the penetration under the paper's load: about 23.5 kN
    assert impact_force(5e-6, 0.0, params) == pytest.approx(23511.30, abs=0.01)


def test_damping_weight_ramps_to_c_max(params):
    rate = 0.02  # m/s
    d = params.d
    for x, weight in [(d / 2, params.c_max / 2), (d, params.c_max),
                      (3 * d, params.c_max), (d / 4, params.c_max * 0.15625)]:
        damping = impact_force(x, rate, params) - impact_force(x, 0.0, params)
        assert damping == pytest.approx(weight * rate, rel=1e-6)


def test_force_never_negative_when_separating_fast(params):
    x = np.array([1e-7, 5e-6, params.d / 2, params.d, 2 * params.d])
    rate = -1e3  # m/s, enough to overwhelm the elastic term everywhere
    assert np.all(params.k * x**1.5 + step(x, 0, 0, params.d, params.c_max)
                  * rate < 0.0)
    np.testing.assert_array_equal(impact_force(x, rate, params), 0.0)


def test_force_broadcasts_and_keeps_scalars(params):
    assert np.shape(impact_force(1e-6, 0.0, params)) == ()
    out = impact_force(np.array([[1e-6], [2e-6]]), np.array([0.0, 0.1, -0.1]),
                       params)
    assert out.shape == (2, 3)


def test_force_propagates_nan(params):
    assert math.isnan(impact_force(float("nan"), 0.0, params))
    assert math.isnan(impact_force(1e-6, float("nan"), params))


# --- friction coefficient ----------------------------------------------------

def test_friction_coefficient_key_values(params):
    v = np.array([0.0, params.v_s / 2, params.v_s, params.v_d, 2 * params.v_d,
                  10.0])
    np.testing.assert_allclose(
        friction_coefficient(v, params),
        [0.0, 0.04, 0.08, 0.05, 0.05, 0.05], atol=1e-15)
    # halfway between v_s and v_d: mean of mu_s and mu_d
    mid = (params.v_s + params.v_d) / 2
    assert friction_coefficient(mid, params) == pytest.approx(0.065)


def test_friction_coefficient_is_even_in_v(params):
    v = np.linspace(0.0, 2 * params.v_d, 101)
    np.testing.assert_array_equal(friction_coefficient(-v, params),
                                  friction_coefficient(v, params))


def test_friction_coefficient_is_continuous(params):
    eps = 1e-12
    for v in (params.v_s, params.v_d):
        below = friction_coefficient(v * (1 - eps), params)
        above = friction_coefficient(v * (1 + eps), params)
        assert below == pytest.approx(above, abs=1e-9)
    # no jump anywhere: increments bounded by the steepest STEP slope,
    # 1.5 mu_s / v_s, times the grid spacing
    v, dv = np.linspace(0.0, 1.5 * params.v_d, 200001, retstep=True)
    max_slope = 1.5 * params.mu_s / params.v_s
    assert np.max(np.abs(np.diff(friction_coefficient(v, params)))) <= (
        max_slope * dv * (1 + 1e-9))


def test_friction_coefficient_bounds(params):
    v = np.linspace(-1.0, 1.0, 10001)
    mu = friction_coefficient(v, params)
    assert mu.min() >= 0.0 and mu.max() <= params.mu_s


# --- scalar twins ------------------------------------------------------------

def _force_grid(p):
    xs = [-1e-3, -1e-12, 0.0, 1e-12, 1e-6, 5e-6, p.d / 2, p.d * (1 - 1e-12),
          p.d, p.d * (1 + 1e-12), 2 * p.d, 1e-3]
    rates = [-1e4, -1.0, -1e-3, 0.0, 1e-3, 1.0, 1e4]
    return [(x, r) for x in xs for r in rates]


@pytest.mark.parametrize("p", [
    ContactParameters.paper(),
    ContactParameters(k=3e9, e=1.0, c_max=1e3, d=2e-5),
    ContactParameters(k=1e14, e=2.2, c_max=0.0, d=1e-3),
])
def test_scalar_force_agrees_with_vector(p):
    grid = _force_grid(p)
    x = np.array([g[0] for g in grid])
    rate = np.array([g[1] for g in grid])
    vector = impact_force(x, rate, p)
    scalar = [impact_force_scalar(a, b, p.k, p.e, p.c_max, p.d) for a, b in grid]
    np.testing.assert_allclose(scalar, vector, rtol=1e-14, atol=0.0)
    assert all(type(f) is float for f in scalar)
    # the grid reaches every regime, including the clip when there is damping
    assert np.any(vector == 0.0) and np.any(vector > 0.0)
    assert np.any((x > 0) & (vector == 0.0)) == (p.c_max > 0)


def test_scalar_force_propagates_nan(params):
    law = (params.k, params.e, params.c_max, params.d)
    assert math.isnan(impact_force_scalar(float("nan"), 0.0, *law))
    assert math.isnan(impact_force_scalar(1e-6, float("nan"), *law))


def test_scalar_friction_agrees_with_vector(params):
    p = params
    v = np.array([0.0, 1e-9, p.v_s / 3, p.v_s * (1 - 1e-12), p.v_s,
                  p.v_s * (1 + 1e-12), (p.v_s + p.v_d) / 2, p.v_d, 3 * p.v_d,
                  50.0])
    v = np.concatenate([v, -v])
    law = (p.mu_s, p.mu_d, p.v_s, p.v_d)
    scalar = [friction_coefficient_scalar(float(s), *law) for s in v]
    np.testing.assert_allclose(scalar, friction_coefficient(v, p),
                               rtol=1e-14, atol=0.0)
    assert all(type(m) is float for m in scalar)
    assert math.isnan(friction_coefficient_scalar(float("nan"), *law))


@pytest.mark.parametrize("rate", [1e-3, 0.05, 2.0, 40.0])
def test_friction_integral_matches_quadrature(params, rate):
    """The closed-form integral of mu over a linearly growing sliding speed."""
    from scipy.integrate import quad

    p = params
    law = (p.mu_s, p.mu_d, p.v_s, p.v_d)
    for x in (0.3 * p.v_s / rate, p.v_s / rate, 0.5 * (p.v_s + p.v_d) / rate, p.v_d / rate,
              5 * p.v_d / rate):
        expected, _ = quad(lambda u: float(friction_coefficient(rate * u, p)), 0.0, x,
                           points=[p.v_s / rate, p.v_d / rate], epsabs=0.0, epsrel=1e-12,
                           limit=200)
        assert friction_integral_scalar(x, rate, *law) == pytest.approx(expected, rel=1e-9)
    # far from the stiction zone the mean coefficient is mu_d
    x = 1e4 * p.v_d / rate
    assert friction_integral_scalar(x, rate, *law) / x == pytest.approx(p.mu_d, rel=1e-3)


def test_line_load_is_a_clipped_linear_law():
    x = np.array([-1e-6, 0.0, 1e-6, 2e-6, 2e-6])
    rate = np.array([0.0, 1.0, 0.0, 0.0, -1e3])
    expected = [0.0, 0.0, 2e10 * 1e-6, 2e10 * 2e-6, 0.0]  # the last would pull: clipped
    np.testing.assert_allclose(line_load(x, rate, 2e10, 1e5), expected, rtol=1e-15)
    scalar = [line_load_scalar(a, b, 2e10, 1e5) for a, b in zip(x, rate)]
    np.testing.assert_allclose(scalar, expected, rtol=1e-15)
    # linear in the approach, damping proportional to the rate
    assert line_load(3e-6, 0.0, 2e10, 1e5) == pytest.approx(3 * line_load(1e-6, 0.0, 2e10, 1e5))
    assert line_load(1e-6, 0.1, 2e10, 1e5) - line_load(1e-6, 0.0, 2e10, 1e5) == pytest.approx(1e4)


# --- Hertz (Eq. 9 and 11) ----------------------------------------------------

def test_hertz_stiffness_paper_data():
    k = hertz_stiffness(*MATERIAL)
    # 6.06e5 N/mm^1.5 per unit correction coefficient (DESIGN.md §4)
    assert k / N_PER_MM15 == pytest.approx(6.0618e5, rel=1e-4)
    # the same number from the paper's units (mm, N/mm²): N/mm^1.5
    k_mm = hertz_stiffness(20.25, 83.25, 2.07e5, 2.07e5, 0.285, 0.285)
    assert k_mm == pytest.approx(k / N_PER_MM15, rel=1e-12)
    # dimensional check: k = 4/3 sqrt(R*) E*
    r_star = R1 * R2 / (R1 + R2)
    e_star = E_STEEL / (2 * (1 - NU_STEEL**2))
    assert k == pytest.approx(4 / 3 * math.sqrt(r_star) * e_star, rel=1e-14)
    k_110 = hertz_stiffness(*MATERIAL, correction=110.0)
    assert k_110 == pytest.approx(110 * k)


def test_paper_stiffness_implies_correction_of_110(params):
    rho = implied_correction_coefficient(params.k, *MATERIAL)
    assert rho == pytest.approx(109.70, abs=0.01)
    assert round(float(rho)) == 110
    k = hertz_stiffness(*MATERIAL, correction=rho)
    assert k == pytest.approx(params.k)


def test_hertz_stiffness_dissimilar_materials():
    # steel on aluminium, 1/E* = (1 - ν1²)/E1 + (1 - ν2²)/E2
    k = hertz_stiffness(0.01, 0.03, 2.1e11, 7.0e10, 0.3, 0.33)
    e_star = 1 / ((1 - 0.3**2) / 2.1e11 + (1 - 0.33**2) / 7.0e10)
    assert k == pytest.approx(4 / 3 * math.sqrt(0.0075) * e_star, rel=1e-14)


@pytest.mark.parametrize("rho", [1.0, 109.7])
def test_hertz_approach_inverts_stiffness(rho):
    force = np.array([0.0, 1.0, 1e3, 23603.48, 1e6])
    x = hertz_approach(force, *MATERIAL, correction=rho)
    k = hertz_stiffness(*MATERIAL, correction=rho)
    np.testing.assert_allclose(k * x**1.5, force, rtol=1e-12)
    # Eq. (11) as printed in the paper
    (r1, r2, e1, e2, nu1, nu2) = MATERIAL
    printed = np.cbrt(9 * force**2 * (r1 + r2)
                      * (e1 * (1 - nu2**2) + e2 * (1 - nu1**2))**2
                      / (16 * r1 * r2 * rho**2 * e1**2 * e2**2))
    np.testing.assert_allclose(x, printed, rtol=1e-12)


def test_hertz_approach_paper_load(params):
    # 23603.48 N with the paper's k (ρ ≈ 110): about 5 µm, as DESIGN.md §3 says
    rho = implied_correction_coefficient(params.k, *MATERIAL)
    x = hertz_approach(23603.48, *MATERIAL, correction=rho)
    assert x == pytest.approx((23603.48 / params.k) ** (2 / 3), rel=1e-12)
    assert x == pytest.approx(5.013e-6, rel=1e-3)


def test_hertz_approach_rejects_pull():
    with pytest.raises(ValueError, match="force"):
        hertz_approach([1.0, -1.0], *MATERIAL)


# ---------------------------------------------------------------------------
# Contact kernel: tooth-pair forces from the exact geometry
# ---------------------------------------------------------------------------
import pytest  # noqa: E402
from scipy.optimize import least_squares  # noqa: E402

from lsbg.contact import MeshContact  # noqa: E402
from lsbg.gear.design import GearPairDesign  # noqa: E402
from lsbg.gear.geometry import GearPair  # noqa: E402
from lsbg.gear.vectors import rotate  # noqa: E402

LOAD = 1964.99


@pytest.fixture(scope="module", params=["logarithmic", "circular"])
def kernel(request):
    return MeshContact(GearPair(GearPairDesign(trace=request.param)))


def _normal_line_hit(pair, member, side, rotation, origin, direction, rho0):
    """Where the line origin + s direction pierces the member's flank (any tooth).

    Brute force on the flank surfaces themselves: solve
    flank(R, theta) rotated by the member's rotation + 2 pi j / z = origin + s direction
    for every tooth j, and keep the hit nearest the origin.
    """
    z = pair.design.teeth[member - 1]
    u = pair.rotation_axis[member]
    lo, hi = pair.flank_polar_range(member)
    # the tooth whose flank lies nearest in azimuth, and its neighbours
    body0, _ = pair.flank(member, side, rho0, math.acos(origin @ pair.axis[member] / (origin @ origin) ** 0.5))
    offset = (pair.azimuth(member, origin) - pair.azimuth(member, body0) - rotation) / (2 * math.pi / z)
    best = None
    for j in (round(offset) - 1, round(offset), round(offset) + 1):
        turn = rotation + 2 * math.pi * j / z

        def residual(v):
            p, _ = pair.flank(member, side, v[0], v[1])
            return rotate(p, u, turn) - (origin + v[2] * direction)

        polar0 = math.acos(origin @ pair.axis[member] / (origin @ origin) ** 0.5)
        fit = least_squares(residual, [rho0, polar0, 0.0], xtol=1e-15, ftol=1e-15, gtol=1e-15,
                            x_scale=[1e-3, 1e-2, 1e-6])
        # the deepest point may sit on the tip edge, and the line through it
        # pierces the flank slightly beyond
        if fit.cost < 1e-24 and lo - 1e-3 <= fit.x[1] <= hi + 1e-3 and (best is None or abs(fit.x[2]) < abs(best[0])):
            _, n = pair.flank(member, side, fit.x[0], fit.x[1])
            best = (fit.x[2], rotate(n, u, turn))
    return best


@pytest.mark.parametrize("mismatch", [2e-6, 4e-5])
def test_kernel_matches_brute_force_flank_surfaces(kernel, mismatch):
    """Normal approach and direction of every pair agree with closest points of
    the rotated flank surfaces."""
    pair = kernel.pair
    for pinion_angle in (0.013, 0.21):
        gear_angle = (pinion_angle * kernel.e1 - mismatch) / kernel.e2
        details = kernel.pair_contacts(pinion_angle, gear_angle)
        assert len(details) >= 2
        for pc in details:
            plane = pair.planes[pc.side]
            rho = pc.cone_distance
            point = plane.point(rho, pc.phase + plane.curve.polar_angle(rho))
            normal = plane.in_plane_normal(rho, pc.phase + plane.curve.polar_angle(rho))
            s1, n1 = _normal_line_hit(pair, 1, pc.side, pinion_angle, point, normal, rho)
            s2, n2 = _normal_line_hit(pair, 2, pc.side, gear_angle, point, normal, rho)
            approach = s1 - s2  # pinion flank beyond the gear flank along pinion -> gear
            assert approach == pytest.approx(pc.penetration, rel=2e-3, abs=1e-11)
            # the flank normals are the contact normal (outward: pinion along n)
            assert abs(n1 @ normal) == pytest.approx(1.0, abs=1e-8)
            assert abs(n2 @ normal) == pytest.approx(1.0, abs=1e-8)


def test_static_preload_carries_the_load(kernel):
    gear_angle = kernel.static_gear_angle(LOAD)
    torque, pinion_torque, deepest, *_ = kernel.forces(0.0, gear_angle)
    assert torque == pytest.approx(LOAD, rel=1e-9)
    # without friction the torques on the two members are in the ratio z1/z2
    assert -pinion_torque / torque == pytest.approx(9 / 37, rel=1e-12)
    # the approach is a few micrometres (Hertz with the paper's k)
    assert 1e-6 < deepest < 6e-6


@pytest.mark.parametrize("load", [1.0, LOAD, 4 * LOAD])
@pytest.mark.parametrize("pinion_angle", [0.0, 0.13, 0.41])
def test_static_gear_angle_matches_an_independent_root_finder(kernel, load, pinion_angle):
    from scipy.optimize import brentq

    base = pinion_angle * kernel.e1 / kernel.e2

    def residual(eps):
        return kernel.forces(pinion_angle, base - eps / kernel.e2).gear_torque - load

    eps = brentq(residual, 0.0, 1e-3, xtol=1e-18, rtol=1e-14)
    got = (base - kernel.static_gear_angle(load, pinion_angle)) * kernel.e2
    assert got == pytest.approx(eps, rel=1e-9)


def test_static_gear_angle_names_an_impossible_load(kernel):
    with pytest.raises(ValueError, match="load_torque = 1000000000000000.0: the contact cannot carry it"):
        kernel.static_gear_angle(1e15)


def test_no_force_with_clearance_and_backlash(kernel):
    # pinion behind by less than the backlash: neither side touches
    gap = kernel.pair.design.backlash * kernel.pair.design.base_cone_constant / kernel.pair.design.mean_cone_distance
    eps = -0.5 * gap
    torque, _, deepest, *_ = kernel.forces(0.0, -eps / kernel.e2)
    assert torque == 0.0 and deepest < 0
    # behind by more than the backlash: coast flanks push the gear backwards
    eps = -1.2 * gap
    torque = kernel.forces(0.0, -eps / kernel.e2).gear_torque
    details = kernel.pair_contacts(0.0, -eps / kernel.e2)
    assert torque < 0 and {p.side for p in details} == {"coast"}


def test_force_never_negative_and_friction_opposes_sliding(kernel):
    w1 = math.radians(7703.0)
    gear_angle = kernel.static_gear_angle(LOAD)
    for w2 in (w1 * 9 / 37 * 1.01, w1 * 9 / 37 * 0.99):
        details = kernel.pair_contacts(0.1, gear_angle + 0.1 * 9 / 37, w1, w2)
        for pc in details:
            assert pc.normal_force >= 0
            assert pc.friction_coefficient == pytest.approx(0.05) or pc.sliding_speed < 0.01
    # separating fast: the damping term would pull, the law clips it to zero
    details = kernel.pair_contacts(0.1, gear_angle + 0.1 * 9 / 37, 0.0, 1e4)
    assert details
    assert all(pc.normal_force == 0.0 for pc in details)


@pytest.mark.parametrize("pinion_speed", [math.radians(7703.0), -1e3, 1e9])
def test_the_table_prefetch_leaves_the_forces_alone(kernel, pinion_speed):
    """The point model prefetches the phase table's rows the contact lines
    will reach (kernels._prefetch_rows): however fast they turn, the normal
    force at a state is the one at rest (the gear keeps pace, no approach
    rate), and a NaN speed gives NaN, not a crash or a hang."""
    gear_angle = kernel.static_gear_angle(LOAD, 0.1)
    at_rest = kernel.forces(0.1, gear_angle)
    gear_speed = pinion_speed * kernel.e1 / kernel.e2
    moving = kernel.forces(0.1, gear_angle, pinion_speed, gear_speed)
    assert moving.normal_force == pytest.approx(at_rest.normal_force, rel=1e-6)
    assert moving.max_penetration == at_rest.max_penetration
    assert moving.pairs == at_rest.pairs
    assert math.isnan(kernel.forces(0.1, gear_angle, float("nan"), 0.0).normal_force)
