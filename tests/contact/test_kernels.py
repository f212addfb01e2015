"""The line contact model: sliced contact lines against the continuous field, the
standard's mesh stiffness, gradual load take-up, energy balance and the mesh mode's damping."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from lsbg.contact import ContactParameters, MeshContact, calibrated_line_stiffness
from lsbg.contact import kernels
from lsbg.gear.design import GearPairDesign
from lsbg.dynamics.compiled_engine import PRESCRIBED, integrate, tableau
from lsbg.gear.geometry import GearPair

LOAD = 1964.99
GEAR_INERTIA = 0.0159  # about the paper's gear [kg m^2]
LINE = ContactParameters(model="line")


@pytest.fixture(scope="module", params=["logarithmic", "circular"])
def pair(request):
    return GearPair(GearPairDesign(trace=request.param))


def field_torque(pair, contact, pinion_angle, eps):
    """Gear torque of the continuous line law: k_l eps e2 sum over the lines of the
    integral of rho^2 cos(beta_p) over each line's part inside the field (quadrature on
    the generating curve, no slices)."""
    plane = pair.planes["drive"]
    first, last = contact._line_range(plane)
    base = contact.orientation * pinion_angle * contact.e1  # the pinion's line
    base += math.ceil((first - base) / contact.pitch) * contact.pitch
    total = 0.0
    for phase in np.arange(base, last + 1e-12, contact.pitch):
        lo, hi = plane.line_segment(phase)
        if hi > lo:
            total += quad(lambda rho: rho**2 * math.cos(float(plane.curve.ray_angle(rho))),
                          float(lo), float(hi), epsabs=0.0, epsrel=1e-12)[0]
    return contact.params.line_stiffness * eps * contact.e2 * total


@pytest.mark.parametrize("slices, tolerance", [(20, 2e-3), (160, 4e-5)])
def test_sliced_torque_converges_to_the_continuous_line_law(pair, slices, tolerance):
    contact = MeshContact(pair, LINE.replace(slices=slices, mu_s=0.0, mu_d=0.0))
    eps = 8e-4
    for pinion_angle in np.linspace(0.0, 2 * math.pi / 9, 11):
        gear_angle = (pinion_angle * contact.e1 - eps) / contact.e2
        torque = contact.forces(pinion_angle, gear_angle).gear_torque
        assert torque == pytest.approx(field_torque(pair, contact, pinion_angle, eps),
                                       rel=tolerance)


def test_mean_mesh_stiffness_is_its_closed_form(pair):
    contact = MeshContact(pair, LINE.replace(mu_s=0.0, mu_d=0.0))
    eps, h = 8e-4, 1e-7
    stiffness = []
    for pinion_angle in np.linspace(0.0, 2 * math.pi / 9, 400, endpoint=False):
        plus = contact.forces(pinion_angle, (pinion_angle * contact.e1 - eps - h) / contact.e2)
        minus = contact.forces(pinion_angle, (pinion_angle * contact.e1 - eps + h) / contact.e2)
        # dT2/dphi2 = e2 dT2/deps
        stiffness.append((plus.gear_torque - minus.gear_torque) / (2 * h) * contact.e2)
    assert np.mean(stiffness) == pytest.approx(contact.mean_torsional_stiffness(), rel=2e-4)
    # mesh stiffness along the line of action at the mean point, per unit face width
    c_gamma = contact.mean_mesh_stiffness() / pair.design.face_width
    assert 5e9 < c_gamma < 40e9


def test_default_line_stiffness_is_calibrated_to_iso_6336():
    """ISO 6336-1 c_gamma = 20 N/(mm um) at the paper's LSBG (the default's source)."""
    pair = GearPair(GearPairDesign(trace="logarithmic"))
    calibrated = calibrated_line_stiffness(pair)
    assert calibrated == pytest.approx(ContactParameters().line_stiffness, rel=2e-3)
    contact = MeshContact(pair, LINE)
    c_gamma = contact.mean_mesh_stiffness() / pair.design.face_width
    assert c_gamma == pytest.approx(20e9, rel=3e-3)
    # the helical-gear form c_gamma = k_l eps_alpha cos(beta_p) (R_e^3 - R_i^3) / (3 b R_m^2)
    d = pair.design
    profile = pair.contact_ratio()["profile"]
    helical = calibrated * profile * math.cos(d.plane_spiral_angle) * (
        d.outer_cone_distance**3 - d.inner_cone_distance**3) / (
        3 * d.face_width * d.mean_cone_distance**2)
    assert helical == pytest.approx(20e9, rel=1e-9)


def test_a_pair_takes_up_load_gradually(pair):
    """Line model: the torque under a fixed mismatch is continuous in the mesh
    position; the point model's jumps when a tooth pair enters at full force."""
    line = MeshContact(pair, LINE.replace(mu_s=0.0, mu_d=0.0))
    point = MeshContact(pair, ContactParameters(mu_s=0.0, mu_d=0.0))
    angles = np.linspace(0.0, 2 * math.pi / 9, 20001)
    jumps = {}
    for name, contact, eps in (("line", line, 8e-4), ("point", point, 5e-5)):
        torque = np.array([contact.forces(a, (a * contact.e1 - eps) / contact.e2).gear_torque
                           for a in angles])
        jumps[name] = np.max(np.abs(np.diff(torque))) / torque.mean()
    assert jumps["line"] < 2e-4
    assert jumps["point"] > 0.05


@pytest.mark.parametrize("model", ["point", "line"])
def test_energy_balance_friction_only_dissipates(pair, model):
    """At kinematic speeds (no approach rate) the power the pinion puts into the mesh
    equals what the gear takes out without friction, and exceeds it with friction."""
    w1 = math.radians(7703.0)
    w2 = w1 * 9 / 37
    for mu in (0.0, 0.05):
        contact = MeshContact(pair, ContactParameters(model=model, mu_s=mu, mu_d=mu),
                              gear_inertia=GEAR_INERTIA)
        eps = 8e-4 if model == "line" else 3e-5
        for a in np.linspace(0.01, 2 * math.pi / 9, 7):
            f = contact.forces(a, (a * contact.e1 - eps) / contact.e2, w1, w2)
            loss = -f.pinion_torque * w1 - f.gear_torque * w2
            if mu == 0.0:
                assert loss == pytest.approx(0.0, abs=1e-9 * f.gear_torque * w2)
            else:
                assert loss > 1e-4 * f.gear_torque * w2


def test_mesh_mode_rings_at_its_frequency_with_its_damping_ratio():
    """Free vibration of the gear on the line-contact spring, pinion at rest: the
    measured frequency and damping ratio are the mode's at that mesh position."""
    pair = GearPair(GearPairDesign())
    zeta = 0.05
    contact = MeshContact(pair, LINE.replace(mu_s=0.0, mu_d=0.0, damping_ratio=zeta),
                          gear_inertia=GEAR_INERTIA)
    rest = contact.static_gear_angle(LOAD)
    h = 1e-8
    local = (contact.forces(0.0, rest - h).gear_torque
             - contact.forces(0.0, rest + h).gear_torque) / (2 * h)
    omega = math.sqrt(local / GEAR_INERTIA)
    omega_mean = 2 * math.pi * contact.natural_frequency(GEAR_INERTIA)
    expected_zeta = zeta * omega / omega_mean  # stiffness-proportional slice damping
    times = np.linspace(0.0, 0.006, 12001)
    # the pinion held at rest (speed 0, ramp 1 s): the gear's angle and speed
    states, status, *_ = integrate(PRESCRIBED, times, np.array([rest - 2e-5, 0.0]),
                                   np.array([0.0, 1.0, LOAD, GEAR_INERTIA]), *contact.arrays,
                                   *tableau("DOP853"), 1e-11, np.array([1e-14, 1e-10]), 1e-5,
                                   1e-3, 1e3, 1)
    assert status == 0
    x = states[:, 0] - rest
    peaks = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1
    peaks = peaks[x[peaks] > 0][:6]
    decrement = np.mean(np.log(x[peaks[:-1]] / x[peaks[1:]]))
    measured_zeta = decrement / math.sqrt(4 * math.pi**2 + decrement**2)
    period = np.mean(np.diff(times[peaks]))
    measured_omega = 2 * math.pi / period / math.sqrt(1 - measured_zeta**2)
    assert measured_omega == pytest.approx(omega, rel=5e-3)
    assert measured_zeta == pytest.approx(expected_zeta, rel=0.03)
    assert 0.7 * zeta < expected_zeta < 1.3 * zeta


def test_line_model_only_quantities_refuse_the_point_model(pair):
    with pytest.raises(ValueError, match="line model.*'point'"):
        MeshContact(pair).mean_torsional_stiffness()


def test_pair_contacts_report_the_line(pair):
    contact = MeshContact(pair, LINE)
    rest = contact.static_gear_angle(LOAD)
    pairs, loads = contact.pair_contacts(0.0, rest, slice_loads=True)
    assert 2 <= len(pairs) <= 4 and loads.shape == (len(pairs), LINE.slices)
    assert sum(p.normal_force for p in pairs) == pytest.approx(
        contact.forces(0.0, rest).normal_force)
    for p, row in zip(pairs, loads):
        assert p.side == "drive" and p.contact_length > 0
        # the slices' loads per unit length times their lengths give the pair's load
        lengths = contact.arrays[2][0, :, kernels.B_LENGTH]
        assert p.normal_force <= np.sum(row * lengths) * (1 + 1e-12)
    assert sum(p.contact_length for p in pairs) == pytest.approx(0.036, rel=0.1)
