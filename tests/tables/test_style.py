"""The reports' one table style: headers, units, significant figures, intervals."""

import re

import numpy as np
import pandas as pd
import pytest

from lsbg.tables import line_model
from lsbg.tables.style import (cell_label, column_header, display_unit, format_number,
                               format_table, run_label, with_interval)


@pytest.mark.parametrize("name, header", [
    ("tangential_force_outer", "tangential force at d2/2"),
    ("gear_speed_full_std_deg_s", "gear angular velocity full std [deg/s]"),
    ("tangential_force_std_low", "tangential contact force std, CI low"),
    ("mesh_stiffness_mean_N_per_um", "mesh stiffness mean [N/µm]"),
    ("c_gamma_N_per_mm_um", "c gamma [N/(mm·µm)]"),
    ("te_pp_slices_x2_change_percent", "TE peak to peak slices ×2 change [%]"),
    ("unloaded_te_max_rad", "unloaded TE largest [rad]"),
    ("spiral_angle_deg", "spiral angle [deg]"),
])
def test_headers_are_words_with_units(name, header):
    assert column_header(name) == header
    assert "_" not in column_header(name)


def test_every_column_of_the_report_tables_gets_a_header_without_underscores():
    names = ["std_SBG_low", "dynamic_factor_LSBG", "phase_std_median", "ratio_high",
             "transmission_error_sampled_std", "k_l_for_c_gamma_20_N_per_mm_um",
             "gear_speed_std_rel_diff_percent", "mean_difference_percent", "contact_model"]
    assert not [n for n in names if "_" in column_header(n)]


@pytest.mark.parametrize("value, text", [
    (25602.83, "25603"), (1873.7203, "1874"), (0.810049, "0.8100"), (8.61287e-05, "8.613×10⁻⁵"),
    (2.8e-13, "2.8×10⁻¹³"), (1.25e7, "1.25×10⁷"), (0.0, "0"), (-0.00057, "−5.7×10⁻⁴".replace("−", "-")),
    (3, "3"), (True, "yes"), (None, "—"), (float("nan"), "—"), (pd.NA, "—"), ("SBG", "SBG"),
])
def test_numbers_with_four_significant_figures(value, text):
    assert format_number(value) == text


def test_digits_and_units():
    assert format_number(0.81004, digits=3) == "0.810"
    assert display_unit("urad") == "µrad" and display_unit("N/um") == "N/µm"
    assert display_unit("N/(mm um)") == "N/(mm·µm)" and display_unit("deg/s") == "deg/s"


def test_run_ids_and_categories_read_as_words():
    assert run_label("logarithmic_beta35_line_compiled") == "LSBG 35°, line model, compiled"
    assert run_label("circular_beta22.5_point_pybullet") == "SBG 22.5°, point model, pybullet"
    assert (run_label("logarithmic_beta35_line_stiffness_N_per_mm_um_x0.5")
            == "LSBG 35°, line stiffness ×0.5")
    assert run_label("not a run") == "not a run"
    assert cell_label("tangential_force") == "tangential contact force"
    # a trace by its construction, so the two SBGs read apart
    assert cell_label("circular") == "SBG, paper's arc" and cell_label("urad") == "µrad"
    assert cell_label("face_milled") == "SBG, ISO 23509 face-milled"
    assert cell_label(3.5) == 3.5


def test_value_and_interval_in_one_column():
    df = pd.DataFrame({"quantity": ["gear_speed"], "ratio": [0.8853], "ratio_low": [0.8441],
                       "ratio_high": [0.9302], "calmer": ["SBG"]})
    out = with_interval(df, "ratio")
    assert list(out.columns) == ["quantity", "ratio SBG/LSBG (95 % CI)", "calmer"]
    assert out.iloc[0, 1] == "0.885 (0.844–0.930)"


def test_table_html_has_readable_headers_and_no_missing_marker():
    df = pd.DataFrame({"trace": ["logarithmic", "circular"], "spiral_angle_deg": [35.0, 22.5],
                       "quantity": ["gear_speed", "mesh_stiffness"],
                       "out_of_control": pd.array([2, pd.NA], dtype="Int64"),
                       "full_rate_std": [34.2997, np.nan], "ad_pvalue": [8.61287e-05, 0.6]})
    html = format_table(df, formats={"ad_pvalue": "{:.2g}"})
    headers = re.findall(r"<th>(.*?)</th>", html)
    assert headers == ["trace", "spiral angle [deg]", "quantity", "subgroups out of control",
                       "full-rate std", "p (AD)"]
    cells = re.findall(r"<td[^>]*>(.*?)</td>", html)
    assert cells[:6] == ["LSBG", "35", "gear angular velocity", "2", "34.30", "8.6e-05"]
    assert cells[6:] == ["SBG, paper&#x27;s arc", "22.5", "mesh stiffness", "—", "—", "0.6"]
    assert "NA" not in html and "nan" not in html


def test_angle_ranges_and_where_each_type_is_calmer():
    grid = [20, 22.5, 25, 27.5, 30, 32.5, 35]
    assert line_model.angle_ranges([20, 22.5, 25, 35], grid) == "20–25°, 35°"
    assert line_model.angle_ranges([]) == ""
    ratios = pd.DataFrame({
        "spiral_angle_deg": grid * 2,
        "quantity": ["gear_speed"] * 7 + ["tangential_force"] * 7,
        "calmer": ["LSBG", "LSBG", "LSBG", "SBG", "SBG", "SBG", "SBG",
                   "LSBG", "neither", "LSBG", "SBG", "SBG", "neither", "SBG"]})
    table = line_model.calmer_by_angle(ratios).set_index("quantity")
    assert table.loc["gear_speed", "LSBG"] == "20–25°"
    assert table.loc["gear_speed", "SBG"] == "27.5–35°"
    assert table.loc["gear_speed", "neither"] == "none"
    assert table.loc["tangential_force", "LSBG"] == "20°, 25°"
    assert table.loc["tangential_force", "neither"] == "22.5°, 32.5°"
    assert table.loc["tangential_force", "angles"] == 7


def test_sentences_and_tables_share_the_number_format():
    from lsbg import stats

    assert stats.format_number(34690.4) == "34690"          # not 3.469e+04
    assert stats.format_number(1.0736e4) == format_number(1.0736e4) == "10736"
    assert stats.scientific(3.5527e-15) == "3.55×10⁻¹⁵" and stats.scientific(1e-6) == "10⁻⁶"


def test_int_format_is_significant_figures_and_design_points_read_as_words():
    df = pd.DataFrame({"ad_pvalue": [1.04e-15, 0.6012], "run": ["circular_beta35", "x"]})
    html = format_table(df, formats={"ad_pvalue": 2})
    assert re.findall(r"<td[^>]*>(.*?)</td>", html) == ["10⁻¹⁵", "SBG 35°",
                                                        "0.60", "x"]
