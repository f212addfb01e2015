"""Every dataset the test study writes is labelled: a 5-line plot can publish it."""

import pytest

from tests.workflow.helpers import dataset_label_problems, unit_problem


@pytest.mark.slow
def test_every_dataset_of_the_study_has_units_and_long_names(study):
    """All of results/ of the session's study: every variable and coordinate has units
    and a long_name (CF-1.11), its units a unit string ("1" where dimensionless)."""
    root, _ = study
    assert len(list((root / "results").rglob("*.nc"))) > 20
    problems = dataset_label_problems(root / "results")
    assert not problems, "\n".join(problems[:40])


@pytest.mark.parametrize("units, ok", [
    ("um", True), ("m", True), ("N m", True), ("deg/s", True), ("1", True),
    ("N/(mm um)", True), ("mm/(0.1 mm)", True), ("kg m2", True),
    ("u", False), ("", False), ("mm (deg for Sigma)", False), ("N/(mm", False)])
def test_unit_check_tells_a_unit_from_a_cut_one(units, ok):
    assert (unit_problem(units) is None) == ok
