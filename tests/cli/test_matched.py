"""``lsbg matched-pairs``: the traces' order checked; fronts that do not overlap give no pair
and a dataset that says so."""

import numpy as np
import xarray as xr

from lsbg import cli
from tests.matched.test_run import box, converged


def inputs(tmp_path, first="logarithmic"):
    paths = {}
    # the LSBG's pattern movement all above the SBG's: nothing within the caliper
    fronts = {first: converged(first, [3.9, 4.0], [1500, 1600], [1, 1]),
              "face_milled": converged("face_milled", [2.1, 2.2], [1500, 1600], [1, 1])}
    for trace, ds in fronts.items():
        paths[trace] = tmp_path / f"{trace}_converged.nc"
        ds.to_netcdf(paths[trace])
        release = xr.Dataset(attrs={"design_trace": trace, "fe_aligned_positions": 24})
        release.to_netcdf(tmp_path / f"{trace}_release.nc")
        rating = xr.Dataset({"contact_safety": ("member", [1.0, 1.1]),
                             "bending_safety": ("member", [2.0, 2.1]),
                             "contact_stress": 1500.0, "root_stress": ("member", [400, 410])})
        rating.to_netcdf(tmp_path / f"{trace}_rating.nc")
        (tmp_path / trace).mkdir(exist_ok=True)
    # a search's front: only its trace and seed are read where no pair is found
    xr.Dataset(attrs={"design_trace": first, "seed": 1}).to_netcdf(tmp_path / "front.nc")
    box().to_netcdf(tmp_path / "trace_fronts.nc")
    traces = [first, "face_milled"]
    return (["matched-pairs", "--converged", *[str(paths[t]) for t in traces],
             "--geometry", *[str(tmp_path / t) for t in traces],
             "--release", *[str(tmp_path / f"{t}_release.nc") for t in traces],
             "--compliance-file", *[str(tmp_path / f"{t}_compliance.nc") for t in traces],
             "--rating", *[str(tmp_path / f"{t}_rating.nc") for t in traces],
             "--front", str(tmp_path / "front.nc"),
             "--trace-fronts", str(tmp_path / "trace_fronts.nc"),
             "--out", str(tmp_path / "matched_pairs.nc")])


def test_no_overlap_no_pairs(tmp_path, capsys):
    assert cli.main(inputs(tmp_path)) == 0
    ds = xr.load_dataset(tmp_path / "matched_pairs.nc")
    assert ds.sizes["pair"] == 0 and ds.attrs["pairs_found"] == 0
    assert ds.attrs["candidates"] == "2 2" and ds.attrs["dropped_by_caliper"] == 2
    assert ds.attrs["enough_pairs"] == 0 and np.isnan(ds["ratio_wilcoxon_p"]).all()
    # the rating is the design point's, carried per trace
    assert ds.attrs["rating_logarithmic_bending_safety"] == "2 2.1"
    assert "0 pairs of 2 2 designs within caliper 0.05" in capsys.readouterr().out


def test_the_logarithmic_trace_comes_first(tmp_path, capsys):
    assert cli.main(inputs(tmp_path, first="circular")) == 2
    assert "give the logarithmic trace's first" in capsys.readouterr().err
    assert not (tmp_path / "matched_pairs.nc").exists()


def test_more_full_runs_than_pairs_is_refused(tmp_path, capsys):
    argv = inputs(tmp_path) + ["--set", "optimise.matched.pairs=2", "--set",
                             "optimise.matched.full_runs=3"]
    assert cli.main(argv) == 2
    error = capsys.readouterr().err
    assert "optimise.matched.full_runs = 3: at most optimise.matched.pairs = 2" in error
    assert not (tmp_path / "matched_pairs.nc").exists()
