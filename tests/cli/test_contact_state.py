"""The contact state on the command line and in the dynamics.

``lsbg tca`` and ``lsbg misalignment-map`` write what the library computes;
``--config``'s ``flank_modification`` and ``misalignment`` sections (and ``--set
flank_modification.KEY=VALUE`` / ``--set misalignment.KEY=VALUE``) reach every line-model
command; without them every command gives today's conjugate numbers, bit for
bit; bad input is named, exit code 2, nothing written.
"""

import numpy as np
import pytest
import xarray as xr
import yaml

from lsbg import cli
from lsbg.contact import ContactParameters
from lsbg.gear.design import GearPairDesign
from lsbg.dynamics import SimulationSettings, load_model, simulate
from lsbg.solid.export import write_geometry
from lsbg.gear.geometry import GearPair
from lsbg.tca.loaded import ltca_for_geometry
from lsbg.tca.analysis import tooth_contact_analysis
from lsbg.tca.modification import FlankModification
from lsbg.tca.misalignment import Misalignment
from lsbg.tca.separation import RealFlanks

SHORT = SimulationSettings(duration=0.04, samples=20, ramp_time=0.01, engine="compiled",
                           full_rate_after=0.01)
CROWNED = {"lengthwise_crowning_um": 25, "profile_crowning_um": 5}


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    root = tmp_path_factory.mktemp("contact_state_cli")
    geometry = root / "logarithmic_beta35"
    write_geometry(GearPairDesign(), geometry)
    config = root / "config.yaml"
    config.write_text(yaml.safe_dump({"flank_modification": CROWNED,
                                      "misalignment": {"pinion_axial_P_mm": 0.05},
                                      "tca": {"positions": 40},
                                      "misalignment_map": {"steps": 3, "positions": 20}}))
    return {"root": root, "geometry": geometry, "config": config}


def run(argv):
    return cli.main([str(a) for a in argv])


def test_tca_command_writes_what_the_library_computes(world, capsys):
    out = world["root"] / "tca.nc"
    assert run(["tca", "--geometry", world["geometry"], "--config", world["config"],
                "--out", out]) == 0
    written = xr.open_dataset(out)
    expected = tooth_contact_analysis(GearPair(GearPairDesign()), FlankModification(25e-6, 5e-6),
                                      Misalignment(pinion_axial=5e-5), positions=40)
    np.testing.assert_array_equal(written["transmission_error"], expected["transmission_error"])
    assert written.attrs["misalignment_pinion_axial_P_mm"] == pytest.approx(0.05)
    assert written.attrs["flank_modification_lengthwise_crowning_um"] == pytest.approx(25)
    assert "arcsec" in capsys.readouterr().out


def test_options_override_the_config(world):
    out = world["root"] / "tca_options.nc"
    assert run(["tca", "--geometry", world["geometry"], "--config", world["config"],
                "--set", "misalignment.pinion_axial_P_mm=0",
                "--set", "flank_modification.profile_crowning_um=0",
                "--set", "tca.positions=24", "--out", out]) == 0
    ds = xr.open_dataset(out)
    assert ds.sizes["mesh_phase"] == 24
    assert ds.attrs["misalignment_pinion_axial_P_mm"] == 0
    # pure lengthwise crowning: no unloaded transmission error (docs/model.md)
    assert ds.attrs["transmission_error_peak_to_peak_urad"] < 1.0


def test_misalignment_map_command_and_its_tca(world):
    out, tca = world["root"] / "vh.nc", world["root"] / "vh_tca.nc"
    assert run(["misalignment-map", "--geometry", world["geometry"], "--config", world["config"],
                "--set", "misalignment_map.axes=[P, G]", "--set", "misalignment_map.range=0.05",
                "--out", out, "--tca-out", tca]) == 0
    vh = xr.open_dataset(out)
    assert vh["transmission_error_unloaded_pp"].dims == ("P", "G")
    np.testing.assert_allclose(vh["P"], [-0.05, 0.0, 0.05])
    # the grid is added to the config's P = 0.05 mm: the map's centre is that assembly
    direct = tooth_contact_analysis(GearPair(GearPairDesign()), FlankModification(25e-6, 5e-6),
                                    Misalignment(pinion_axial=5e-5), positions=20,
                                    grid=(61, 121))
    assert float(vh["transmission_error_unloaded_pp"].sel(P=0.0, G=0.0)) == pytest.approx(
        direct.attrs["transmission_error_peak_to_peak_urad"], rel=1e-12)
    assert xr.open_dataset(tca).sizes["mesh_phase"] == 40


def test_sensitivity_cases_of_the_map_and_the_loaded_tca_are_the_options_they_stand_for(world):
    """A case is the same command with the case's settings: crowning x1 is the base map
    itself, crowning x2 the map of twice the config's ease-off, stiffness x2 the map on
    twice the bed (its unloaded half unchanged)."""
    root = world["root"]
    base, doubled = root / "vh_base.nc", root / "vh_doubled.nc"
    assert run(["misalignment-map", "--geometry", world["geometry"], "--config", world["config"],
                "--out", base, "--case", "crowning=1", "--case", "crowning=2",
                "--set", "misalignment_map.sweep_steps=3",   # the cases' grid: the base map's
                "--case", "line_stiffness_N_per_mm_um=2",
                "--case-out", root / "vh_{case}.nc"]) == 0
    assert run(["misalignment-map", "--geometry", world["geometry"], "--config", world["config"],
                "--set", "flank_modification.lengthwise_crowning_um=50",
                "--set", "flank_modification.profile_crowning_um=10", "--out", doubled]) == 0
    one, two = xr.open_dataset(root / "vh_crowning_x1.nc"), xr.open_dataset(root / "vh_crowning_x2.nc")
    assert one.attrs["sensitivity_case"] == "crowning_x1"
    xr.testing.assert_equal(one.drop_attrs(), xr.open_dataset(base).drop_attrs())
    xr.testing.assert_equal(two.drop_attrs(), xr.open_dataset(doubled).drop_attrs())
    stiff = xr.open_dataset(root / "vh_line_stiffness_N_per_mm_um_x2.nc")
    xr.testing.assert_equal(stiff["transmission_error_unloaded_pp"], one["transmission_error_unloaded_pp"])
    assert not np.allclose(stiff["transmission_error_loaded_pp"], one["transmission_error_loaded_pp"])
    # the loaded TCA's case: the command with the doubled ease-off
    assert run(["ltca", "--geometry", world["geometry"], "--config", world["config"],
                "--set", "tca.loaded_positions=16", "--out", root / "ltca.nc",
                "--case", "crowning=2",
                "--case-out", root / "ltca_{case}.nc"]) == 0
    assert run(["ltca", "--geometry", world["geometry"], "--config", world["config"],
                "--set", "tca.loaded_positions=16",
                "--set", "flank_modification.lengthwise_crowning_um=50",
                "--set", "flank_modification.profile_crowning_um=10",
                "--out", root / "ltca2.nc"]) == 0
    case, direct = xr.open_dataset(root / "ltca_crowning_x2.nc"), xr.open_dataset(root / "ltca2.nc")
    np.testing.assert_array_equal(case["transmission_error"], direct["transmission_error"])
    assert case.attrs["sensitivity_case"] == "crowning_x2"


@pytest.mark.parametrize("argv, message", [
    (["tca", "--set", "misalignment.X=1"],
     "--set 'misalignment.X=1': misalignment.X: unknown key (known: gear_axial_G_mm, "
     "offset_E_mm, pinion_axial_P_mm, shaft_angle_error_deg)"),
    # the letter shortcut is gone: the letter is no key
    (["tca", "--set", "misalignment.P=0.05"], "misalignment.P: unknown key"),
    (["tca", "--set", "flank_modification.lengthwise_crowning_um=-3"],
     "flank_modification.lengthwise_crowning_um: -3 is less than the minimum of 0"),
    (["tca", "--set", "misalignment.gear_axial_G_mm=-0.5"],
     "gear_axial_G_mm = -0.5: the members interfere"),
    (["tca", "--set", "tca.positions=4"], "tca.positions: 4 is less than the minimum of 8"),
    (["misalignment-map", "--set", "misalignment_map.steps=4"],
     "misalignment_map.steps = 4: must be an odd whole number >= 3"),
    (["ltca", "--set", "flank_modification.bias"],
     "--set 'flank_modification.bias': must be section.key=value"),
])
def test_bad_input_is_named_and_nothing_written(world, capsys, argv, message):
    out = world["root"] / "never.nc"
    assert run([argv[0], "--geometry", world["geometry"], *argv[1:], "--out", out]) == 2
    assert message in capsys.readouterr().err
    assert not out.exists()


def test_line_model_without_modification_is_todays_bit_for_bit(world):
    line = ContactParameters(model="line")
    today = simulate(world["geometry"], SHORT, line)
    aligned = simulate(world["geometry"], SHORT, line, flanks=RealFlanks())
    for name in ("gear_speed", "tangential_force", "transmission_error"):
        np.testing.assert_array_equal(today[name], aligned[name])
    mesh = ltca_for_geometry(world["geometry"], 1964.99, line, phases=32)
    same = ltca_for_geometry(world["geometry"], 1964.99, line, phases=32, flanks=RealFlanks())
    np.testing.assert_array_equal(mesh["transmission_error"], same["transmission_error"])


def test_dynamics_on_crowned_flanks_carries_their_excitation(world):
    line = ContactParameters(model="line")
    crowned = RealFlanks(FlankModification(25e-6, 5e-6))
    model = load_model(world["geometry"], line, crowned)
    assert model.contact.separation is not None
    ds = simulate(world["geometry"], SHORT, line, flanks=crowned)
    assert ds.attrs["flank_modification_lengthwise_crowning_um"] == pytest.approx(25)
    today = simulate(world["geometry"], SHORT, line)
    # in the steady state the run's mean transmission error moves by what the loaded TCA
    # on the same flanks says the crowning adds at rest
    steady = ds["time"] > 0.01
    shift = float(ds["transmission_error"].where(steady).mean()
                  - today["transmission_error"].where(steady).mean())
    static = [ltca_for_geometry(world["geometry"], 1964.99, line, phases=64, flanks=f)
              for f in (crowned, None)]
    expected = (static[0].attrs["transmission_error_mean_urad"]
                - static[1].attrs["transmission_error_mean_urad"])
    assert expected > 50.0
    assert shift == pytest.approx(expected, rel=0.1)
    # the point model, the paper's reproduction, keeps the conjugate flanks
    point = load_model(world["geometry"], ContactParameters(), crowned)
    assert point.contact.separation is None


def test_config_sections_reach_the_line_model_commands(world):
    out = world["root"] / "mesh.nc"
    assert run(["ltca", "--geometry", world["geometry"], "--config", world["config"],
                "--set", "tca.loaded_positions=16", "--set", "simulation.load_torque_N_m=100",
                "--out", out]) == 0
    ds = xr.open_dataset(out)
    assert ds.attrs["load_torque_N_m"] == 100 and ds.sizes["mesh_phase"] == 16
    assert ds.attrs["flank_modification_profile_crowning_um"] == pytest.approx(5)
    assert ds.attrs["misalignment_pinion_axial_P_mm"] == pytest.approx(0.05)
    assert ds.attrs["loaded_pattern_length_per_face_width"] < 1.0
