"""``lsbg sweep-run`` and ``lsbg sweep-combine``: a swept run is the single run with the same
settings, bit for bit; the combined dataset holds the runs' own statistics."""

import numpy as np
import pytest
import xarray as xr
import yaml

from lsbg import cli
from lsbg.gear.design import GearPairDesign
from lsbg.solid.export import write_geometry
from lsbg.aggregate.runs import steady

SHORT = {"simulation": {"duration_s": 0.05, "samples": 25, "ramp_time_s": 0.01,
                        "full_rate_after_s": 0.01},
         "statistics": {"steady_state_after_s": 0.01, "control_chart_window_s": [0.01, 0.05],
                        "subgroup_size": 5}}


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    root = tmp_path_factory.mktemp("sweep_cli")
    geometry = root / "logarithmic_beta35"
    write_geometry(GearPairDesign(), geometry)
    config = root / "config.yaml"
    config.write_text(yaml.safe_dump(SHORT))
    runs = [root / f"mu{k}.nc" for k in range(3)]
    argv = ["sweep-run", "--geometry", geometry, "--config", config, "--set", "contact.model=line",
            "--sweep", "friction"]
    for path, mu in zip(runs, (0.0, 0.05, 0.15)):
        argv += ["--point", path, f"contact.dynamic_friction={mu}"]
    assert cli.main([str(a) for a in argv]) == 0
    return {"root": root, "geometry": geometry, "config": config, "runs": runs}


def test_a_swept_run_is_the_single_run_with_its_settings(world):
    single = world["root"] / "single.nc"
    assert cli.main([str(a) for a in ["simulate", "--geometry", world["geometry"], "--engine",
                                      "compiled", "--set", "contact.model=line", "--config",
                                      world["config"], "--set", "contact.dynamic_friction=0.05",
                                      "--out", single]]) == 0
    with xr.open_dataset(world["runs"][1]) as swept, xr.open_dataset(single) as direct:
        for name in ("gear_speed", "tangential_force", "gear_speed_full"):
            np.testing.assert_array_equal(swept[name], direct[name])
        assert swept.attrs["sweep_contact_dynamic_friction"] == 0.05
        assert swept.attrs["sweep_name"] == "friction"
        assert swept.attrs["contact_dynamic_friction_coefficient"] == pytest.approx(0.05)
        assert swept.attrs["contact_model"] == direct.attrs["contact_model"] == "line"
    # and friction does change the run
    with xr.open_dataset(world["runs"][0]) as a, xr.open_dataset(world["runs"][2]) as b:
        assert not np.array_equal(a["gear_speed_full"], b["gear_speed_full"])


def test_the_combined_dataset_holds_each_runs_statistics(world):
    out, table = world["root"] / "friction.nc", world["root"] / "friction.csv"
    assert cli.main([str(a) for a in ["sweep-combine", "--runs", *world["runs"], "--config",
                                      world["config"], "--out", out, "--csv", table]]) == 0
    with xr.open_dataset(out) as ds:
        assert ds["contact.dynamic_friction"].values.tolist() == [0.0, 0.05, 0.15]
        assert ds["contact.dynamic_friction"].attrs["units"] == "1"
        assert ds["gear_speed_std"].attrs["units"] == "deg/s"
        for k, path in enumerate(world["runs"]):
            with xr.open_dataset(path) as run:
                expected = steady(run, "gear_speed", 0.01).std(ddof=1)
            value = ds["gear_speed_std"].sel(trace="logarithmic", spiral_angle=35.0)[k]
            assert float(value) == pytest.approx(float(expected), rel=1e-12)
        assert (ds["dynamic_factor"] >= 1).all()
    import pandas as pd

    rows = pd.read_csv(table)
    assert rows["contact.dynamic_friction"].tolist().count(0.05) == rows["quantity"].nunique()


def test_a_swept_run_records_the_quasi_static_contact_of_lsbg_ltca_and_tca(world):
    """A point's quasi-static figures are those lsbg ltca (loaded TE, uniform bed) and lsbg
    tca (bearing pattern) give for its settings; more lengthwise crowning shortens the
    pattern."""
    from lsbg.experiments.sweeps import CONTACT_FIGURES

    root, figures = world["root"], {}
    for crowning in (10, 40):
        run, mesh, tca = (root / f"{name}{crowning}.nc" for name in ("crown", "ltca", "tca"))
        setting = f"flank_modification.lengthwise_crowning_um={crowning}"
        common = ["--geometry", world["geometry"], "--config", world["config"]]
        assert cli.main([str(a) for a in ["sweep-run", *common, "--set", "contact.model=line",
                                          "--sweep", "crowning", "--point", run, setting]]) == 0
        assert cli.main([str(a) for a in ["ltca", *common, "--set", setting,
                                          "--out", mesh]]) == 0
        assert cli.main([str(a) for a in ["tca", *common, "--set", setting, "--out", tca]]) == 0
        with xr.open_dataset(run) as r, xr.open_dataset(mesh) as m, xr.open_dataset(tca) as t:
            figures[crowning] = {k: r.attrs[f"static_{k}"] for k in CONTACT_FIGURES}
            for name, (kind, attribute, _, _) in CONTACT_FIGURES.items():
                source = m if kind == "loaded" else t
                assert figures[crowning][name] == pytest.approx(source.attrs[attribute],
                                                                rel=1e-12), name
    assert figures[40]["pattern_length"] < figures[10]["pattern_length"]
    assert figures[40]["loaded_te_peak_to_peak"] != figures[10]["loaded_te_peak_to_peak"]


def test_a_design_point_of_its_own_and_bad_points(world, capsys):
    wide = world["root"] / "wide.nc"
    assert cli.main([str(a) for a in ["sweep-run", "--geometry", world["geometry"], "--config",
                                      world["config"], "--set", "contact.model=line",
                                      "--sweep", "width", "--point", wide,
                                      "design.face_width_mm=20"]]) == 0
    with xr.open_dataset(wide) as ds:
        assert ds.attrs["design_face_width_mm"] == pytest.approx(20)
        assert ds.attrs["design_trace"] == "logarithmic"
        assert ds.attrs["design_spiral_angle_deg"] == pytest.approx(35)
        assert ds.attrs["contact_model"] == "line"
    capsys.readouterr()
    for point, message in ((["x.nc", "statistics.subgroup_size=4"], "must be SECTION.KEY=VALUE"),
                           (["x.nc", "contact.dynamic_friction=-1"], "dynamic_friction"),
                           (["contact.slices=4"], "the output file comes first")):
        argv = ["sweep-run", "--geometry", str(world["geometry"]), "--sweep", "s", "--point",
                *[str(world["root"] / p) if p.endswith(".nc") else p for p in point]]
        assert cli.main(argv) == 2
        err = capsys.readouterr().err
        assert message in err and err.count("\n") == 1, err
    assert not (world["root"] / "x.nc").exists()
    assert cli.main(["sweep-combine", "--runs", str(world["root"] / "wide.nc"),
                     str(world["runs"][0]), "--out", str(world["root"] / "mixed.nc")]) == 2
    assert "runs of several sweeps: friction, width" in capsys.readouterr().err


def test_the_contact_model_is_a_setting(world, capsys):
    """``--set contact.model=...`` (the former --contact-model) sets the model of a batch;
    the former option is refused by argparse."""
    out = world["root"] / "point.nc"
    assert cli.main([str(a) for a in ["sweep-run", "--geometry", world["geometry"], "--config",
                                      world["config"], "--set", "contact.model=point",
                                      "--sweep", "model", "--point", out,
                                      "contact.dynamic_friction=0.05"]]) == 0
    with xr.open_dataset(out) as ds:
        assert ds.attrs["contact_model"] == "point"
    with pytest.raises(SystemExit) as exit_:
        cli.main([str(a) for a in ["sweep-run", "--geometry", world["geometry"],
                                   "--contact-model", "line", "--sweep", "s", "--point",
                                   world["root"] / "y.nc", "contact.slices=4"]])
    assert exit_.value.code == 2
    assert "unrecognized arguments: --contact-model line" in capsys.readouterr().err
    assert not (world["root"] / "y.nc").exists()
