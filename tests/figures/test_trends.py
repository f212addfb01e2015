"""The sweep report's figures read well: labelled in words with units, no text cut off."""

import pandas as pd
import pytest

from lsbg.figures import trends
from tests.figures.test_base import readability_problems

KEY = "flank_modification.lengthwise_crowning_um"


@pytest.fixture
def crowning():
    """A lengthwise-crowning sweep's long table, both gear types, three points."""
    rows = [{"gear_type": t, "spiral_angle_deg": 35.0, KEY: c,
             "tangential_force_full_rate_std": 150 - c + k, "dynamic_factor": 1.01 + k / 100,
             "loaded_te_peak_to_peak": 120 - c + k, "pattern_length": 25 - c / 3 + k,
             "pattern_centre_cone_distance": 73.8 - c / 100 + k}
            for k, t in enumerate(("SBG", "LSBG")) for c in (10.0, 20.0, 40.0)]
    return pd.DataFrame(rows)


def test_parameter_sweep_figure_labels_fit(crowning):
    """The datasets' long_names and units as axis labels, wrapped to their panels: the
    swept key's unit whole ("[µm]", not "crowning u"), nothing cut off or overprinted."""
    variables = ["loaded_te_peak_to_peak", "pattern_length", "pattern_centre_cone_distance"]
    units = {KEY: "um", "loaded_te_peak_to_peak": "urad", "pattern_length": "mm",
             "pattern_centre_cone_distance": "mm"}
    labels = {KEY: "lengthwise crowning",
              "loaded_te_peak_to_peak": "quasi-static loaded TE, peak to peak",
              "pattern_length": "bearing pattern length",
              "pattern_centre_cone_distance": "bearing pattern centre, cone distance"}
    fig = trends.plot_parameter_sweep(crowning, KEY, variables, units, labels=labels)
    assert fig.axes[0].get_xlabel() == "lengthwise crowning [µm]"
    assert "[µrad]" in fig.axes[0].get_ylabel()
    assert readability_problems(fig) == []
