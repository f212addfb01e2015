"""The optimisation's report text: how each type's design was chosen."""

import xarray as xr

from lsbg.tables.optimise import choice_text


def _front(choose_from, below, chosen=0):
    return xr.Dataset(attrs={"choice_rule": "knee", "choose_from": choose_from,
                             "chosen_below_shared_transmission_error": int(below),
                             "chosen": chosen})


def test_the_choice_text_names_the_rule_and_where_it_chose_from():
    fronts = {("LSBG", 1): _front("below_shared", True), ("SBG", 1): _front("below_shared", True),
              ("LSBG", 2): _front("below_shared", False)}  # the next seed does not choose
    text = choice_text(fronts)
    assert text == ("the knee rule among its front's designs whose loaded TE at the rated "
                    "torque is below the shared ease-off's")
    fronts[("SBG", 1)] = _front("below_shared", False)
    assert choice_text(fronts).endswith("(SBG: no such design passed, so chosen from the whole "
                                        "front)")
    # no design of the front passed (the search's rule writes chosen = -1): the shared stands
    fronts[("LSBG", 1)] = _front("below_shared", False, chosen=-1)
    assert choice_text(fronts).endswith(
        "(SBG: no such design passed, so chosen from the whole front; LSBG: no design of the "
        "front passed, so the shared ease-off stands)")
    fronts = {("LSBG", 1): _front("front", False)}
    assert choice_text(fronts) == "the knee rule over its whole front"


def _scored(chosen):
    """A front of two designs with their mesh efficiencies and the shared ease-off's."""
    import numpy as np

    from lsbg.tables.optimise import COEFFICIENTS

    ds = xr.Dataset({"efficiency": ("individual", np.array([98.5, 98.7])),
                     "reference_efficiency": 98.29,
                     **{name: ("individual", np.array([30.0, 40.0])) for name in COEFFICIENTS}},
                    attrs={"chosen": chosen, "friction_law": "iso_tr_14179_2",
                           "objectives": "efficiency",
                           "reference_flank_modification_lengthwise_crowning_um": 25.0})
    ds["efficiency"].attrs.update(long_name="mesh efficiency", units="%")
    return ds


def test_a_type_that_keeps_the_shared_ease_off_has_no_nan_in_its_text_or_table():
    from lsbg.tables.optimise import chosen_table, efficiency_text

    fronts = {("SBG", 1): _scored(-1), ("LSBG", 1): _scored(1)}
    text = efficiency_text(fronts)
    assert "nan" not in text
    assert "SBG 98.29 % (it keeps the shared ease-off)" in text
    assert "LSBG 98.29 % with the shared ease-off, 98.70 % with its own" in text
    table = chosen_table(fronts).set_index("quantity")
    assert not table[["SBG chosen", "LSBG chosen"]].isna().any().any()
    # the SBG keeps the shared ease-off: its chosen values are the shared ones
    assert table.loc["lengthwise crowning", "SBG chosen"] == 25.0
    assert table.loc["lengthwise crowning", "LSBG chosen"] == 40.0
    assert table.loc["mesh efficiency", "SBG chosen"] == 98.29
