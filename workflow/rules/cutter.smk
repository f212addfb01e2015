# The SBG's cutter radius as a design variable (the cutter_sweep section;
# lsbg.experiments.cutter, docs/usage.md "The cutter-radius sweep"): at the paper's
# design point, `lsbg cutter-point` builds the LSBG and the SBG of cutter_sweep.trace at
# each cutter radius of the sweep (the nominal ones that fit, the design's and the
# curvature-matched one) in memory and writes each one's V-H map at sweep_steps with its
# loaded TE (uniform bed) and FE stresses (results/cutter/*.nc), for the sweep report.
# Quasi-static, a job per point; the FE loaded TCA is computed where cutter_sweep.fe asks
# for it, except the LSBG's and the study's own SBG's, which are read from the tooth
# stage (results/tooth/). A point without FE is seconds of work: a local rule.


def cutter_point_settings(point):
    """The ``--set`` values of a point's design: the paper's angle, its trace and radius."""
    settings = [f"design.trace={point['trace']}", f"design.spiral_angle_deg={PAPER_SPIRAL}"]
    if point["trace"] != "logarithmic":
        settings.append(f"design.cutter_radius_mm={point['radius_mm']!r}")
    return settings


def cutter_fe_input(point):
    """The study's FE loaded TCA of the same pair where it has one: the LSBG's, and the SBG's
    at the design's cutter when the sweep's trace is the study's SBG's."""
    if not point["fe"]:
        return []
    own = point["trace"] == "logarithmic" or (point["trace"] in plan.PAPER_TRACES
                                              and "design" in point["roles"])
    return [STUDY.fe_ltca(point["trace"], PAPER_SPIRAL)] if own else []


#: What every point depends on besides its own design (rerun triggers).
CUTTER_TRIGGERS = dict(
    contact_state=plan.contact_state_params(config, PAPER_SPIRAL, SWEEP_ENGINE),
    sections=plan.canonical({k: config[k] for k in ("design", "tooth", "tca", "cutter_sweep")}),
)

for _point in STUDY.cutter_points:
    _fe = cutter_fe_input(_point)
    _name = Path(_point["file"]).stem.replace(".", "_")  # (a rule's name is a word)

    rule:
        name:
            f"cutter_{_name}"
        localrule: not (_point["fe"] and not _fe)
        input:
            config=ancient(FILES["study_config"]),
            fe_ltca=_fe,
            sources=sources("cutter-point"),
        output:
            out=_point["file"],
        params:
            **command("cutter-point", set=cutter_point_settings(_point), roles=_point["roles"],
                      radius_mm=_point["radius_mm"], fe=_point["fe"] and not _fe),
            **CUTTER_TRIGGERS,
        log:
            f"logs/cutter/{Path(_point['file']).stem}.log",
        # (no profile entry: the rules are the sweep's; an FE compliance as tooth_compliance's)
        resources:
            mem_mb=4000 if _point["fe"] and not _fe else 1000,
            cpus_per_task=1,
            runtime=config["limits"]["tooth_minutes"] + 5 if _point["fe"] and not _fe else 10,
        shell:
            LSBG
