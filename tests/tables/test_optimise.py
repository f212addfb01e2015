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
