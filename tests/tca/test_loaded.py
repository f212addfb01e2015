"""Loaded tooth contact analysis: conjugacy without load, linearity, the standard's
stiffness, harmonics, the CLI, and a slow dynamic run that reproduces it."""

import math

import numpy as np
import pytest
import xarray as xr

from lsbg import cli
from lsbg.tca import loaded as ltca
from lsbg.contact import ContactParameters, MeshContact
from lsbg.gear.design import GearPairDesign
from lsbg.dynamics import SimulationSettings, load_model
from lsbg.solid.export import write_geometry
from lsbg.gear.geometry import GearPair
from lsbg.gear.vectors import rotate

LOAD = 1964.99
LINE = ContactParameters(model="line")


@pytest.fixture(scope="module", params=["logarithmic", "circular"])
def pair(request):
    return GearPair(GearPairDesign(trace=request.param))


@pytest.fixture(scope="module")
def analysis(pair):
    return ltca.loaded_tca(MeshContact(pair, LINE), LOAD)


def test_dataset_has_the_issue_quantities_with_units(analysis):
    assert analysis.sizes["mesh_phase"] == ltca.PHASES >= 200
    units = {"transmission_error": "urad", "mesh_stiffness": "N/um", "contact_length": "mm",
             "pair_load": "N", "tooth_pair_load": "N", "contact_pattern": "N/mm"}
    for name, unit in units.items():
        assert analysis[name].attrs["units"] == unit and analysis[name].attrs["long_name"]
    assert analysis.contact_pattern.dims == ("cone_distance", "profile_angle")
    assert analysis.attrs["Conventions"] == "CF-1.11"
    # the tooth pairs carry the load between them: their normal loads add up to the
    # normal force that balances the torque at every mesh position
    assert (analysis.pair_load.sum("tooth_pair") > 0).all()
    assert np.all(analysis.pair_load.values >= 0)
    te = analysis.transmission_error.values
    assert analysis.attrs["transmission_error_peak_to_peak_urad"] == pytest.approx(np.ptp(te))


def test_unloaded_transmission_error_is_zero_on_the_flank_surfaces(pair):
    """Conjugate flanks: the classical unloaded TCA on the flank surfaces (not the
    plane-of-action kernel) finds no transmission error."""
    angles = np.linspace(0.0, 2 * math.pi / 9, 7)
    te = ltca.unloaded_transmission_error(pair, angles)
    assert np.max(np.abs(te)) < 1e-9


class ThickerPinion(GearPair):
    """The pair with every pinion flank turned forward by ``delta`` (a thicker tooth)."""

    delta = 1e-5

    def flank(self, member, side, cone_distance, polar_angle):
        points, normals = super().flank(member, side, cone_distance, polar_angle)
        if member == 1:
            u = self.rotation_axis[1]
            points, normals = rotate(points, u, self.delta), rotate(normals, u, self.delta)
        return points, normals


def test_unloaded_transmission_error_sees_a_misplaced_flank(pair):
    """The same TCA is not blind: pinion flanks 10 µrad ahead touch the gear earlier,
    which then runs ahead of its kinematic position by 10 µrad z1/z2."""
    thicker = ThickerPinion(pair.design)
    te = ltca.unloaded_transmission_error(thicker, np.linspace(0.0, 2 * math.pi / 9, 3))
    np.testing.assert_allclose(te, -ThickerPinion.delta * 9 / 37, rtol=1e-6)


def test_linear_in_load(pair):
    contact = MeshContact(pair, LINE)
    single = ltca.loaded_tca(contact, LOAD, phases=32)
    double = ltca.loaded_tca(contact, 2 * LOAD, phases=32)
    np.testing.assert_allclose(double.transmission_error, 2 * single.transmission_error,
                               rtol=1e-9)
    np.testing.assert_allclose(double.mesh_stiffness, single.mesh_stiffness, rtol=1e-6)
    np.testing.assert_allclose(double.pair_load, 2 * single.pair_load, rtol=1e-9, atol=1e-6)


def test_unloaded_analysis_touches_at_the_kinematic_position(pair, analysis):
    """At zero load the model's flanks touch with no transmission error (they are
    conjugate), carry nothing, and the slope at first touch is the loaded
    stiffness (the slice law is linear)."""
    unloaded = ltca.loaded_tca(MeshContact(pair, LINE), 0.0, phases=32)
    assert np.abs(unloaded.transmission_error.values * 1e-6).max() < 1e-9
    assert np.abs(unloaded.pair_load.values).max() < 1e-6
    np.testing.assert_allclose(unloaded.mesh_stiffness, analysis.mesh_stiffness[::8], rtol=1e-3)


def test_mesh_stiffness_is_the_standards_and_its_closed_form(analysis):
    c_gamma = analysis.attrs["mesh_stiffness_per_face_width_N_per_mm_um"]
    assert 5 < c_gamma < 40
    assert c_gamma == pytest.approx(20.0, rel=0.02)  # calibrated at the paper's design
    assert analysis.attrs["mesh_stiffness_mean_N_per_um"] == pytest.approx(
        analysis.attrs["mean_mesh_stiffness_closed_form_N_per_um"], rel=1e-6)
    # the static TE is the load over the stiffness, referred to the gear's base radius
    force = LOAD / (analysis.attrs["base_radius_gear_mm"] * 1e-3)
    approach = force / (analysis.mesh_stiffness.values * 1e6)
    np.testing.assert_allclose(analysis.transmission_error.values * 1e-6,
                               approach / (analysis.attrs["base_radius_gear_mm"] * 1e-3),
                               rtol=1e-4)


def test_half_the_crowning_loads_the_teeth_as_half_the_stiffness(pair):
    """An invariant of the uniform bed, not a fit: a slice carries k (d - c s), so the
    ease-off scaled by c loads the teeth exactly as the stiffness scaled by c does
    (at an approach d / c). The sensitivity cases crowning x0.5 and line stiffness
    x0.5 therefore share their load distribution and edge loads."""
    from lsbg.tca.separation import RealFlanks

    def analysed(crowning, stiffness_factor):
        flanks = RealFlanks.from_config({"lengthwise_crowning_um": 25 * crowning,
                                         "profile_crowning_um": 5 * crowning}, {})
        params = LINE.replace(line_stiffness=LINE.line_stiffness * stiffness_factor)
        return ltca.loaded_tca(MeshContact(pair, params, separation=flanks.separation(pair)),
                               LOAD, phases=16)

    half_crowning, half_stiffness = analysed(0.5, 1.0), analysed(1.0, 0.5)
    # (to the equilibrium's iteration: 0.06 % measured)
    np.testing.assert_allclose(half_crowning["pair_load"], half_stiffness["pair_load"],
                               rtol=2e-3, atol=1e-4 * LOAD)
    np.testing.assert_allclose(half_stiffness["transmission_error"],
                               2 * half_crowning["transmission_error"], rtol=2e-3)
    # and it is not trivially so: the crowning does change the load sharing
    full = analysed(1.0, 1.0)
    assert np.abs(full["pair_load"] - half_crowning["pair_load"]).max() > 0.01 * LOAD


def test_harmonics_of_a_known_signal():
    phase = np.arange(256) / 256
    signal = 5.0 + 3.0 * np.sin(2 * np.pi * phase) + 0.5 * np.cos(6 * np.pi * phase + 0.3)
    np.testing.assert_allclose(ltca.harmonic_amplitudes(signal), [3.0, 0.0, 0.5], atol=1e-12)


def test_slices_converge(pair):
    figures = [ltca.loaded_tca(MeshContact(pair, LINE.replace(slices=n)), LOAD, phases=64)
               .attrs["transmission_error_peak_to_peak_urad"] for n in (20, 80)]
    assert figures[0] == pytest.approx(figures[1], rel=2e-3)


def test_point_model_and_bad_input_are_refused(pair):
    with pytest.raises(ValueError, match="line model"):
        ltca.loaded_tca(MeshContact(pair), LOAD)
    with pytest.raises(ValueError, match="phases = 3"):
        ltca.loaded_tca(MeshContact(pair, LINE), LOAD, phases=3)
    with pytest.raises(ValueError, match="load_torque = -1"):
        ltca.loaded_tca(MeshContact(pair, LINE), -1.0)


@pytest.fixture(scope="module")
def geometry(tmp_path_factory):
    out = tmp_path_factory.mktemp("ltca") / "geometry"
    write_geometry(GearPairDesign(), out)
    return out


def test_slow_dynamic_run_reproduces_the_quasi_static_transmission_error(geometry):
    """At a mesh frequency 200 times below the mesh mode, the run's transmission error
    follows the loaded TCA (no friction: the TCA is at rest)."""
    params = LINE.replace(mu_s=0.0, mu_d=0.0)
    model = load_model(geometry, params)
    static = ltca.loaded_tca(model.contact, LOAD, phases=128)
    settings = SimulationSettings(engine="compiled", duration=0.3, samples=150, ramp_time=0.05,
                                  pinion_speed=math.radians(360.0), rtol=1e-10)
    record = model.run(settings)
    run = record.samples
    after = run.time > 0.1
    phase = (run.pinion_angle[after] * model.contact.e1 / model.contact.pitch) % 1.0
    expected = np.interp(phase, static.mesh_phase.values, static.transmission_error.values,
                         period=1.0)
    te = (run.pinion_angle[after] * 9 / 37 - run.gear_angle[after]) * 1e6
    np.testing.assert_allclose(te, expected, rtol=2e-3)
    assert np.ptp(te) > 0.5 * np.ptp(static.transmission_error.values)


def test_cli_writes_the_analysis_and_refuses_bad_input(geometry, tmp_path, capsys):
    out = tmp_path / "mesh" / "point.nc"
    assert cli.main(["ltca", "--geometry", str(geometry), "--set", "tca.loaded_positions=64",
                     "--set", "simulation.load_torque_N_m=1000", "--out", str(out)]) == 0
    assert "urad peak to peak" in capsys.readouterr().out
    with xr.open_dataset(out) as ds:
        assert ds.sizes["mesh_phase"] == 64 and ds.attrs["load_torque_N_m"] == 1000.0
        assert ds.attrs["contact_model"] == "line"
    bad = tmp_path / "bad.nc"
    assert cli.main(["ltca", "--geometry", str(geometry), "--set", "tca.loaded_positions=3",
                     "--out", str(bad)]) == 2
    assert "tca.loaded_positions: 3 is less than the minimum of 8" in capsys.readouterr().err
    assert cli.main(["ltca", "--geometry", str(geometry), "--set", "contact.slices=1",
                     "--out", str(bad)]) == 2
    assert "contact.slices: 1 is less than the minimum of 2" in capsys.readouterr().err
    assert not bad.exists()
