"""The summary table of short real runs (lsbg.aggregate.summary), through the API and the CLI."""

import math

import numpy as np
import pandas as pd
import pytest
import xarray as xr
import yaml

from lsbg import cli, stats
from lsbg.gear import theory
from lsbg.aggregate.summary import (SUMMARY_COLUMNS, SUMMARY_QUANTITIES, SUMMARY_UNITS,
                                    statistics_options, summary_table)


def test_summary_table_columns_and_values(runs, pybullet_runs, windows):
    table = summary_table(pybullet_runs, **windows)
    assert list(table.columns) == list(SUMMARY_COLUMNS) == [
        "trace", "spiral_angle_deg", "contact_model", "engine", "run", "quantity", "mean", "std",
        "ad_statistic", "ad_pvalue", "theory", "error_rate_percent", "out_of_control",
        "full_rate_std", "sampling_std_min", "sampling_std_max", "dynamic_factor",
        "peak_to_peak", "harmonic_1", "harmonic_2", "harmonic_3", "full_rate_std_below_1",
        "full_rate_std_1_3", "full_rate_std_4_7", "full_rate_std_8_up", "full_rate_std_mode"]
    assert len(table) == 3 * len(SUMMARY_QUANTITIES)
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
        assert list(rows.quantity) == list(SUMMARY_QUANTITIES)
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


def test_summary_table_loaded_tca_rows(runs, windows):
    table = summary_table([runs["sbg35_line"]], meshes=[runs["sbg35_mesh"]], **windows)
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
    # every row's quantity has the unit its dataset writes (the reports' unit column)
    with xr.open_dataset(runs["sbg35_mesh"]) as mesh, xr.open_dataset(runs["sbg35_line"]) as run:
        assert SUMMARY_UNITS["static_transmission_error"] == mesh.transmission_error.attrs["units"]
        assert SUMMARY_UNITS["mesh_stiffness"] == mesh.mesh_stiffness.attrs["units"]
        for quantity in table[table.engine != "ltca"].quantity.unique():
            assert SUMMARY_UNITS[quantity] == run[quantity].attrs["units"], quantity


def test_summary_table_default_windows_need_a_long_run(runs):
    # the paper's windows (after 0.2 s, 0.8-1.0 s) do not fit a 0.05 s run: the
    # error names the file and the quantity
    with pytest.raises(ValueError, match="sbg35_pybullet.nc: gear_speed: no sample after"):
        summary_table([runs["sbg35"]])
    with pytest.raises(ValueError, match="sbg35_pybullet.nc: gear_speed: .*window"):
        summary_table([runs["sbg35"]], steady_state_after=0.01)


def test_statistics_options_validates_keys():
    assert statistics_options(None) == {}
    assert statistics_options({"steady_state_after_s": 0.2,
                                     "control_chart_window_s": [0.8, 1.0],
                                     "subgroup_size": 4}) == {
        "steady_state_after": 0.2, "window": (0.8, 1.0), "subgroup_size": 4}
    for bad, key in (({"window": [0, 1]}, "statistics.window"),
                     ({"control_chart_window_s": [1.0, 0.8]}, "statistics.control_chart_window_s"),
                     ({"subgroup_size": 1}, "statistics.subgroup_size"),
                     ({"subgroup_size": True}, "statistics.subgroup_size"),
                     ({"steady_state_after_s": "soon"}, "statistics.steady_state_after_s")):
        with pytest.raises(ValueError, match=key):
            statistics_options(bad)


def test_cli_summary_reads_the_statistics_section(pybullet_runs, tmp_path, windows):
    config = tmp_path / "study.yaml"
    config.write_text(yaml.safe_dump({
        "design": {"module_mm": 4.5}, "simulation": {"duration_s": 0.05},
        "statistics": {"steady_state_after_s": 0.01, "control_chart_window_s": [0.01, 0.05],
                       "subgroup_size": 5}}))
    out = tmp_path / "results" / "summary.csv"
    assert cli.main(["summary", "--runs", *map(str, pybullet_runs), "--config", str(config),
                     "--out", str(out)]) == 0
    written = pd.read_csv(out)
    assert list(written.columns) == list(SUMMARY_COLUMNS)
    expected = summary_table(pybullet_runs, **windows)
    pd.testing.assert_frame_equal(written, expected, check_exact=False, rtol=1e-12,
                                  check_dtype=False)
    assert [p.name for p in out.parent.iterdir()] == ["summary.csv"]
    # --set overrides the configuration
    out2 = tmp_path / "summary2.csv"
    assert cli.main(["summary", "--runs", str(pybullet_runs[0]), "--config", str(config),
                     "--set", "statistics.subgroup_size=4",
                     "--set", "statistics.control_chart_window_s=[0.018, 0.05]",
                     "--out", str(out2)]) == 0
    written = pd.read_csv(out2)
    assert len(written) == len(SUMMARY_QUANTITIES)
    expected = summary_table(pybullet_runs[:1], steady_state_after=0.01, window=(0.018, 0.05),
                             subgroup_size=4)
    pd.testing.assert_frame_equal(written, expected, check_exact=False, rtol=1e-12,
                                  check_dtype=False)


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


def test_spiral_angle_is_rounded_in_tables(runs, windows):
    # 30 deg round-trips through radians as 29.999999999999996
    with xr.open_dataset(runs["lsbg30"]) as run:
        assert math.isclose(run.attrs["design_spiral_angle_deg"], 30.0)
    table = summary_table([runs["lsbg30"]], **windows)
    assert set(table.spiral_angle_deg) == {30.0}


# ----------------------------------------------------------- contact state
def test_contact_state_rows_of_tcas_and_maps(runs, tmp_path, windows):
    from lsbg.files import write_dataset
    from lsbg.aggregate.summary import CONTACT_STATE_QUANTITIES, tca_summary, vh_summary
    from tests.aggregate.test_combine import synthetic_tca, synthetic_vh_map

    tca = synthetic_tca("circular", 35.0, te_pp=50.0)
    (row,) = tca_summary(tca)
    assert (row["engine"], row["quantity"], row["trace"], row["spiral_angle_deg"]) == (
        "tca", "unloaded_transmission_error", "circular", 35.0)
    assert row["peak_to_peak"] == pytest.approx(50.0)
    assert row["mean"] == pytest.approx(tca.transmission_error.values.mean())
    assert row["std"] == pytest.approx(tca.transmission_error.values.std(ddof=1))
    assert row["contact_model"] is None and row["out_of_control"] is None
    vh = synthetic_vh_map("circular", 35.0, axes=("P", "Sigma"))
    rows = vh_summary(vh)
    assert [r["quantity"] for r in rows] == [f"{q}_per_0_1_{axis}" for axis in ("P", "Sigma")
                                             for q in CONTACT_STATE_QUANTITIES]
    assert rows[0]["quantity"] == "pattern_shift_lengthwise_per_0_1_P"
    for r in rows:
        assert r["mean"] == vh.attrs[r["quantity"]] and r["engine"] == "tca"
        assert np.isnan(r["std"]) and np.isnan(r["peak_to_peak"])
    # the units the combined dataset writes (lsbg.aggregate.combine.add_contact_state)
    from lsbg.aggregate.combine import add_contact_state
    from tests.aggregate.test_combine import _points

    combined = add_contact_state(_points(), [tca], [vh])
    for quantity in [r["quantity"] for r in rows]:
        assert SUMMARY_UNITS[quantity] == combined[quantity].attrs["units"], quantity
    assert SUMMARY_UNITS["unloaded_transmission_error"] == tca.transmission_error.attrs["units"]
    # the quantities are the map's sensitivities (lsbg.tca.vh_map)
    from lsbg.tca.vh_map import SENSITIVITY_QUANTITIES

    assert tuple(CONTACT_STATE_QUANTITIES) == SENSITIVITY_QUANTITIES
    # through summary_table and the CLI: after the runs' and the loaded TCAs' rows
    files = [tmp_path / "tca" / "circular_beta35.nc", tmp_path / "vh" / "circular_beta35.nc"]
    write_dataset(tca, files[0])
    write_dataset(vh, files[1])
    table = summary_table([runs["sbg35_line"]], meshes=[runs["sbg35_mesh"]], tca=[files[0]],
                          vh_maps=[files[1]], **windows)
    state = table[table.engine == "tca"]
    assert len(state) == 1 + 2 * len(CONTACT_STATE_QUANTITIES)
    assert list(table.engine.iloc[-len(state):]) == ["tca"] * len(state)
    assert set(state.run) == {"circular_beta35"} and state.contact_model.isna().all()
    out = tmp_path / "summary.csv"
    assert cli.main(["summary", "--runs", str(runs["sbg35_line"]), "--tca", str(files[0]),
                     "--vh", str(files[1]), "--set", "statistics.steady_state_after_s=0.01",
                     "--set", "statistics.control_chart_window_s=[0.01, 0.05]",
                     "--set", "statistics.subgroup_size=5", "--out", str(out)]) == 0
    written = pd.read_csv(out)
    assert list(written.columns) == list(SUMMARY_COLUMNS)
    assert (written.engine == "tca").sum() == len(state)
    value = written[written.quantity == "transmission_error_loaded_pp_per_0_1_Sigma"]["mean"]
    assert float(value.iloc[0]) == vh.attrs["transmission_error_loaded_pp_per_0_1_Sigma"]


def test_the_design_and_the_load_that_vary_are_columns(runs, windows, tmp_path):
    """summary.csv names what differs between the runs: a face width or a load that is not
    the same for every row is a column; the same design everywhere adds none."""
    from lsbg.dynamics.dataset import open_run
    from lsbg.files import write_dataset

    same = summary_table([runs["lsbg35"], runs["sbg35"]], **windows)
    assert list(same.columns) == list(SUMMARY_COLUMNS)
    other = open_run(runs["lsbg35"])
    other.attrs.update(design_face_width_mm=30.0, solver_load_torque_N_m=1000.0)
    write_dataset(other, tmp_path / "wider.nc")
    table = summary_table([runs["lsbg35"], tmp_path / "wider.nc"], **windows)
    assert list(table.columns) == [*SUMMARY_COLUMNS, "design_face_width_mm", "load_torque_N_m"]
    rows = len(SUMMARY_QUANTITIES)
    assert table["design_face_width_mm"].tolist() == [25.0] * rows + [30.0] * rows
    assert table["load_torque_N_m"].tolist() == [1964.99] * rows + [1000.0] * rows


def test_summary_table_splits_every_full_rate_std_by_band(runs, windows):
    from lsbg.aggregate.runs import full_rate_series, run_band_split

    table = summary_table([runs["sbg35_line"], runs["lsbg35"]], **windows)
    harmonic = ["full_rate_std_below_1", "full_rate_std_1_3", "full_rate_std_4_7",
                "full_rate_std_8_up"]
    runs_rows = table[table.engine != "ltca"]
    assert runs_rows[harmonic].notna().all().all()
    with xr.open_dataset(runs["sbg35_line"]) as run:
        for row in runs_rows[runs_rows.contact_model == "line"].itertuples():
            split = run_band_split(run, row.quantity, windows["steady_state_after"])
            # the squares add up to the variance over whole mesh periods, which is within
            # a few per cent of the full record's (7 of 7.7 periods here)
            parts = sum(getattr(row, c) ** 2 for c in harmonic)
            assert parts == pytest.approx(split.total, rel=1e-9)
            full = full_rate_series(run, row.quantity, windows["steady_state_after"])
            assert math.sqrt(parts) == pytest.approx(full.std(ddof=1), rel=0.1)
            # the line model's mesh mode lies near the 9th mesh harmonic
            assert 0 < row.full_rate_std_mode <= math.sqrt(split.total) * (1 + 1e-12)
    point = runs_rows[runs_rows.contact_model == "point"]
    assert point.full_rate_std_mode.isna().all()   # a point-model run records no mesh mode
