"""The torsional driveline: its modes against the closed forms of its reduced models, its
equations against its linearisation, power balance, the engines' agreement, convergence,
and the prescribed pinion unchanged."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from lsbg.config import fill_defaults, load_schema
from lsbg.contact import ContactParameters
from lsbg.contact.kernels import mesh_series
from lsbg.dynamics import SimulationSettings, load_model
from lsbg.dynamics.checks import driveline_problems
from lsbg.dynamics.compiled_engine import DRIVELINE, integrate, tableau
from lsbg.dynamics.driveline import (DRIVELINE_CONFIG_KEYS, Driveline, driveline_rates,
                                     driveline_values)
from lsbg.gear.design import GearPairDesign
from lsbg.solid.export import write_geometry

#: The default driveline on the paper's solids (lsbg geometry of Table 1, LSBG 35 deg).
PINION_SOLID, GEAR_SOLID = 3.0517e-5, 0.015912
#: The paper's LSBG's mean torsional mesh stiffness (line model, uniform bed) [N m/rad], rho.
MESH, RHO = 2.109e6, 9 / 37


def default(**changes):
    return dataclasses.replace(Driveline.from_config({}, PINION_SOLID, GEAR_SOLID), **changes)


# --------------------------------------------------------------- modes and closed forms
def test_soft_shafts_leave_the_two_inertia_mesh_mode():
    line = default(propshaft_stiffness=33.0, half_shaft_stiffness=17.0)
    frequencies, _ = line.modes(MESH, RHO)
    assert frequencies[-1] == pytest.approx(line.mesh_mode_frequency(MESH, RHO), rel=1e-3)
    free, _ = line.modes(MESH, RHO, held=False)
    assert free[-1] == pytest.approx(line.mesh_mode_frequency(MESH, RHO), rel=1e-3)


@pytest.mark.parametrize("held", [True, False])
def test_a_rigid_mesh_leaves_the_shafts_chain(held):
    line = default()
    frequencies, _ = line.modes(MESH * 1e6, RHO, held=held)
    shafts = frequencies[-3:-1]  # below the (now very stiff) mesh mode
    np.testing.assert_allclose(shafts, line.rigid_mesh_frequencies(RHO, held=held), rtol=1e-3)


def test_each_shafts_own_mode_where_the_other_is_rigid():
    stiff_half = default(half_shaft_stiffness=1.7e10)
    free, _ = stiff_half.modes(MESH * 1e6, RHO, held=False)
    assert free[1] == pytest.approx(stiff_half.propshaft_frequency(RHO), rel=0.01)
    stiff_prop = default(propshaft_stiffness=3.3e10)
    free, _ = stiff_prop.modes(MESH * 1e6, RHO, held=False)
    assert free[1] == pytest.approx(stiff_prop.half_shaft_frequency(RHO), rel=0.01)


def test_default_modes_and_the_pinion_free():
    """The default minibus driveline: the vehicle on the half-shafts near 1 Hz (drive end
    held; 9 Hz free), the axle on the propeller shaft near 420 Hz, the mesh near 1.76 kHz.
    With the pinion's tooth body alone (no shaft, no flange) the mesh mode is the issue's
    10 kHz, raised by the propeller shaft's stiffness on the light pinion."""
    line = default()
    held, shapes = line.modes(MESH, RHO)
    np.testing.assert_allclose(held, [0.983, 424.0, 1762.0], rtol=2e-3)
    assert line.mesh_mode_frequency(MESH, RHO) == pytest.approx(1692, rel=2e-3)
    # the mesh mode is the pinion against the gear: their shapes' signs differ
    assert np.sign(shapes[0, 2]) != np.sign(shapes[1, 2])
    bare = default(pinion_inertia=PINION_SOLID)
    two_inertia = bare.mesh_mode_frequency(MESH, RHO)
    assert two_inertia == pytest.approx(10.2e3, rel=0.01)
    assert bare.modes(MESH, RHO)[0][-1] == pytest.approx(
        math.hypot(two_inertia, math.sqrt(bare.propshaft_stiffness / PINION_SOLID) / (2 * math.pi)),
        rel=0.01)


# --------------------------------------------------------------- configuration
def test_schema_defaults_are_the_modules():
    config = {}
    fill_defaults(config, load_schema())
    assert config["driveline"] == {key: default for key, (default, _) in DRIVELINE_CONFIG_KEYS.items()}


@pytest.mark.parametrize("key, value, why", [
    ("tyre_radius_m", 0, "must be a positive number"),
    ("carrier_inertia_kg_m2", -1e-3, "must be a non-negative number"),
    ("half_shaft_damping_ratio", 1.0, "damping ratio"),
    ("propshaft_stiffness_N_m_per_rad", "stiff", "must be a positive number"),
    ("wheelbase_m", 3.0, "unknown key"),
])
def test_each_key_is_checked_by_name(key, value, why):
    with pytest.raises(ValueError, match=f"^driveline.{key} = {value!r}: .*{why}"):
        driveline_values({key: value})
    (problem,) = driveline_problems({"driveline": {key: value}})
    assert problem.startswith(f"driveline.{key} = {value!r}:")


def test_pybullet_refuses_the_driveline():
    with pytest.raises(ValueError, match="simulation.boundary = 'driveline': .*pybullet"):
        SimulationSettings.from_config({"boundary": "driveline"}, engine="pybullet")


# --------------------------------------------------------------- runs
@pytest.fixture(scope="module")
def model(tmp_path_factory):
    out = tmp_path_factory.mktemp("driveline") / "geometry"
    write_geometry(GearPairDesign(trace="logarithmic"), out)
    return load_model(out, ContactParameters.from_config({"model": "line"}), driveline={})


#: A steady run: the start's transient (the axle's mode, 424 Hz, zeta 0.05: time constant
#: 7.5 ms) decayed by e^-6 at 0.05 s; 0.05-0.1 s is 9.6 mesh cycles.
STEADY = SimulationSettings(engine="compiled", boundary="driveline", duration=0.1, samples=50,
                            ramp_time=0.0, full_rate=200000.0, full_rate_after=0.05)


def gear_speed_std(record):
    return float(np.degrees(record.full_rate.gear_speed).std())


@pytest.fixture(scope="module")
def runs(model):
    return {engine: model.run(STEADY.replace(engine=engine)) for engine in ("compiled", "scipy")}


def test_the_equations_linearise_to_the_stiffness_matrix(model):
    """Finite differences of the compiled equations about the start, averaged over a mesh
    cycle, give -M^-1 K of :meth:`Driveline.matrices` at the mean mesh stiffness."""
    y0, system = model.driveline_problem(STEADY)
    contact = model.contact
    line = model.driveline
    mass, stiffness = line.matrices(contact.mean_torsional_stiffness(), contact.e1 / contact.e2)
    jacobian = np.zeros((3, 3))
    phases = 64
    step = 1e-9
    for k in range(phases):
        base = y0.copy()
        base[0] = k * contact.pitch / (phases * contact.e1)  # pinion through one base pitch
        base[1] += base[0] * contact.e1 / contact.e2
        base[3:] = 0.0  # at rest: no damping or friction in the difference
        out_plus, out_minus = np.empty((1, 6)), np.empty((1, 6))
        for j in range(3):
            plus, minus = base.copy(), base.copy()
            plus[j] += step
            minus[j] -= step
            driveline_rates(0.0, plus, out_plus, 0, system, *contact.arrays)
            driveline_rates(0.0, minus, out_minus, 0, system, *contact.arrays)
            jacobian[:, j] += (out_plus[0, 3:] - out_minus[0, 3:]) / (2 * step) / phases
    expected = -np.linalg.solve(mass, stiffness)
    # shaft terms exact; the mesh's mean over 64 phases within 1 % of the closed-form mean
    np.testing.assert_allclose(jacobian, expected, rtol=0.01, atol=1e-6 * np.abs(expected).max())


def test_power_balance_over_a_steady_run(model):
    """Input power at the drive end = load power + dissipated (the shafts' dampers, the
    mesh's damping and friction) + the change of kinetic and shaft energy, over 0.01-0.06 s
    within 1e-5 of the input energy (the states from the compiled loop on a 2-us grid,
    the powers integrated by the trapezoid rule)."""
    contact = model.contact
    y0, system = model.driveline_problem(STEADY)
    speed, offset, kp, cp, kh, ch, j1, j2, jv, load = system
    times = np.linspace(0.0, 0.06, 30001)
    atol = np.array([STEADY.atol_angle] * 3 + [STEADY.atol_speed] * 3)
    states, status, *_ = integrate(DRIVELINE, times, y0, system, *contact.arrays,
                                   *tableau("DOP853"), STEADY.rtol, atol, 2e-6,
                                   model.penetration_limit, model.speed_limit(STEADY), 4)
    assert status == 0
    keep = times >= 0.01
    t, (phi1, phi2, phi_v, w1, w2, w_v) = times[keep], states[keep].T
    torques = mesh_series(phi1, phi2, w1, w2, *contact.arrays)
    drive_twist, half_twist = offset + speed * t - phi1, phi2 - phi_v
    shaft = kp * drive_twist + cp * (speed - w1)
    energy_in = np.trapezoid(shaft * speed, t)
    load_energy = np.trapezoid(load * w_v, t)
    mesh_loss = -np.trapezoid(torques[:, 0] * w2 + torques[:, 1] * w1, t)
    damper_loss = np.trapezoid(cp * (speed - w1) ** 2 + ch * (w2 - w_v) ** 2, t)
    stored = 0.5 * (j1 * w1**2 + j2 * w2**2 + jv * w_v**2 + kp * drive_twist**2
                    + kh * half_twist**2)
    balance = energy_in - load_energy - mesh_loss - damper_loss - (stored[-1] - stored[0])
    assert abs(balance) < 1e-5 * energy_in
    # the losses: mostly the mesh's friction (mu 0.05), a fraction of a per cent
    assert 0.0 < mesh_loss / energy_in < 0.02 and 0.0 < damper_loss < mesh_loss


def test_engines_agree_on_the_steady_gear_speed(runs):
    compiled, scipy = (gear_speed_std(runs[e]) for e in ("compiled", "scipy"))
    assert compiled == pytest.approx(scipy, rel=2e-5)
    # Eq. 12 within 0.1 deg/s: the start's transient kicks the vehicle's mode (1 Hz, a
    # time constant of 3 s) by about 0.05 deg/s
    mean = np.degrees(runs["compiled"].full_rate.gear_speed).mean()
    assert mean == pytest.approx(math.degrees(STEADY.pinion_speed) * 9 / 37, abs=0.1)


@pytest.mark.parametrize("change", [{"rtol": 0.5e-8}, {"samples": 100}])
def test_halving_the_tolerance_or_the_largest_step(model, runs, change):
    finer = gear_speed_std(model.run(STEADY.replace(**change)))
    assert finer == pytest.approx(gear_speed_std(runs["compiled"]), rel=1e-5)


# --------------------------------------------------------------- the paper's boundary
#: Full-rate gear angle, speed and torque of 20-ms runs (ramp 10 ms) of the paper's LSBG
#: under the prescribed pinion, made by lsbg's main branch before the driveline (commit
#: 2ac4019): the compiled and scipy engines, both contact models.
REFERENCE = Path(__file__).parent / "data" / "prescribed_pinion_main.npz"


@pytest.mark.parametrize("contact_model", ["line", "point"])
@pytest.mark.parametrize("engine", ["compiled", "scipy"])
def test_the_prescribed_pinion_is_as_before(model, engine, contact_model):
    geometry = Path(model.urdf).parent
    old = np.load(REFERENCE)
    settings = SimulationSettings(engine=engine, duration=0.02, samples=10, ramp_time=0.01,
                                  full_rate_after=0.01)
    record = load_model(geometry, ContactParameters.from_config({"model": contact_model})
                        ).run(settings)
    # Bit for bit on a machine like the one that made the file; on another processor the
    # geometry's sums round differently (seen: 1e-9 to 8e-6 of each series' scale, and the
    # adaptive scipy engine 2 % more steps), far below what the driveline's code could
    # change by taking the pinion's path (its states, its ramp: order one)
    for name in ("gear_angle", "gear_speed", "gear_torque"):
        reference = old[f"{contact_model}_{engine}_{name}"]
        series = getattr(record.full_rate, name)
        assert series.shape == reference.shape, name
        assert np.abs(series - reference).max() <= 5e-5 * np.abs(reference).max(), name
    steps = int(old[f"{contact_model}_{engine}_steps"])
    assert record.steps == pytest.approx(steps, rel=0.05)


# --------------------------------------------------------------- lsbg simulate
def test_lsbg_simulate_runs_the_configured_boundary(model, tmp_path, capsys):
    from lsbg import cli
    from lsbg.dynamics.dataset import open_run

    geometry = str(Path(model.urdf).parent)
    short = ["--set", "contact.model=line", "--set", "simulation.duration_s=0.02",
             "--set", "simulation.samples=10", "--set", "simulation.ramp_time_s=0.01",
             "--set", "simulation.full_rate_after_s=0.01", "--engine", "compiled"]
    runs = {}
    for boundary in ("prescribed_pinion", "driveline"):
        out = tmp_path / f"{boundary}.nc"
        assert cli.main(["simulate", "--geometry", geometry, *short,
                         "--set", f"simulation.boundary={boundary}",
                         "--set", "driveline.vehicle_mass_kg=3000", "--out", str(out)]) == 0
        runs[boundary] = open_run(out)
    held = runs["driveline"]
    assert held.attrs["solver_boundary"] == "driveline"
    assert held.attrs["driveline_vehicle_inertia_kg_m2"] == pytest.approx(3000 * 0.35**2)
    assert held.attrs["mesh_natural_frequency_hz"] == held.attrs["driveline_mode3_hz"]
    assert "driveline_mode1_hz" not in runs["prescribed_pinion"].attrs
    # the driveline's pinion moves with the mesh; the prescribed one does not
    assert held.pinion_speed.values[-1] != runs["prescribed_pinion"].pinion_speed.values[-1]
    assert "driveline" in capsys.readouterr().out
