"""Trace against trace (lsbg.optimise.fronts): the statistics against direct computations."""

import math

import numpy as np
import pytest
import xarray as xr

from lsbg import cli
from lsbg.optimise import fronts
from lsbg.optimise.release import seeds_agree

OBJECTIVES = ["transmission_error", "pattern_movement", "contact_pressure", "mesh_loss"]


def synthetic_front(rng, shift, n=25):
    """A 4-objective trade-off surface (sum of the normalised objectives constant), moved."""
    x = rng.random((n, 3))
    return np.column_stack([x, 1.5 - x.sum(axis=1) / 2]) + shift


def test_non_dominated_keeps_exactly_the_undominated_rows():
    values = np.array([[1, 3], [2, 2], [3, 1], [2, 3], [3, 3], [1, 3]], float)
    assert fronts.non_dominated(values).tolist() == [True, True, True, False, False, True]


def test_a12_counts_wins_and_half_ties():
    assert fronts.vargha_delaney_a12([3, 4, 5], [1, 2, 3]) == pytest.approx((8 + 0.5) / 9)
    assert fronts.vargha_delaney_a12([1], [2]) == 0.0


def test_eaf_statistic_is_the_mean_absolute_attainment_difference_on_a_grid():
    rng = np.random.default_rng(3)
    a = [rng.random((12, 2)) for _ in range(3)]
    b = [rng.random((12, 2)) * 0.8 + 0.25 for _ in range(3)]
    _, difference, statistic = fronts.eaf_difference(a, b)
    assert np.all(np.abs(difference) <= 1)
    # the attainment functions by brute force on a fine grid of cell centres
    g = (np.arange(600) + 0.5) * fronts.REFERENCE / 600
    x, y = np.meshgrid(g, g)

    def attained(sets):
        return np.mean([np.any((s[:, 0][:, None, None] <= x) & (s[:, 1][:, None, None] <= y),
                               axis=0) for s in sets], axis=0)

    assert statistic == pytest.approx(np.mean(np.abs(attained(a) - attained(b))), abs=3e-3)


def test_a_permutation_p_cannot_go_below_two_labelings_in_twenty():
    rng = np.random.default_rng(1)
    a = [synthetic_front(rng, 0.0) for _ in range(3)]
    b = [synthetic_front(rng, 0.4) for _ in range(3)]
    p, labelings = fronts.permutation_p(a, b, lambda x, y: fronts.eaf_difference(
        [s[:, :2] for s in x], [s[:, :2] for s in y])[2])
    assert labelings == math.comb(6, 3) == 20
    # the statistic is the same for a labeling and its swap: the least p is 2/20
    assert p == pytest.approx(0.1)


@pytest.mark.parametrize("a12, ab, ba, expected", [
    (0.71, 0.1, 0.2, 1), (0.9, 0.3, 0.2, 0), (0.29, 0.3, 0.2, -1), (0.5, 0.1, 0.5, 0),
    (0.1, 0.1, 0.5, 0), (math.nan, 0.1, 0.2, None)])
def test_verdict_rule_as_docs_state_it(a12, ab, ba, expected):
    got = fronts.verdict(a12, ab, ba)
    assert (math.isnan(got) if expected is None else got == expected)


def test_a_front_moved_down_is_better_by_every_statistic():
    rng = np.random.default_rng(0)
    better = [synthetic_front(rng, 0.0) for _ in range(3)]
    worse = [synthetic_front(rng, 0.3) for _ in range(3)]
    stats = fronts.trace_statistics(better, worse, OBJECTIVES)
    assert stats["a12"] == 1.0 and stats["mann_whitney_p"] == pytest.approx(0.1)
    assert stats["epsilon_ab"] < 0.1 < stats["epsilon_ba"]
    assert stats["dominated_share_a"] < 0.05 < 0.9 < stats["dominated_share_b"]
    assert stats["verdict"] == 1
    swapped = fronts.trace_statistics(worse, better, OBJECTIVES)
    assert swapped["verdict"] == -1
    assert swapped["a12"] == 0.0
    # the box is the one over both traces' fronts: the same either way round
    assert np.allclose(stats["low"], swapped["low"]) and np.allclose(stats["high"], swapped["high"])


def test_no_feasible_member_gives_no_verdict():
    empty = [np.zeros((0, 4))] * 3
    rng = np.random.default_rng(2)
    stats = fronts.trace_statistics([synthetic_front(rng, 0.0) for _ in range(3)], empty,
                                    OBJECTIVES)
    assert math.isnan(stats["verdict"])
    assert stats["hypervolume_b"].tolist() == [0.0, 0.0, 0.0]


def converged_dataset(trace, sets, seeds):
    members = np.concatenate([[s] * len(v) for s, v in zip(seeds, sets)]).astype(int)
    table = np.vstack(sets)
    result = {"seed": members, "individual": np.arange(members.size),
              "search": {n: table[:, k] for k, n in enumerate(OBJECTIVES)},
              "converged": {n: table[:, k] for k, n in enumerate(OBJECTIVES)},
              "edge_load": np.full(members.size, -0.01), "kept": np.ones(members.size, bool),
              "seeds": list(seeds), "positions": 96}
    return fronts.converged_front_dataset(result, OBJECTIVES, {"design_trace": trace})


def test_lsbg_trace_fronts_recomputes_the_statistics_from_the_files(tmp_path, capsys):
    rng = np.random.default_rng(4)
    scale = np.array([40.0, 3.0, 1900.0, 1.8])
    paths = []
    for trace, shift in (("logarithmic", 0.3), ("face_milled", 0.0)):
        sets = [synthetic_front(rng, shift) * scale for _ in range(3)]
        path = tmp_path / f"{trace}.nc"
        converged_dataset(trace, sets, [1, 2, 3]).to_netcdf(path)
        paths.append(path)
    out = tmp_path / "trace_fronts.nc"
    # the order of the files does not matter: the logarithmic trace is the first
    assert cli.main(["trace-fronts", "--converged", str(paths[1]), str(paths[0]),
                     "--out", str(out)]) == 0
    assert "the SBG's fronts are better (indicative)" in capsys.readouterr().out
    ds = xr.load_dataset(out)
    assert list(ds["trace"].values) == ["logarithmic", "face_milled"]
    assert float(ds["verdict"]) == -1 and float(ds["a12"]) == 0.0
    assert ds.attrs["least_attainable_p"] == pytest.approx(0.1)
    assert ds.attrs["indicative"] == 1
    assert ds["box_low_contact_pressure"].attrs["units"] == "MPa"
    for name in ds.data_vars:
        assert ds[name].attrs["long_name"] and "units" in ds[name].attrs, name
    # the hypervolumes recomputed from the converged fronts on disk
    sets = [fronts.seed_sets(xr.load_dataset(p)) for p in paths]
    again = fronts.trace_statistics(*sets, OBJECTIVES)
    assert np.allclose(ds["hypervolume"].values[0], again["hypervolume_a"])


def test_seeds_agree_when_all_keep_the_shared_design_or_release_alike():
    verdict = {"transmission_error": np.array([30.0, 30.2, 34.0]),
               "root_stress": np.array([500.0, 501.0, 500.0])}
    criteria = ("transmission_error", "root_stress")
    assert seeds_agree([-1, -1, -1], verdict, criteria, 0.01)
    assert not seeds_agree([-1, 0, -1], verdict, criteria, 0.01)
    assert seeds_agree([0, 1], verdict, criteria, 0.01)
    assert not seeds_agree([0, 2], verdict, criteria, 0.01)
