"""The sweep dataset of short real runs (lsbg.aggregate.combine), through the API and the CLI."""

import numpy as np
import pytest
import xarray as xr

from lsbg import cli
from lsbg.aggregate.combine import combine_runs
from lsbg.dynamics.dataset import FULL_RATE_VARIABLES, VARIABLES
from lsbg.files import write_dataset


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
        # (a long definition is the description; the label is short: lsbg.files.short_labels)
        attrs = sweep[name].attrs
        assert attrs["units"] == units
        assert attrs.get("description", attrs["long_name"]) == long_name
        assert len(attrs["long_name"]) <= 40
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
        shifted = run.load().assign_coords(time=run.time.copy(data=run.time.values * 2))
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


# ----------------------------------------------------------- contact state
def synthetic_tca(trace="logarithmic", spiral=35.0, te_pp=48.0, positions=8):
    """A small dataset shaped like an unloaded TCA (lsbg.tca.analysis.tooth_contact_analysis)."""
    phase = np.arange(positions) / positions
    te = 0.5 * te_pp * np.cos(2 * np.pi * phase)
    return xr.Dataset(
        {"transmission_error": ("mesh_phase", te, {"units": "urad",
                                                    "long_name": "unloaded transmission error"})},
        coords={"mesh_phase": ("mesh_phase", phase, {"units": "1"})},
        attrs={"design_trace": trace, "design_spiral_angle_deg": spiral,
               "transmission_error_peak_to_peak_urad": float(np.ptp(te)),
               "pattern_centre_cone_distance_mm": 73.4, "pattern_centre_height_mm": 4.1,
               "pattern_length_mm": 15.5, "pattern_length_per_face_width": 0.62,
               "edge_contact_share": 0.25, "backlash_min_urad": 1300.0})


def synthetic_vh_map(trace="logarithmic", spiral=35.0, steps=3, axes=("E", "P")):
    """A small dataset shaped like a V-H map (lsbg.tca.vh_map.misalignment_map): every
    variable is a plane a + 10 x + 100 y, so each cell says where it sits."""
    values = np.linspace(-0.1, 0.1, steps)
    x, y = np.meshgrid(values, values, indexing="ij")
    variables = {
        "pattern_shift_lengthwise": ("mm", "movement of the pattern's centre towards the heel"),
        "pattern_shift_profile": ("mm", "movement of the pattern's centre towards the gear's tip"),
        "transmission_error_unloaded_pp": ("urad", "unloaded transmission error, peak to peak"),
        "transmission_error_loaded_pp": ("urad", "loaded transmission error, peak to peak"),
        "edge_contact_share": ("1", "share of mesh positions whose contact ellipse reaches an "
                                    "edge"),
    }
    units = {"E": "mm", "P": "mm", "G": "mm", "Sigma": "degree"}
    attrs = {"design_trace": trace, "design_spiral_angle_deg": spiral, "axes": " ".join(axes),
             "load_torque_N_m": 1964.99}
    for k, letter in enumerate(axes):
        for n, name in enumerate(variables):
            attrs[f"{name}_per_0_1_{letter}"] = float(n + 10 * k + spiral)
    return xr.Dataset(
        {name: (axes, n + 10 * x + 100 * y, {"units": u, "long_name": text})
         for n, (name, (u, text)) in enumerate(variables.items())},
        coords={a: (a, values, {"units": units[a], "long_name": f"displacement {a}"})
                for a in axes},
        attrs=attrs)


def _points(traces=("logarithmic", "circular"), angles=(30.0, 35.0)):
    """A stand-in for the sweep dataset: its design-point axes and one variable."""
    return xr.Dataset(
        {"contact_ratio": (("trace", "spiral_angle"), np.ones((len(traces), len(angles))),
                           {"units": "1"})},
        coords={"trace": ("trace", list(traces)),
                "gear_type": ("trace", [{"logarithmic": "LSBG"}.get(t, "SBG") for t in traces]),
                "spiral_angle": ("spiral_angle", list(angles), {"units": "degree"})})


def test_add_contact_state_stacks_tcas_and_maps_on_the_union_grid():
    from lsbg.aggregate.combine import TCA_VARIABLES, add_contact_state

    sweep = _points()
    tcas = [synthetic_tca("logarithmic", 35.0, te_pp=48.0),
            synthetic_tca("circular", 30.0, te_pp=55.0)]
    maps = [synthetic_vh_map("logarithmic", 35.0, steps=5),      # the paper's point
            synthetic_vh_map("circular", 30.0, steps=3)]         # a sweep point
    out = add_contact_state(sweep, tcas, maps)
    assert "unloaded_transmission_error_peak_to_peak" not in sweep     # sweep not changed
    # one value per design point from each unloaded TCA, NaN where none
    for attr, (name, units, long_name) in TCA_VARIABLES.items():
        assert out[name].dims == ("trace", "spiral_angle")
        assert out[name].attrs == {"units": units, "long_name": long_name}
        assert float(out[name].sel(trace="circular", spiral_angle=30.0)) == tcas[1].attrs[attr]
        assert np.isnan(out[name].sel(trace="circular", spiral_angle=35.0))
    assert float(out.unloaded_transmission_error_peak_to_peak.sel(
        trace="logarithmic", spiral_angle=35.0)) == pytest.approx(48.0)
    # the maps on the union of their grids: 5 values per axis, the 3-step map on 3 of them
    assert out.vh_pattern_shift_lengthwise.dims == ("trace", "spiral_angle", "E", "P")
    np.testing.assert_allclose(out.E.values, np.linspace(-0.1, 0.1, 5))
    assert out.E.attrs["units"] == "mm" and out.E.attrs["long_name"] == "displacement E"
    small = out.vh_transmission_error_loaded_pp.sel(trace="circular", spiral_angle=30.0).values
    assert np.isfinite(small).sum() == 9
    np.testing.assert_allclose(small[::2, ::2], maps[1].transmission_error_loaded_pp.values)
    assert np.isnan(small[1]).all() and np.isnan(small[:, 3]).all()
    full = out.vh_pattern_shift_profile.sel(trace="logarithmic", spiral_angle=35.0).values
    np.testing.assert_allclose(full, maps[0].pattern_shift_profile.values)
    assert np.isnan(out.vh_pattern_shift_profile.sel(trace="logarithmic", spiral_angle=30.0)).all()
    assert out.vh_edge_contact_share.attrs["units"] == "1"
    assert out.vh_pattern_shift_lengthwise.attrs["long_name"].startswith("V-H map: movement")
    # each sensitivity, per design point, in the quantity's unit per 0.1 of the axis
    for letter in ("E", "P"):
        name = f"pattern_shift_lengthwise_per_0_1_{letter}"
        assert out[name].dims == ("trace", "spiral_angle")
        assert out[name].attrs["units"] == "mm/(0.1 mm)"
        assert f"per 0.1 mm of displacement {letter}" in out[name].attrs["long_name"]
        assert float(out[name].sel(trace="circular", spiral_angle=30.0)) == \
            maps[1].attrs[name]
    assert out.transmission_error_loaded_pp_per_0_1_P.attrs["units"] == "urad/(0.1 mm)"
    for var in out.data_vars.values():
        assert "units" in var.attrs, var.name
    assert all("long_name" in var.attrs for name, var in out.data_vars.items()
               if name != "contact_ratio")


def test_add_contact_state_adds_design_points_the_runs_lack():
    from lsbg.aggregate.combine import add_contact_state

    out = add_contact_state(_points(traces=("logarithmic",), angles=(30.0,)),
                            vh_maps=[synthetic_vh_map("circular", 35.0, axes=("G", "Sigma"))])
    assert list(out.trace.values) == ["logarithmic", "circular"]
    assert list(out.gear_type.values) == ["LSBG", "SBG"]
    assert list(out.spiral_angle.values) == [30.0, 35.0]
    assert out.spiral_angle.attrs["units"] == "degree"
    assert np.isnan(out.contact_ratio.sel(trace="circular")).all()
    assert float(out.contact_ratio.sel(trace="logarithmic", spiral_angle=30.0)) == 1.0
    assert out.vh_pattern_shift_lengthwise.dims == ("trace", "spiral_angle", "G", "Sigma")
    assert out.transmission_error_unloaded_pp_per_0_1_Sigma.attrs["units"] == \
        "urad/(0.1 degree)"
    xr.testing.assert_identical(add_contact_state(_points()), _points())   # nothing to add


def test_add_contact_state_rejects_duplicates_and_other_axes():
    from lsbg.aggregate.combine import add_contact_state

    twice = synthetic_tca()
    twice.encoding["source"] = "results/tca/logarithmic_beta35.nc"
    with pytest.raises(ValueError, match="logarithmic_beta35.nc: unloaded TCA of design point "
                                         "logarithmic, 35 deg already given"):
        add_contact_state(_points(), [synthetic_tca(), twice])
    other = synthetic_vh_map("circular", 30.0, axes=("G", "P"))
    other.encoding["source"] = "results/vh/circular_beta30.nc"
    with pytest.raises(ValueError, match="circular_beta30.nc: V-H map on the axes G P"):
        add_contact_state(_points(), vh_maps=[synthetic_vh_map(), other])


def test_cli_combine_adds_the_contact_state(pybullet_runs, tmp_path, capsys):
    files = {}
    for name, ds in (("tca", synthetic_tca("circular", 35.0)),
                     ("vh", synthetic_vh_map("circular", 35.0))):
        files[name] = tmp_path / name / "circular_beta35.nc"
        write_dataset(ds, files[name])
    out = tmp_path / "sweep.nc"
    assert cli.main(["combine", "--runs", *map(str, pybullet_runs), "--tca", str(files["tca"]),
                     "--vh", str(files["vh"]), "--out", str(out)]) == 0
    with xr.open_dataset(out) as ds:
        assert ds.pattern_length.sel(trace="circular", spiral_angle=35.0) == 15.5
        assert np.isnan(ds.pattern_length.sel(trace="logarithmic", spiral_angle=35.0))
        assert ds.vh_pattern_shift_lengthwise.sizes["E"] == 3
        assert "1 unloaded TCAs and 1 V-H maps" in ds.attrs["history"]
        assert "tca/circular_beta35.nc" in ds.attrs["history"]
    # a run file is not a TCA: exit 2, naming the file
    code = cli.main(["combine", "--runs", str(pybullet_runs[0]), "--tca", str(pybullet_runs[0]),
                     "--out", str(tmp_path / "bad.nc")])
    assert code == 2 and "not an unloaded-TCA dataset" in capsys.readouterr().err
