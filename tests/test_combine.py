"""The sweep dataset of short real runs (lsbg.combine), through the API and the CLI."""

import numpy as np
import pytest
import xarray as xr

from lsbg import cli
from lsbg.combine import combine_runs
from lsbg.results import FULL_RATE_VARIABLES, VARIABLES, write_dataset


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
    combined = combine_runs([runs["lsbg35"], runs["lsbg35_line"], runs["sbg35_line"]],
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
        combine_runs([runs["lsbg35"]], meshes=[runs["lsbg35_mesh"], runs["lsbg35_mesh"]])
    with pytest.raises(ValueError, match="lsbg35_pybullet.nc: not a loaded-TCA"):
        combine_runs([runs["lsbg35"]], meshes=[runs["lsbg35"]])


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
        combine_runs([runs["lsbg30"], runs["lsbg35_scipy"]])


def test_combine_runs_rejects_other_time_axes_and_duplicates(runs, tmp_path):
    with xr.open_dataset(runs["sbg35"]) as run:
        shifted = run.load().assign_coords(time=run.time.values * 2)
    other = tmp_path / "slow_time.nc"
    write_dataset(shifted, other)
    with pytest.raises(ValueError, match="slow_time.nc: time axis"):
        combine_runs([runs["lsbg35"], other])
    with pytest.raises(ValueError, match="already given"):
        combine_runs([runs["lsbg35"], runs["lsbg35"]])
    with pytest.raises(FileNotFoundError, match="nowhere.nc"):
        combine_runs([runs["lsbg35"], tmp_path / "nowhere.nc"])
    with pytest.raises(ValueError, match="no run files"):
        combine_runs([])


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
