"""The pinion-speed sweep: run settings, the resonance of the mesh mode, the curve
and its command line, table and figures."""

import math

import numpy as np
import pytest
import xarray as xr

from lsbg import cli
from lsbg.cli.options import settings_of
from lsbg.tca import loaded as ltca
from lsbg.experiments import speed
from lsbg.tables import line_model
from lsbg.contact import ContactParameters
from lsbg.gear.design import GearPairDesign
from lsbg.dynamics import SimulationSettings, load_model, simulate
from lsbg.solid.export import write_geometry

LINE = ContactParameters(model="line")
BASE = SimulationSettings(engine="compiled", full_rate=20000.0, rtol=1e-8)


@pytest.fixture(scope="module")
def geometry(tmp_path_factory):
    root = tmp_path_factory.mktemp("speed")
    dirs = {}
    for trace in ("logarithmic", "circular"):
        dirs[trace] = root / trace
        write_geometry(GearPairDesign(trace=trace), dirs[trace])
    return dirs


def test_speed_grid_has_a_constant_ratio_and_refuses_bad_bounds():
    grid = speed.speed_grid(10.0, 1000.0, 5)
    np.testing.assert_allclose(grid[1:] / grid[:-1], math.sqrt(math.sqrt(100.0)), rtol=1e-12)
    assert grid[0] == pytest.approx(10.0) and grid[-1] == pytest.approx(1000.0)
    with pytest.raises(ValueError, match="start, stop"):
        speed.speed_grid(100.0, 10.0, 5)
    with pytest.raises(ValueError, match="count = 1"):
        speed.speed_grid(1.0, 10.0, 1)


def test_resonance_speeds_put_the_mesh_harmonic_on_the_natural_frequency():
    speeds = speed.resonance_speeds(1800.0, 9, orders=(1, 2, 3))
    mesh = speeds * 9 / (2 * math.pi)
    np.testing.assert_allclose(mesh * np.array([1, 2, 3]), 1800.0, rtol=1e-12)


@pytest.mark.parametrize("omega_deg_s", [3000.0, 73000.0, 190000.0])
def test_speed_settings_hold_whole_output_steps_enough_cycles_and_samples(omega_deg_s):
    omega = math.radians(omega_deg_s)
    settings = speed.speed_settings(BASE, omega, 9, mesh_cycles=100, min_window=0.05,
                                    settle_time=0.05, ramp_time=0.05, samples_per_mesh=32)
    mesh = omega * 9 / (2 * math.pi)
    interval = 1 / speed.OUTPUT_RATE
    assert settings.pinion_speed == omega and settings.ramp_time == 0.05
    assert settings.full_rate_after == pytest.approx(0.1)
    window = settings.duration - settings.full_rate_after
    assert window >= max(0.05, 100 / mesh) - 1e-12
    assert window < max(0.05, 100 / mesh) + interval + 1e-12
    assert settings.duration == pytest.approx(settings.samples * interval)
    assert settings.full_rate >= max(BASE.full_rate, 32 * mesh)
    assert settings.full_rate % speed.OUTPUT_RATE == 0
    with pytest.raises(ValueError, match="mesh_cycles = 0"):
        speed.speed_settings(BASE, omega, 9, mesh_cycles=0)
    with pytest.raises(ValueError, match="settle_time = -1"):
        speed.speed_settings(BASE, omega, 9, settle_time=-1)


def _response(geometry, params, omega_deg_s, **options):
    settings = speed.speed_settings(BASE, math.radians(omega_deg_s), 9, **options)
    values, _, _ = speed.speed_point(simulate(geometry, settings, params))
    return values


def test_the_response_is_quasi_static_below_resonant_at_fn_and_isolated_above(geometry):
    """Far below f_n the dynamic transmission error is the loaded TCA's and the dynamic
    factor is near 1; where the mesh frequency meets f_n the response is amplified;
    well above it the gear can no longer follow (isolation)."""
    params = LINE.replace(mu_s=0.0, mu_d=0.0)      # the TCA is frictionless
    model = load_model(geometry["logarithmic"], params)
    natural = model.contact.natural_frequency(model.gear_inertia)
    assert 1000 < natural < 3000                       # a steel mesh mode, kHz range
    resonance = math.degrees(speed.resonance_speeds(natural, 9, orders=(1,))[0])
    static = ltca.loaded_tca(model.contact, BASE.load_torque, phases=256)
    te = static["transmission_error"].values
    static_rms = float(np.sqrt(np.mean((te - te.mean()) ** 2)))

    slow = _response(geometry["logarithmic"], params, resonance / 25, mesh_cycles=20, min_window=0.02)
    at = _response(geometry["logarithmic"], params, resonance, mesh_cycles=100, min_window=0.02)
    fast = _response(geometry["logarithmic"], params, resonance * 2.5, mesh_cycles=100, min_window=0.02)
    assert slow["dte_rms"] == pytest.approx(static_rms, rel=0.05)
    assert 1.0 < slow["dynamic_factor"] < 1.1
    assert at["dte_rms"] > 4 * slow["dte_rms"]
    assert at["dynamic_factor"] > 1.3
    assert fast["dte_rms"] < 0.5 * slow["dte_rms"]
    assert at["mesh_frequency"] == pytest.approx(natural, rel=1e-9)


#: The speed sweep of these runs: its speeds (a section that sets any of its keys needs
#: them, lsbg/schemas/config.schema.yaml) and a short steady window.
SWEEP = ["--set", "speed_sweep.pinion_speeds_deg_s={start: 40000, stop: 80000, count: 2}",
         "--set", "speed_sweep.mesh_cycles=20", "--set", "speed_sweep.min_window_s=0.01",
         "--set", "speed_sweep.settle_time_s=0.02", "--set", "speed_sweep.ramp_time_s=0.02"]


def speed_run(path, omega, out, *extra):
    return cli.main(["speed-run", "--geometry", str(path), "--engine", "compiled",
                     "--set", f"simulation.pinion_speed_deg_s={omega}", *SWEEP, *extra,
                     "--out", str(out)])


@pytest.fixture(scope="module")
def curve_file(geometry, tmp_path_factory):
    root = tmp_path_factory.mktemp("speed_runs")
    runs = []
    for trace, path in geometry.items():
        for omega in (40000, 80000):
            out = root / f"{trace}_w{omega}.nc"
            assert speed_run(path, omega, out) == 0
            runs.append(out)
    out = root / "speed_curve.nc"
    assert cli.main(["speed-curve", "--runs", *map(str, runs), "--out", str(out)]) == 0
    return out


def test_cli_writes_the_curve_with_units_and_the_natural_frequency(curve_file, geometry,
                                                                   capsys):
    with xr.open_dataset(curve_file) as curve:
        assert list(curve["trace"].values) == ["circular", "logarithmic"]
        np.testing.assert_allclose(curve["pinion_speed"].values, [40000, 80000])
        for name, (units, _) in speed.SPEED_QUANTITIES.items():
            assert curve[name].attrs["units"] == units
            assert np.all(np.isfinite(curve[name].values))
        assert curve["dte_spectrum"].dims == ("trace", "pinion_speed", "frequency")
        np.testing.assert_allclose(curve["mesh_frequency"].values,
                                   np.array([40000, 80000]) * 9 / 360)
        model = load_model(geometry["logarithmic"], LINE)
        natural = model.contact.natural_frequency(model.gear_inertia)
        assert float(curve["natural_frequency"].sel(trace="logarithmic")) == pytest.approx(
            natural, rel=1e-9)
        rows = line_model.speed_curve_table(curve)
        assert list(rows["gear_type"]) == ["SBG, paper's arc", "LSBG"]   # the SBG by its construction
        assert rows["resonance_speed_deg_s"].iloc[1] == pytest.approx(
            math.degrees(2 * math.pi * natural / 9), rel=1e-9)
        ratios = line_model.speed_ratio_table(curve)
        np.testing.assert_allclose(
            ratios["dte_rms_ratio"],
            curve["dte_rms"].sel(trace="circular") / curve["dte_rms"].sel(trace="logarithmic"))
    capsys.readouterr()
    assert cli.main(["mesh-mode", "--geometry", str(geometry["logarithmic"])]) == 0
    assert f"{natural:10.4g} Hz" in capsys.readouterr().out


def test_the_sweep_sets_what_the_simulation_section_would(curve_file, geometry, tmp_path,
                                                          capsys):
    """The speed sweep sets a run's duration, samples and the start of its full-rate record:
    the simulation section's keys for them are ignored by speed-run (still checked by the
    schema), the run is the same; the pinion speed is the simulation section's (the
    schema's default without --set); the former options are refused by argparse."""
    out = tmp_path / "run.nc"
    assert speed_run(geometry["logarithmic"], 40000, out, "--set", "simulation.duration_s=2",
                     "--set", "simulation.samples=1000",
                     "--set", "simulation.full_rate_after_s=0.5") == 0
    with xr.open_dataset(out) as run, \
            xr.open_dataset(curve_file.parent / "logarithmic_w40000.nc") as swept:
        assert run.attrs["solver_duration_s"] == swept.attrs["solver_duration_s"] < 1
        assert run.attrs["solver_samples"] == swept.attrs["solver_samples"] < 1000
        for name in ("gear_speed", "transmission_error", "gear_speed_full"):
            np.testing.assert_array_equal(run[name], swept[name])
    args = cli.build_parser().parse_args(["speed-run", "--geometry",
                                          str(geometry["logarithmic"]), "--out", str(out)])
    assert settings_of(args)["simulation"]["pinion_speed_deg_s"] == 7703
    for old in (["--pinion-speed", "40000"], ["--duration", "1"], ["--mesh-cycles", "20"]):
        with pytest.raises(SystemExit) as exit_:
            cli.main(["speed-run", "--geometry", str(geometry["logarithmic"]), *old,
                      "--out", str(tmp_path / "never.nc")])
        assert exit_.value.code == 2
        assert f"unrecognized arguments: {old[0]}" in capsys.readouterr().err
    assert not (tmp_path / "never.nc").exists()


def test_one_speed_sweep_key_is_enough(geometry):
    args = cli.build_parser().parse_args(["speed-run", "--geometry",
                                          str(geometry["logarithmic"]), "--set",
                                          "speed_sweep.mesh_cycles=20", "--out", "x.nc"])
    assert settings_of(args)["speed_sweep"]["mesh_cycles"] == 20


def test_curve_refuses_mixed_runs_and_point_model_runs(curve_file, geometry, tmp_path):
    runs = sorted(curve_file.parent.glob("*_w*.nc"))
    with xr.open_dataset(runs[0]) as first:
        point = first.load()
    point.attrs.pop("mesh_natural_frequency_hz")
    with pytest.raises(ValueError, match="mesh_natural_frequency_hz"):
        speed.speed_curve([point])
    with pytest.raises(ValueError, match="no speed-sweep runs"):
        speed.speed_curve([])
    datasets = [xr.open_dataset(run).load() for run in runs]
    with pytest.raises(ValueError, match="trace logarithmic has pinion speeds"):
        speed.speed_curve([ds for ds in datasets
                           if not (ds.attrs["design_trace"] == "logarithmic"
                                   and ds.attrs["solver_pinion_speed_deg_s"] > 50000)])


def test_figures_mark_the_resonances(curve_file):
    from lsbg.figures import speed as speed_figures

    with xr.open_dataset(curve_file) as curve:
        curve = curve.load()
    fig = speed_figures.plot_speed_curve(curve)
    axes = [ax for ax in fig.axes if ax.has_data()]
    assert len(axes) >= 3
    resonance = float(curve["resonance_speed"].sel(trace="logarithmic", order=1))
    marks = [line.get_xdata()[0] for line in axes[0].get_lines()
             if len(line.get_xdata()) == 2 and line.get_xdata()[0] == line.get_xdata()[1]]
    assert any(mark == pytest.approx(resonance) for mark in marks)
    campbell = speed_figures.plot_campbell(curve)
    assert campbell.axes


def test_spectrum_map_has_no_holes_where_the_bins_are_finer_than_the_spectrum():
    from lsbg.experiments.speed import _binned_peak

    frequency = np.arange(0.0, 1000.0, 20.0)          # 20 Hz resolution
    amplitude = np.exp(-((frequency - 400.0) / 100.0) ** 2)
    edges = np.linspace(0.0, 1200.0, 121)              # 10 Hz bins
    binned = _binned_peak(frequency, amplitude, edges)
    below = edges[:-1] <= frequency[-1]
    assert np.all(np.isfinite(binned[below])) and np.all(np.isnan(binned[~below]))
    assert np.nanmax(binned) == pytest.approx(1.0)


def test_a_driveline_curve_is_its_own_and_marks_higher_orders(curve_file, geometry, tmp_path,
                                                              capsys):
    """Under the torsional driveline a speed run records its boundary; a curve takes the
    runs of one boundary only, its natural frequency the linearised driveline's mesh mode,
    and gives the resonance speeds of as many mesh harmonics as asked."""
    runs = []
    for trace, path in geometry.items():
        for omega in (40000, 80000):
            out = tmp_path / f"{trace}_driveline_w{omega}.nc"
            assert speed_run(path, omega, out, "--set", "simulation.boundary=driveline") == 0
            runs.append(out)
    out = tmp_path / "curve.nc"
    assert cli.main(["speed-curve", "--runs", *map(str, runs), "--orders", "12",
                     "--out", str(out)]) == 0
    assert "logarithmic, driveline: f_n" in capsys.readouterr().out
    with xr.open_dataset(out) as curve, xr.open_dataset(runs[0]) as run, \
            xr.open_dataset(curve_file) as prescribed:
        assert curve.attrs["solver_boundary"] == "driveline"
        assert prescribed.attrs["solver_boundary"] == "prescribed_pinion"
        assert list(curve["order"].values) == list(range(1, 13))
        trace = run.attrs["design_trace"]
        natural = float(curve["natural_frequency"].sel(trace=trace))
        assert natural == pytest.approx(run.attrs["driveline_mode3_hz"], rel=1e-12)
        np.testing.assert_allclose(curve["resonance_speed"].sel(trace=trace).values,
                                   [natural * 360 / (k * 9) for k in range(1, 13)], rtol=1e-12)
    mixed = [xr.open_dataset(runs[0]).load(),
             xr.open_dataset(sorted(curve_file.parent.glob("*_w*.nc"))[0]).load()]
    with pytest.raises(ValueError, match="mixed solver_boundary"):
        speed.speed_curve(mixed)
    assert cli.main(["speed-curve", "--runs", *map(str, runs), "--orders", "2",
                     "--out", str(tmp_path / "never.nc")]) != 0
    assert "--orders 2: must be at least 3" in capsys.readouterr().err
