"""The sweep dataset and the summary table of short real runs, through the API and the CLI."""

import math

import numpy as np
import pandas as pd
import pytest
import xarray as xr
import yaml

from lsbg import cli, spectra, stats, study, theory
from lsbg.contact import ContactParameters
from lsbg.design import GearPairDesign
from lsbg.dynamics import SimulationSettings, simulate
from lsbg.export import write_geometry
from lsbg.ltca import ltca_for_geometry
from lsbg.results import FULL_RATE_VARIABLES, VARIABLES, write_dataset

SHORT = SimulationSettings(duration=0.05, samples=25, ramp_time=0.01)
# 26 instants 0, 0.002, ..., 0.05 s: 20 samples after 0.01 s, 4 subgroups of 5.
WINDOWS = dict(steady_state_after=0.01, window=(0.01, 0.05), subgroup_size=5)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """Point model: LSBG at 35 and 30 deg, SBG at 35 deg (pybullet) and LSBG at 35 deg
    (scipy); line model: LSBG and SBG at 35 deg (pybullet); their loaded TCAs."""
    root = tmp_path_factory.mktemp("study")
    points = {"lsbg35": ("logarithmic", 35), "sbg35": ("circular", 35),
              "lsbg30": ("logarithmic", 30)}
    paths = {}
    line = ContactParameters(model="line")
    for name, (trace, spiral) in points.items():
        geometry = root / "geometry" / name
        write_geometry(GearPairDesign.from_config({"trace": trace, "spiral_angle_deg": spiral}),
                       geometry)
        paths[name] = root / "runs" / f"{name}_pybullet.nc"
        write_dataset(simulate(geometry, SHORT), paths[name])
        if spiral == 35:
            paths[f"{name}_line"] = root / "runs" / f"{name}_line_pybullet.nc"
            write_dataset(simulate(geometry, SHORT, line), paths[f"{name}_line"])
            paths[f"{name}_mesh"] = root / "mesh" / f"{name}.nc"
            write_dataset(ltca_for_geometry(geometry, 1964.99, phases=64), paths[f"{name}_mesh"])
    paths["lsbg35_scipy"] = root / "runs" / "lsbg35_scipy.nc"
    write_dataset(simulate(root / "geometry" / "lsbg35", SHORT.replace(engine="scipy")),
                  paths["lsbg35_scipy"])
    return paths


@pytest.fixture(scope="module")
def pybullet_runs(runs):
    return [runs["lsbg35"], runs["sbg35"], runs["lsbg30"]]


@pytest.fixture(scope="module")
def sweep(pybullet_runs):
    return study.combine_runs(pybullet_runs)


def test_combine_runs_dims_coordinates_and_units(sweep, runs):
    assert dict(sweep.sizes) == {"contact_model": 1, "trace": 2, "spiral_angle": 2, "time": 26,
                                 "time_full": 2001}
    assert list(sweep.contact_model.values) == ["point"]
    assert list(sweep.trace.values) == ["logarithmic", "circular"]
    assert list(sweep.gear_type.values) == ["LSBG", "SBG"]
    assert list(sweep.spiral_angle.values) == [30.0, 35.0]
    assert sweep.spiral_angle.attrs["units"] == "degree"
    assert sweep.time.attrs["units"] == "s"
    for name, (units, long_name) in VARIABLES.items():
        assert sweep[name].dims == ("contact_model", "trace", "spiral_angle", "time")
        assert sweep[name].attrs["units"] == units and sweep[name].attrs["long_name"] == long_name
    for name, source in FULL_RATE_VARIABLES.items():
        assert sweep[name].dims == ("contact_model", "trace", "spiral_angle", "time_full")
        assert sweep[name].attrs["units"] == VARIABLES[source][0]
    sweep = sweep.sel(contact_model="point")
    with xr.open_dataset(runs["sbg35"]) as run:
        np.testing.assert_array_equal(
            sweep.gear_speed.sel(trace="circular", spiral_angle=35.0).values, run.gear_speed.values)
        np.testing.assert_array_equal(
            sweep.gear_speed_full.sel(trace="circular", spiral_angle=35.0).values,
            run.gear_speed_full.values)
        point = sweep.sel(trace="circular", spiral_angle=35.0)
        assert float(point.contact_ratio) == run.attrs["design_contact_ratio"]
        assert float(point.contact_ratio_face) == run.attrs["design_contact_ratio_face"]
        assert float(point.theory_gear_speed) == run.attrs["theory_gear_speed_deg_s"]
    assert sweep.contact_ratio.dims == ("trace", "spiral_angle")
    assert sweep.contact_ratio.attrs["units"] == "1"
    assert sweep.theory_tangential_force.attrs["units"] == "N"
    # the circular trace was not run at 30 deg
    missing = sweep.sel(trace="circular", spiral_angle=30.0)
    assert np.isnan(missing.gear_speed).all() and np.isnan(missing.contact_ratio)
    assert np.isfinite(sweep.gear_speed.sel(trace="logarithmic", spiral_angle=30.0)).all()


def test_combine_runs_stacks_contact_models_and_loaded_tcas(runs):
    combined = study.combine_runs([runs["lsbg35"], runs["lsbg35_line"], runs["sbg35_line"]],
                                  meshes=[runs["lsbg35_mesh"], runs["sbg35_mesh"]])
    assert list(combined.contact_model.values) == ["point", "line"]
    assert np.isnan(combined.gear_speed.sel(contact_model="point", trace="circular")).all()
    assert np.isfinite(combined.gear_speed.sel(contact_model="line", trace="circular")).all()
    with xr.open_dataset(runs["sbg35_mesh"]) as mesh:
        point = combined.sel(trace="circular", spiral_angle=35.0)
        assert float(point.static_transmission_error_peak_to_peak) == \
            mesh.attrs["transmission_error_peak_to_peak_urad"]
        np.testing.assert_array_equal(point.static_transmission_error.values,
                                      mesh.transmission_error.values)
        assert combined.mesh_stiffness.dims == ("trace", "spiral_angle", "mesh_phase")
    with pytest.raises(ValueError, match="lsbg35.nc: design point logarithmic, 35 deg already"):
        study.combine_runs([runs["lsbg35"]], meshes=[runs["lsbg35_mesh"], runs["lsbg35_mesh"]])
    with pytest.raises(ValueError, match="lsbg35_pybullet.nc: not a loaded-TCA"):
        study.combine_runs([runs["lsbg35"]], meshes=[runs["lsbg35"]])


def test_full_rate_record_holds_the_output_samples(runs):
    """The output instants inside the full-rate record are full-rate instants: the
    values agree, and the sampling phase of the paper's statistic that starts
    with the output sampling gives its standard deviation."""
    for name in ("lsbg35", "sbg35_line"):
        run = study.open_run(runs[name])
        assert run.attrs["solver_full_rate_hz"] == 50000.0
        t_full = run.time_full.values
        assert t_full[0] == pytest.approx(0.01) and t_full[-1] == pytest.approx(0.05)
        assert np.diff(t_full) == pytest.approx(2e-5)
        on_grid = np.isin(np.round(run.time.values, 9), np.round(t_full, 9))
        assert on_grid.sum() == 21
        for quantity, (variable, _) in study.FULL_RATE_OF.items():
            if quantity == "tangential_force_outer":
                continue
            full = run[variable].values
            np.testing.assert_allclose(full[::100], run[quantity].values[on_grid], rtol=1e-12)
            spread = spectra.sampling_phase_spread(study.full_rate_series(run, quantity, 0.01),
                                                   50000.0, 500.0)
            assert spread.size == 100
            assert spread[0] == pytest.approx(study.steady(run, quantity, 0.01).std(ddof=1),
                                              rel=1e-12)


def test_combine_runs_global_attributes(sweep, pybullet_runs):
    attrs = sweep.attrs
    assert attrs["Conventions"] == "CF-1.11"
    for key in ("title", "source", "history"):
        assert isinstance(attrs[key], str) and attrs[key]
    assert all(p.name in attrs["history"] for p in pybullet_runs)
    assert attrs["solver_engine"] == "pybullet"
    assert attrs["design_pinion_teeth"] == 9 and attrs["solver_samples"] == 25
    # what differs between the runs is not a global attribute
    assert "design_trace" not in attrs and "design_spiral_angle_deg" not in attrs
    assert all(isinstance(v, (str, int, float, np.number)) for v in attrs.values())


def test_combine_runs_rejects_mixed_engines_naming_the_file(runs):
    with pytest.raises(ValueError, match="lsbg35_scipy.nc.*engine 'scipy'"):
        study.combine_runs([runs["lsbg30"], runs["lsbg35_scipy"]])


def test_combine_runs_rejects_other_time_axes_and_duplicates(runs, tmp_path):
    with xr.open_dataset(runs["sbg35"]) as run:
        shifted = run.load().assign_coords(time=run.time.values * 2)
    other = tmp_path / "slow_time.nc"
    write_dataset(shifted, other)
    with pytest.raises(ValueError, match="slow_time.nc: time axis"):
        study.combine_runs([runs["lsbg35"], other])
    with pytest.raises(ValueError, match="already given"):
        study.combine_runs([runs["lsbg35"], runs["lsbg35"]])
    with pytest.raises(FileNotFoundError, match="nowhere.nc"):
        study.combine_runs([runs["lsbg35"], tmp_path / "nowhere.nc"])
    with pytest.raises(ValueError, match="no run files"):
        study.combine_runs([])


def test_summary_table_columns_and_values(runs, pybullet_runs):
    table = study.summary_table(pybullet_runs, **WINDOWS)
    assert list(table.columns) == list(study.SUMMARY_COLUMNS) == [
        "trace", "spiral_angle_deg", "contact_model", "engine", "run", "quantity", "mean", "std",
        "ad_statistic", "ad_pvalue", "theory", "error_rate_percent", "out_of_control",
        "full_rate_std", "sampling_std_min", "sampling_std_max", "dynamic_factor",
        "peak_to_peak", "harmonic_1", "harmonic_2", "harmonic_3"]
    assert len(table) == 3 * len(study.SUMMARY_QUANTITIES)
    with_theory = table[table.theory.notna()]
    assert set(table.quantity) - set(with_theory.quantity) == {"transmission_error"}
    np.testing.assert_allclose(
        with_theory.error_rate_percent,
        100 * (with_theory["mean"] - with_theory.theory).abs() / with_theory.theory)
    # the sampled std lies inside its spread over sampling phases
    assert (table.sampling_std_min <= table["std"] * (1 + 1e-12)).all()
    assert (table["std"] <= table.sampling_std_max * (1 + 1e-12)).all()
    torque = table[table.quantity == "contact_torque"]
    assert (torque.dynamic_factor > 1.0).all() and table.dynamic_factor.notna().sum() == 3
    assert set(table.run) == {"lsbg35_pybullet", "sbg35_pybullet", "lsbg30_pybullet"}
    with xr.open_dataset(runs["lsbg30"]) as run:
        rows = table[(table.trace == "logarithmic") & (table.spiral_angle_deg == 30.0)]
        assert list(rows.quantity) == list(study.SUMMARY_QUANTITIES)
        for row in rows.itertuples():
            x = stats.steady_state(run[row.quantity].values, run.time.values, 0.01)
            assert x.size == 20
            ad = stats.anderson_darling(x)
            assert (row.ad_statistic, row.ad_pvalue) == (ad.statistic, ad.pvalue)
            assert row.mean == pytest.approx(x.mean()) and row.std == pytest.approx(x.std(ddof=1))
            groups = stats.subgroups_from_window(run[row.quantity].values, run.time.values,
                                                 0.01, 0.05, 5)
            assert groups.shape == (4, 5)
            assert row.out_of_control == stats.xbar_r_chart(groups).out_of_control.size <= 4
        theories = dict(zip(rows.quantity, rows.theory))
    assert theories["gear_speed"] == pytest.approx(float(theory.gear_speed(7703.0, 9, 37)))
    assert theories["tangential_force"] == theories["tangential_force_outer"] == pytest.approx(
        23603.48, abs=0.01)
    assert theories["contact_torque"] == 1964.99
    assert set(table.engine) == {"pybullet"}


def test_summary_table_loaded_tca_rows(runs):
    table = study.summary_table([runs["sbg35_line"]], meshes=[runs["sbg35_mesh"]], **WINDOWS)
    mesh_rows = table[table.engine == "ltca"]
    assert list(mesh_rows.quantity) == ["static_transmission_error", "mesh_stiffness"]
    with xr.open_dataset(runs["sbg35_mesh"]) as mesh:
        te = mesh_rows.iloc[0]
        assert te.peak_to_peak == pytest.approx(np.ptp(mesh.transmission_error.values))
        assert te.harmonic_1 == mesh.attrs["transmission_error_harmonic_1_urad"]
        assert te.contact_model == "line" and te.run == "sbg35"
        assert mesh_rows.iloc[1]["mean"] == pytest.approx(mesh.mesh_stiffness.values.mean())
    assert mesh_rows.out_of_control.isna().all()
    assert table[table.engine != "ltca"].contact_model.unique().tolist() == ["line"]


def test_summary_table_default_windows_need_a_long_run(runs):
    # the paper's windows (after 0.2 s, 0.8-1.0 s) do not fit a 0.05 s run: the
    # error names the file and the quantity
    with pytest.raises(ValueError, match="sbg35_pybullet.nc: gear_speed: no sample after"):
        study.summary_table([runs["sbg35"]])
    with pytest.raises(ValueError, match="sbg35_pybullet.nc: gear_speed: .*window"):
        study.summary_table([runs["sbg35"]], steady_state_after=0.01)


def test_statistics_options_validates_keys():
    assert study.statistics_options(None) == {}
    assert study.statistics_options({"steady_state_after_s": 0.2,
                                     "control_chart_window_s": [0.8, 1.0],
                                     "subgroup_size": 4}) == {
        "steady_state_after": 0.2, "window": (0.8, 1.0), "subgroup_size": 4}
    for bad, key in (({"window": [0, 1]}, "statistics.window"),
                     ({"control_chart_window_s": [1.0, 0.8]}, "statistics.control_chart_window_s"),
                     ({"subgroup_size": 1}, "statistics.subgroup_size"),
                     ({"subgroup_size": True}, "statistics.subgroup_size"),
                     ({"steady_state_after_s": "soon"}, "statistics.steady_state_after_s")):
        with pytest.raises(ValueError, match=key):
            study.statistics_options(bad)


# ------------------------------------------------------------------ CLI
def test_cli_combine_writes_the_sweep_atomically(pybullet_runs, sweep, tmp_path, capsys):
    out = tmp_path / "results" / "sweep.nc"
    assert cli.main(["combine", "--runs", *map(str, pybullet_runs), "--out", str(out)]) == 0
    assert "3 runs" in capsys.readouterr().out
    assert [p.name for p in out.parent.iterdir()] == ["sweep.nc"]
    with xr.open_dataset(out) as written:
        xr.testing.assert_identical(written.drop_attrs(), sweep.drop_attrs())
        assert written.attrs["Conventions"] == "CF-1.11"


def test_cli_combine_mixed_engines_exit_2(runs, tmp_path, capsys):
    out = tmp_path / "sweep.nc"
    code = cli.main(["combine", "--runs", str(runs["lsbg30"]), str(runs["lsbg35_scipy"]),
                     "--out", str(out)])
    assert code == 2
    assert "lsbg35_scipy.nc" in capsys.readouterr().err
    assert not out.exists()


def test_cli_summary_reads_the_statistics_section(pybullet_runs, tmp_path):
    config = tmp_path / "study.yaml"
    config.write_text(yaml.safe_dump({
        "design": {"module_mm": 4.5}, "simulation": {"duration_s": 0.05},
        "statistics": {"steady_state_after_s": 0.01, "control_chart_window_s": [0.01, 0.05],
                       "subgroup_size": 5}}))
    out = tmp_path / "results" / "summary.csv"
    assert cli.main(["summary", "--runs", *map(str, pybullet_runs), "--config", str(config),
                     "--out", str(out)]) == 0
    written = pd.read_csv(out)
    assert list(written.columns) == list(study.SUMMARY_COLUMNS)
    expected = study.summary_table(pybullet_runs, **WINDOWS)
    pd.testing.assert_frame_equal(written, expected, check_exact=False, rtol=1e-12,
                                  check_dtype=False)
    assert [p.name for p in out.parent.iterdir()] == ["summary.csv"]
    # options override the configuration
    out2 = tmp_path / "summary2.csv"
    assert cli.main(["summary", "--runs", str(pybullet_runs[0]), "--config", str(config),
                     "--subgroup-size", "4", "--window", "0.018", "0.05",
                     "--out", str(out2)]) == 0
    assert len(pd.read_csv(out2)) == len(study.SUMMARY_QUANTITIES)


def test_cli_summary_bad_statistics_key_exit_2(pybullet_runs, tmp_path, capsys):
    config = tmp_path / "study.yaml"
    config.write_text(yaml.safe_dump({"statistics": {"steady_state_after": 0.2}}))
    out = tmp_path / "summary.csv"
    code = cli.main(["summary", "--runs", str(pybullet_runs[0]), "--config", str(config),
                     "--out", str(out)])
    assert code == 2
    err = capsys.readouterr().err
    assert "statistics.steady_state_after" in err and "unknown key" in err
    assert not out.exists()
    # a window that does not fit the runs: exit 2, naming the file
    code = cli.main(["summary", "--runs", str(pybullet_runs[0]), "--out", str(out)])
    assert code == 2 and "lsbg35_pybullet.nc" in capsys.readouterr().err
    assert not out.exists()


def test_spiral_angle_is_rounded_in_tables(runs):
    # 30 deg round-trips through radians as 29.999999999999996
    with xr.open_dataset(runs["lsbg30"]) as run:
        assert math.isclose(run.attrs["design_spiral_angle_deg"], 30.0)
    table = study.summary_table([runs["lsbg30"]], **WINDOWS)
    assert set(table.spiral_angle_deg) == {30.0}


# ------------------------------------------------------- report pieces
def test_engine_agreement_and_theory_table(runs):
    pybullet, scipy = study.open_run(runs["lsbg35"]), study.open_run(runs["lsbg35_scipy"])
    agreement = study.engine_agreement([pybullet, scipy, study.open_run(runs["sbg35"])], 0.01)
    assert list(agreement.quantity) == ["gear_speed", "tangential_force"]
    row = agreement.iloc[0]
    assert (row.gear_type, row.engine, row.reference) == ("LSBG", "pybullet", "scipy")
    x, y = study.steady(pybullet, "gear_speed", 0.01), study.steady(scipy, "gear_speed", 0.01)
    assert row.std_ratio == pytest.approx(x.std(ddof=1) / y.std(ddof=1))
    assert row.within_tolerance == (abs(row.std_ratio - 1) <= 0.03)
    table = study.theory_table([pybullet, study.open_run(runs["sbg35"])], 0.01)
    assert list(table.gear_type) == ["SBG"] * 3 + ["LSBG"] * 3
    lsbg_speed = table[(table.gear_type == "LSBG") & (table.quantity == "gear_speed")].iloc[0]
    assert lsbg_speed.simulated == pytest.approx(x.mean())
    assert lsbg_speed.paper_simulated == 1873.77 and lsbg_speed.paper_error_rate_percent == 0.0036
    assert np.isnan(table[table.quantity == "tangential_force_outer"].paper_simulated).all()


def test_open_pair_checks_the_gear_types(runs):
    pair = study.open_pair(runs["sbg35"], runs["lsbg35"])
    assert list(pair) == ["SBG", "LSBG"]
    assert study.open_pair("", None) is None
    with pytest.raises(ValueError, match="a LSBG run .* given as the SBG run"):
        study.open_pair(runs["lsbg35"], runs["sbg35"])
    with pytest.raises(ValueError, match="both"):
        study.open_pair(runs["sbg35"], "")


def test_fluctuation_conclusion_follows_the_data():
    rng = np.random.default_rng(3)
    calm, rough = rng.normal(0, 1, 400), rng.normal(0, 2, 400)
    sbg_calmer = {"gear_speed": stats.compare_fluctuation(calm, rough)}
    assert "contradict" in study.fluctuation_conclusion(sbg_calmer)
    lsbg_calmer = {"gear_speed": stats.compare_fluctuation(rough, calm)}
    text = study.fluctuation_conclusion(lsbg_calmer)
    assert "support the paper's conclusion" in text and "The paper's ratio" in text
    same = {"gear_speed": stats.compare_fluctuation(calm, rng.normal(0, 1, 400))}
    assert "No difference is significant" in study.fluctuation_conclusion(same)
