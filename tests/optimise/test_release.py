"""The release of an ease-off from the fronts (lsbg.optimise.release)."""

import dataclasses
from functools import lru_cache

import numpy as np
import pytest

from lsbg.config import resolve_config
from lsbg.optimise import preference
from lsbg.optimise.release import (ReleaseSettings, release_dataset, release_design,
                                   release_problems, released_modification)
from lsbg.optimise.verdict import STATE_FIGURES, fe_combined, fe_group_values

#: A tiny search of the paper's LSBG (tests/optimise/test_run.py's bounds).
TINY = ["optimise.population=6", "optimise.generations=2", "optimise.phases=12",
        "optimise.edge_load_tolerance=1", "optimise.bounds.bias_um=[0, 0]",
        "optimise.bounds.spiral_angle_correction_um=[0, 0]",
        "optimise.bounds.pressure_angle_correction_um=[0, 0]",
        "optimise.bounds.lengthwise_crowning_um=[20, 45]",
        "optimise.bounds.profile_crowning_um=[0, 20]",
        "optimise.bounds.pinion_tip_relief_um=[0, 15]",
        "optimise.bounds.gear_tip_relief_um=[0, 15]", "misalignment_map.range=0.02",
        "optimise.release.largest_positions=48", "optimise.release.candidates=3",
        "optimise.release.fe_candidates=1", "optimise.release.convergence=0.03"]


def test_the_settings_defaults_are_the_schemas():
    section = resolve_config([], [])["optimise"]["release"]
    assert ReleaseSettings.from_config(section) == ReleaseSettings()
    assert ReleaseSettings.from_config({}) == ReleaseSettings()


@pytest.mark.parametrize("section, key", [
    ({"criteria": ["mesh_loss"]}, "optimise.release.criteria"),
    ({"weights": {"efficiency": 1.0}}, "optimise.release.weights"),
    ({"weights": {"transmission_error": -1.0}}, "optimise.release.weights"),
    ({"largest_positions": 32}, "optimise.release.largest_positions = 32"),
])
def test_bad_settings_name_their_key(section, key):
    problems = release_problems(section, phases=24)
    assert len(problems) == 1 and problems[0].startswith(key)
    with pytest.raises(ValueError, match=key.split(" ")[0]):
        ReleaseSettings.from_config(section)


@pytest.fixture(scope="module")
def released(coarse_compliance):
    from lsbg.gear.design import GearPairDesign
    from lsbg.gear.geometry import GearPair
    from lsbg.optimise.checks import run_settings
    from lsbg.optimise.objectives import Evaluator
    from lsbg.optimise.run import optimise_pair

    pair = GearPair(GearPairDesign())
    config = resolve_config([], TINY)
    settings = run_settings(config, pair.design)
    fronts = [optimise_pair(pair, settings, seed=s) for s in (1, 2)]
    release = ReleaseSettings.from_config(config["optimise"]["release"])

    @lru_cache(maxsize=None)
    def evaluator_at(positions):
        return Evaluator(pair, dataclasses.replace(settings["evaluation"], phases=positions))

    result = release_design(evaluator_at, settings, release, fronts, coarse_compliance)
    return (release_dataset(result, release, {"design_trace": "logarithmic"}), result,
            evaluator_at, settings, release)


def test_the_shared_designs_fe_figures_are_at_its_converged_positions(released,
                                                                      coarse_compliance):
    ds, result, evaluator_at, settings, _ = released
    groups = {}
    for group in STATE_FIGURES:
        n = ds.attrs[f"fe_{group}_positions"]
        assert n in (12, 24, 48)
        groups[group] = fe_group_values(evaluator_at, coarse_compliance,
                                        [settings["reference"]], n, group)
        changes = [float(c) for c in ds.attrs[f"fe_{group}_changes"].split()]
        # stopped at the first doubling within the criterion, or at the largest
        assert all(c >= 0.03 for c in changes[:-1])
        assert (changes[-1] < 0.03) == bool(ds.attrs[f"fe_{group}_converged"])
    again = fe_combined(**groups)
    for name, value in again.items():
        assert float(ds[f"reference_fe_{name}"]) == pytest.approx(float(value[0]), rel=1e-9)


def test_only_a_design_no_worse_under_fe_is_released(released):
    ds, result, _, _, release = released
    evaluated = ds["fe_evaluated"].values == 1
    assert 1 <= evaluated.sum() <= 2  # one per front
    reference = {n: float(ds[f"reference_verdict_{n}"]) for n in release.criteria}
    values = {n: ds[f"verdict_{n}"].values[evaluated] for n in release.criteria}
    expected = preference.released(values, reference, release.criteria, release.tolerance)
    assert (ds["released"].values[evaluated] == 1).tolist() == expected.tolist()
    assert not np.any(ds["released"].values[~evaluated])
    k = ds.attrs["chosen"]
    if k < 0:
        assert ds.attrs["shared_kept"] == 1 and released_modification(ds) is None
    else:
        assert ds["released"].values[k] == 1 and ds["checked_edge_contact"].values[k] <= 0
        scores = ds["score"].values[ds["released"].values == 1]
        assert ds["score"].values[k] == scores.min()
        assert released_modification(ds) == result["modifications"][k]
    # the candidates' converged uniform-bed figures, at the recorded positions
    n = ds.attrs["uniform_positions"]
    assert n >= 12 and ds.attrs["uniform_changes"]
