"""``lsbg optimise``: bad input named with exit code 2 and nothing written; a tiny run
writes the front and says what it chose."""

import pytest
import xarray as xr

from lsbg import cli
from lsbg.gear.design import GearPairDesign
from lsbg.solid.export import write_geometry

TINY = ["optimise.population=4", "optimise.generations=1", "optimise.phases=8",
        "misalignment_map.range=0.02", "optimise.edge_load_tolerance=1",
        "optimise.bounds.lengthwise_crowning_um=[30, 40]",
        "optimise.bounds.profile_crowning_um=[10, 15]",
        "optimise.bounds.pinion_tip_relief_um=[10, 12]",
        "optimise.bounds.gear_tip_relief_um=[10, 12]",
        "optimise.bounds.bias_um=[0, 0]", "optimise.bounds.spiral_angle_correction_um=[0, 0]",
        "optimise.bounds.pressure_angle_correction_um=[0, 0]"]


@pytest.fixture(scope="module")
def geometry(tmp_path_factory):
    folder = tmp_path_factory.mktemp("optimise_cli") / "circular_beta35"
    write_geometry(GearPairDesign.from_config({"trace": "circular"}), folder, step=False)
    return folder


def run(geometry, out, *settings):
    argv = ["optimise", "--geometry", str(geometry), "--out", str(out)]
    for text in settings:
        argv += ["--set", text]
    return cli.main(argv)


@pytest.mark.parametrize("setting, message", [
    ("optimise.bounds.lengthwise_crowning_um=[60, 5]",
     "optimise.bounds.lengthwise_crowning_um = [60, 5]: the lower bound is above the upper"),
    ("optimise.objectives=[noise]", "optimise.objectives[0]: 'noise' is not one of"),
    ("optimise.choose_from=nearest", "optimise.choose_from: 'nearest' is not one of"),
    ("optimise.population=1000", "optimise.population = 1000, optimise.generations = 18: "),
])
def test_bad_input_is_one_line_and_nothing_is_written(geometry, tmp_path, capsys, setting,
                                                      message):
    out = tmp_path / "front.nc"
    assert run(geometry, out, setting) == 2
    error = capsys.readouterr().err
    assert error.startswith(f"lsbg optimise: error: {message}") and error.count("\n") == 1
    assert not out.exists()


def test_a_tiny_run_writes_its_front(geometry, tmp_path, capsys):
    out = tmp_path / "front.nc"
    assert run(geometry, out, *TINY) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("lsbg optimise: circular: ")
    with xr.open_dataset(out) as ds:
        assert ds.sizes["individual"] == 4 and ds.attrs["population"] == 4
        assert ds.attrs["history"].startswith("lsbg ")  # the command line as typed
        chosen = ds.attrs["chosen"]
    assert (chosen >= 0) == any(line.startswith("lsbg optimise: chosen (knee") for line in lines)


@pytest.mark.parametrize("setting, message", [
    ("optimise.release.criteria=[mesh_loss]",
     "optimise.release.criteria[0]: 'mesh_loss' is not one of"),
    ("optimise.release.largest_positions=32",
     "optimise.release.largest_positions = 32: at least twice optimise.phases = 24"),
])
def test_release_bad_input_is_one_line_and_nothing_is_written(geometry, tmp_path, capsys,
                                                              setting, message):
    out, overlay = tmp_path / "release.nc", tmp_path / "best.yaml"
    argv = ["release", "--geometry", str(geometry), "--front", str(tmp_path / "front.nc"),
            "--compliance-file", str(tmp_path / "compliance.nc"), "--out", str(out),
            "--overlay-out", str(overlay), "--set", setting]
    assert cli.main(argv) == 2
    error = capsys.readouterr().err
    assert error.startswith(f"lsbg release: error: {message}") and error.count("\n") == 1
    assert not out.exists() and not overlay.exists()


def test_release_refuses_the_fronts_of_another_trace(geometry, tmp_path, capsys):
    front = tmp_path / "front.nc"
    xr.Dataset(attrs={"design_trace": "logarithmic"}).to_netcdf(front)
    argv = ["release", "--geometry", str(geometry), "--front", str(front),
            "--compliance-file", str(tmp_path / "compliance.nc"),
            "--out", str(tmp_path / "release.nc"), "--overlay-out", str(tmp_path / "best.yaml")]
    assert cli.main(argv) == 2
    assert capsys.readouterr().err.startswith(
        "lsbg release: error: --front: fronts of logarithmic, not of the geometry's circular")
    assert not (tmp_path / "compliance.nc").exists()  # refused before the FE compliance
