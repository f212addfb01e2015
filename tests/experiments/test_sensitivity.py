"""Sensitivity cases: names, the envelope's corners, the sections a case changes, errors."""

import pytest

from lsbg.experiments.sensitivity import (CASE_STAGES, case_label, case_name, case_sections,
                                          parse_case, scaled_contact, stage_cases, study_cases)

SECTION = {"mesh_damping_ratio": [0.5, 2], "crowning": [0, 0.5, 2],
           "displacement": ["envelope"], "compliance": ["fe"]}
MODIFICATION = {"lengthwise_crowning_um": 25, "profile_crowning_um": 5, "bias_um": 2}


def test_every_entry_is_one_case_and_the_envelope_one_per_corner():
    cases = study_cases(SECTION, {"axes": ["E", "P"], "range": 0.05})
    assert list(cases) == ["mesh_damping_ratio_x0.5", "mesh_damping_ratio_x2", "crowning_x0",
                           "crowning_x0.5", "crowning_x2", "displaced_E+0.05_P+0.05",
                           "displaced_E+0.05_P-0.05", "displaced_E-0.05_P+0.05",
                           "displaced_E-0.05_P-0.05", "compliance_fe"]
    for name, (key, value) in cases.items():
        assert case_name(key, value) == name
        parsed = parse_case(name)
        assert parsed[0] == key and parsed[1] == (value if isinstance(value, str)
                                                  else pytest.approx(value))
    assert case_label("crowning_x0") == "conjugate flanks (crowning ×0)"
    assert case_label("displaced_E-0.05_P+0.05") == "displaced E-0.05 P+0.05 mm"
    three = study_cases({"displacement": ["envelope"]}, {"axes": ["E", "P", "Sigma"], "range": 0.1})
    assert len(three) == 8 and "displaced_E-0.1_P+0.1_Sigma-0.1" in three


def test_a_case_reaches_only_the_stages_it_changes():
    cases = study_cases(SECTION)
    assert list(stage_cases(cases, "fe_ltca")) == ["crowning_x0", "crowning_x0.5", "crowning_x2"]
    assert list(stage_cases(cases, "contact_state")) == list(stage_cases(cases, "fe_ltca"))
    assert list(stage_cases(cases, "dynamics")) == list(cases)
    assert set(CASE_STAGES) == {"mesh_damping_ratio", "line_stiffness_N_per_mm_um", "slices",
                                "compliance", "crowning", "displacement", "pinion_speed",
                                "boundary"}


def test_a_speed_case_runs_at_its_own_speed_and_is_not_rated():
    """The pinion-speed case reaches the dynamics alone, with its own simulation section; the
    rating (at the study's speed) takes every case but it."""
    from lsbg.experiments.sensitivity import case_simulation, rated_cases

    cases = study_cases({**SECTION, "pinion_speed": [0.25, 1.5]})
    assert "pinion_speed_x0.25" in cases and parse_case("pinion_speed_x1.5") == ("pinion_speed",
                                                                                   1.5)
    assert case_label("pinion_speed_x0.25") == "pinion speed ×0.25"
    assert list(stage_cases(cases, "dynamics")) == list(cases)
    assert "pinion_speed_x1.5" not in stage_cases(cases, "contact_state")
    assert rated_cases(cases) == [c for c in cases if not c.startswith("pinion_speed")]
    simulation = {"pinion_speed_deg_s": 7703.0, "load_torque_N_m": 1964.99}
    assert case_simulation("pinion_speed", 1.5, simulation) == {
        "pinion_speed_deg_s": pytest.approx(11554.5), "load_torque_N_m": 1964.99}
    assert case_simulation("crowning", 2, simulation) == simulation
    assert simulation["pinion_speed_deg_s"] == 7703.0  # untouched
    with pytest.raises(ValueError, match="sensitivity.pinion_speed factor 0"):
        study_cases({"pinion_speed": [0]})


def test_a_boundary_case_switches_the_simulation_and_is_rated():
    from lsbg.experiments.sensitivity import case_simulation, rated_cases

    cases = study_cases({"boundary": ["driveline"], "mesh_damping_ratio": [2]})
    assert list(cases) == ["boundary_driveline", "mesh_damping_ratio_x2"]
    assert parse_case("boundary_driveline") == ("boundary", "driveline")
    assert case_label("boundary_driveline") == "boundary: torsional driveline"
    assert rated_cases(cases) == list(cases)
    assert list(stage_cases(cases, "contact_state")) == []
    simulation = {"boundary": "prescribed_pinion", "pinion_speed_deg_s": 7703.0}
    assert case_simulation("boundary", "driveline", simulation) == {
        "boundary": "driveline", "pinion_speed_deg_s": 7703.0}
    c, m, a = case_sections("boundary", "driveline", {"slices": 20}, MODIFICATION, {})
    assert (c, m, a) == ({"slices": 20}, MODIFICATION, {})
    with pytest.raises(ValueError, match="sensitivity.boundary value 'free'"):
        study_cases({"boundary": ["free"]})


def test_crowning_scales_the_ease_off_and_a_corner_adds_to_the_assembly():
    contact = {"mesh_damping_ratio": 0.05, "slices": 20}
    misalignment = {"offset_E_mm": 0.02, "pinion_axial_P_mm": 0.0}
    c, m, a = case_sections("crowning", 0.5, contact, MODIFICATION, misalignment)
    assert (c, a) == (contact, misalignment)
    assert m == {"lengthwise_crowning_um": 12.5, "profile_crowning_um": 2.5, "bias_um": 1.0}
    _, m, _ = case_sections("crowning", 0, contact, MODIFICATION, misalignment)
    assert not any(m.values())                         # the conjugate flanks
    _, m, a = case_sections("displacement", "E-0.1 P+0.05", contact, MODIFICATION, misalignment)
    assert m == MODIFICATION
    assert a == {"offset_E_mm": pytest.approx(-0.08), "pinion_axial_P_mm": pytest.approx(0.05)}
    _, _, a = case_sections("displacement", "Sigma+0.1", contact, MODIFICATION, {})
    assert a == {"shaft_angle_error_deg": pytest.approx(0.1)}
    c, m, _ = case_sections("mesh_damping_ratio", 2, contact, MODIFICATION, misalignment)
    assert c["mesh_damping_ratio"] == pytest.approx(0.1) and m == MODIFICATION
    assert MODIFICATION["bias_um"] == 2 and misalignment["offset_E_mm"] == 0.02  # untouched


def test_bad_cases_are_named():
    with pytest.raises(ValueError, match="sensitivity.crowning factor -0.5: must be a number >= 0"):
        study_cases({"crowning": [-0.5]})
    with pytest.raises(ValueError, match="sensitivity.displacement value 'corners'"):
        study_cases({"displacement": ["corners"]})
    with pytest.raises(ValueError, match="sensitivity key 'nosuch'"):
        study_cases({"nosuch": [1]})
    with pytest.raises(ValueError, match="sensitivity.slices factor 0"):
        study_cases({"slices": [0]})
    with pytest.raises(ValueError, match="'X\\+0.1' is not LETTER\\+VALUE"):
        case_sections("displacement", "X+0.1", {}, {}, {})
    with pytest.raises(ValueError, match="case 'crowning_y2'"):
        parse_case("crowning_y2")
    assert scaled_contact({"slices": 20}, "crowning", 2) == {}


def test_a_corners_label_gives_back_its_displacements():
    from lsbg.tca.misalignment import corner_displacements, envelope_corners

    for axes in (["E", "P"], ["G", "Sigma"], ["E", "P", "Sigma"]):
        for label, values in envelope_corners(axes, 0.05).items():
            assert corner_displacements(label) == values
