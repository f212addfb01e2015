# Trace against trace in every cell of the trace study (the trace_study section;
# lsbg.optimise.cells, docs/optimise.md "Trace against trace"): a cell is a spiral angle of
# the practice design and a cutter radius of its SBG. The paper's cell is the optimise
# rules' (rules/optimise.smk, results/optimise/trace_fronts.nc); each other cell runs the
# same commands on its own design point: `lsbg practice` at its angle (one overlay per
# angle, the paper angle's is results/practice/design.yaml), the geometry and FE
# compliance, the searches per trace and seed, the release (its converged positions),
# converge-front and trace-fronts (results/optimise/trace_fronts_<cell>.nc). The LSBG has
# no cutter: it runs once per angle, in the angle's cell of the design's cutter, and every
# cutter cell of the angle reads its fronts. The default study has no other cell and no
# job here. The rules' input functions are common.smk's (cell_config, cell_input, ...).

#: The other cells' labels, a wildcard's pattern.
OTHER_CELLS = "|".join(map(re.escape, STUDY.other_cells)) or "none"
#: The spiral angles whose practice design is made here (all but the paper's).
CELL_SPIRALS = "|".join(sorted({re.escape(c["spiral"]) for c in STUDY.other_cells.values()
                                if c["spiral"] != PAPER_SPIRAL})) or "none"


CELL = dict(cell=OTHER_CELLS)


rule cell_practice_design:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
    input:
        config=ancient(FILES["study_config"]),
        sources=sources("practice"),
    output:
        out=FILES["cell_practice_design"],
    params:
        **command("practice"),
        settings=plan.canonical({k: config[k] for k in (
            "design", "practice", "rating", "tooth", "flank_modification")}),
        speed=config["simulation"]["pinion_speed_deg_s"],
    wildcard_constraints:
        spiral=CELL_SPIRALS,
    log:
        "logs/trace_study/beta{spiral}_design.log",
    shell:
        LSBG


rule cell_geometry:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
    input:
        config=cell_config,
        sources=sources("geometry"),
    output:
        out=directory(FILES["cell_geometry"]),
    params:
        **command("geometry", no_step=True, set=cell_set),
        design=plan.canonical(config["design"]),  # rerun trigger
    wildcard_constraints:
        **CELL,
    log:
        "logs/trace_study/{cell}/{trace}_geometry.log",
    shell:
        LSBG


rule cell_compliance:
    input:
        geometry=cell_input("geometry"),
        config=cell_config,
        sources=sources("compliance"),
    output:
        out=FILES["cell_compliance"],
    params:
        **command("compliance"),
        tooth=plan.canonical(config["tooth"]),  # rerun trigger
    wildcard_constraints:
        **CELL,
    log:
        "logs/trace_study/{cell}/{trace}_compliance.log",
    resources:
        runtime=config["limits"]["tooth_minutes"],
    shell:
        LSBG


rule cell_optimise:
    input:
        geometry=cell_input("geometry"),
        config=cell_config,
        sources=sources("optimise"),
    output:
        out=FILES["cell_front"],
    params:
        **command("optimise", set=lambda w: [f"optimise.seed={w.seed}"]),
        settings=OPTIMISE_SETTINGS,
    wildcard_constraints:
        seed="|".join(map(str, STUDY.optimise_seeds)),
        **CELL,
    log:
        "logs/trace_study/{cell}/{trace}_seed{seed}_optimise.log",
    threads: config["optimise"]["workers"]
    resources:
        runtime=5 + int(config["limits"]["optimise_minutes"]),
        mem_mb=1500 + 500 * (config["optimise"]["workers"] - 1),
    shell:
        lsbg_shell("optimise.workers={threads}")


rule cell_release:
    input:
        geometry=cell_input("geometry"),
        config=cell_config,
        front=cell_fronts,
        compliance_file=cell_input("compliance"),
        sources=sources("release"),
    output:
        out=FILES["cell_release"],
        overlay_out=FILES["cell_best_overlay"],
    params:
        **command("release"),
        settings=RELEASE_SETTINGS,
    wildcard_constraints:
        **CELL,
    log:
        "logs/trace_study/{cell}/{trace}_release.log",
    resources:
        runtime=5 + int(config["limits"]["optimise_minutes"]),
    shell:
        LSBG


rule cell_converged_front:
    input:
        geometry=cell_input("geometry"),
        config=cell_config,
        front=cell_fronts,
        release=cell_input("release"),
        sources=sources("converge-front"),
    output:
        out=FILES["cell_converged_front"],
    params:
        **command("converge-front"),
        settings=OPTIMISE_SETTINGS,
    wildcard_constraints:
        **CELL,
    log:
        "logs/trace_study/{cell}/{trace}_converged_front.log",
    resources:
        runtime=5 + int(config["limits"]["optimise_minutes"]),
    shell:
        LSBG


rule cell_trace_fronts:
    input:
        converged=lambda w: STUDY.cell_converged_fronts(w.cell),
        sources=sources("trace-fronts"),
    output:
        out=FILES["cell_trace_fronts"],
    params:
        **command("trace-fronts"),
    wildcard_constraints:
        **CELL,
    log:
        "logs/trace_study/{cell}/trace_fronts.log",
    localrule: True
    resources:
        runtime=10,
    shell:
        LSBG
