"""The practice section checked before any job: the design it makes, its flanks, its spectrum."""

from __future__ import annotations

__all__ = ["practice_problems"]

#: The design keys whose fault at a practice pair is the user's (the overlay sets the
#: shift, the thickness and the undercut rule).
_USER_KEYS = ("design.cutter_radius_mm", "design.face_width_mm", "design.module_mm")


def practice_problems(config):
    """Problems of the ``practice`` section, one line each naming the key.

    The practice design is made (:func:`lsbg.practice.design.practice_overlay`)
    and each trace's pair built from it at the paper's spiral angle (the
    undercut it refuses, its top lands, its contact ratio); its relieved flanks
    are checked against the backlash (:func:`lsbg.tca.checks.modification_problems`);
    the load spectrum's shares must add up to 1 and its torques lie on the
    load curve.

    Parameters
    ----------
    config : dict
        The study's configuration, defaults filled in.

    Returns
    -------
    list of str
    """
    import math

    from lsbg.config import merge_config
    from lsbg.gear.checks import user_message
    from lsbg.gear.design import DesignError, GearPairDesign
    from lsbg.gear.geometry import GearPair
    from lsbg.practice.design import practice_overlay, practice_traces
    from lsbg.practice.spectrum import check_spectrum
    from lsbg.tca.checks import modification_problems
    from lsbg.tca.modification import FlankModification

    section = config["practice"]
    if not section["enabled"]:
        return []
    problems = []
    spectrum = section["load_spectrum"]
    try:
        levels, _ = check_spectrum(spectrum["torque_fractions"], spectrum["cycle_shares"])
    except ValueError as error:
        problems.append(str(error))
        levels = []
    spiral = float(config["paper_spiral_angle_deg"])
    try:
        published = GearPairDesign.from_config({**config["design"], "trace": "logarithmic",
                                                "spiral_angle_deg": spiral})
        overlay, figures = practice_overlay(published, config)
    except (ValueError, DesignError) as error:
        # the first rule given as a number is the likely culprit, else the shift's rule
        key = next((k for k in ("profile_shift", "thickness_modification", "tip_relief_um",
                                "tip_relief_length", "load_torque_N_m")
                    if not isinstance(section[k], str)), "profile_shift")
        return problems + [f"practice.{key} = {section[key]!r}: the practice design cannot be "
                           f"made ({error})"]
    if len(levels) and section["load_torque_N_m"] == "rated":
        # the spectrum's torques are fractions of the practice load, the curve's of the
        # rated torque: here they are the same torque
        top, reach = max(levels), max(section["load_range"])
        if top > reach + 1e-12 or min(levels) < min(section["load_range"]) - 1e-12:
            problems.append(f"practice.load_spectrum.torque_fractions = {[float(x) for x in levels]}: must lie "
                            f"within practice.load_range ({min(section['load_range']):g} to "
                            f"{reach:g} of the rated torque), where the load curves are")
    merged = merge_config(config, overlay)
    modification = FlankModification.from_config(merged["flank_modification"])
    for trace in practice_traces(config):
        try:
            pair = GearPair(GearPairDesign.from_config({**merged["design"], "trace": trace,
                                                        "spiral_angle_deg": spiral}))
        except (ValueError, DesignError) as error:
            head, why = user_message(error, config, ["paper_spiral_angle_deg"])
            if isinstance(error, DesignError) and head.split(" =")[0] in _USER_KEYS:
                # a key of the user's design section (the cutter radius), not the overlay's
                problems.append(f"{head}: {why} (at the practice design's {trace} pair)")
            else:
                problems.append(f"practice.profile_shift = {section['profile_shift']!r}: the "
                                f"practice design's {trace} pair: {error}")
            continue
        problems += [f"practice: the practice design's {trace} pair: {line}"
                     for line in modification_problems(pair, modification)]
    if not math.isfinite(figures["load_torque_N_m"]):
        problems.append(f"practice.load_torque_N_m = {section['load_torque_N_m']!r}: the rated "
                        f"torque is not finite")
    return problems
