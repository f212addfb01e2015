"""A new stage is one subcommand and one rule file; a study folder of one's own brings its own.

Both in the session's study (tests/workflow/conftest.py): a copy of the repository
run once on the test configuration. What a test adds to the copy it takes away
again, with the files' time stamps, so that the other tests see the study as it
was.
"""

import shutil

import pandas as pd
import pytest

from tests.workflow.helpers import TEST_CONFIG, planned_jobs, snakemake, write_yaml

#: A new subcommand: the contact ratio of each design point, read from its geometry.
COMMAND = '''"""``lsbg contact-ratio``: the contact ratio of design points (a test's new stage)."""

from lsbg.cli.options import add_config_options, add_output

__all__ = ["add_contact_ratio_parser"]


def add_contact_ratio_parser(subparsers):
    parser = subparsers.add_parser("contact-ratio", help="contact ratio of design points")
    parser.add_argument("--geometry", nargs="+", required=True, metavar="DIR")
    add_config_options(parser, ("contact",))
    add_output(parser, metavar="TABLE.csv", help="output CSV")
    parser.set_defaults(handler=run_contact_ratio)


def run_contact_ratio(args):
    import pandas as pd

    from lsbg.gear.geometry import GearPair
    from lsbg.solid.directory import read_design

    rows = [{"trace": d.trace, "contact_ratio": GearPair(d).contact_ratio()["total"]}
            for d in map(read_design, args.geometry)]
    pd.DataFrame(rows).to_csv(args.out, index=False)
    return f"{len(rows)} design points -> {args.out}"
'''
#: Its rule: named inputs and outputs, its sources, its command.
RULE = '''EXTENSION_TARGETS.append("results/extensions/contact_ratio.csv")


rule contact_ratio:
    input:
        geometry=[STUDY.geometry(trace, spiral) for trace, spiral in STUDY.points],
        config=ancient(FILES["study_config"]),
        sources=sources("contact-ratio"),
    output:
        out="results/extensions/contact_ratio.csv",
    params:
        **command("contact-ratio"),
    log:
        "logs/extensions/contact_ratio.log",
    shell:
        LSBG
'''


@pytest.fixture
def new_stage(study):
    """The copy with the new subcommand (a module of lsbg.cli: nothing else edited) and its
    rule file; taken away afterwards."""
    root, env = study
    module = root / "lsbg" / "cli" / "contact_ratio.py"
    rule = root / "workflow" / "extensions" / "contact_ratio.smk"
    try:
        module.write_text(COMMAND, encoding="utf-8")
        rule.write_text(RULE, encoding="utf-8")
        yield root, env
    finally:
        module.unlink(missing_ok=True)
        rule.unlink(missing_ok=True)
        shutil.rmtree(root / "results" / "extensions", ignore_errors=True)


@pytest.mark.slow
def test_a_new_stage_is_one_subcommand_and_one_rule_file(new_stage, tmp_path):
    root, env = new_stage
    extra = write_yaml(tmp_path / "extension.yaml", {"extensions": ["contact_ratio"]})
    proc = snakemake("-n", "-p", "--configfile", TEST_CONFIG, extra, cwd=root, env=env,
                     check=True)
    # only the new stage runs: the study is done and none of its sources changed
    assert {rule for rule, _ in planned_jobs(proc.output)} == {"contact_ratio", "all"}
    block = proc.output[proc.output.index("rule contact_ratio:"):]
    # its command line from the rule's names, its sources from the handler's imports
    assert "lsbg -v contact-ratio --geometry results/geometry/" in block
    assert "--config results/config.yaml --out results/extensions/contact_ratio.csv" in block
    assert ".snakemake/lsbg-sources/contact-ratio.sha256" in block.split("output:")[0]
    sources = (root / ".snakemake" / "lsbg-sources" / "contact-ratio.sha256").read_text()
    assert "lsbg/cli/contact_ratio.py" in sources and "lsbg/gear/geometry.py" in sources
    assert "lsbg/dynamics/model.py" not in sources and "lsbg/tca/loaded.py" not in sources
    # a priority from the rule graph: not measured, nothing waits for it (Snakemake prints
    # none for 0), while the study's rules have theirs
    assert "priority:" not in block.split("rule all:")[0]
    assert "priority:" in snakemake("-n", "--configfile", TEST_CONFIG, "--forceall", cwd=root,
                                    env=env, check=True).output
    snakemake("-j1", "--configfile", TEST_CONFIG, extra, cwd=root, env=env, check=True)
    table = pd.read_csv(root / "results" / "extensions" / "contact_ratio.csv")
    assert sorted(table["trace"]) == ["circular", "logarithmic"]
    assert (table["contact_ratio"] > 1).all()


@pytest.mark.slow
def test_a_study_folder_of_ones_own(study, tmp_path):
    """``snakemake -s REPO/Snakefile -d MYSTUDY``: results, logs and reports under the study's
    folder, its own extensions read from there, the repository's results untouched."""
    root, env = study
    mine = tmp_path / "mystudy"
    (mine / "workflow" / "extensions").mkdir(parents=True)
    (mine / "workflow" / "extensions" / "pair_pictures.smk").write_text(
        'EXTENSION_TARGETS.append("results/extensions/pictures.txt")\n\n\n'
        'rule pair_pictures:\n'
        '    input:\n'
        '        [STUDY.geometry(t, s) for t, s in STUDY.points],\n'
        '    output:\n'
        '        "results/extensions/pictures.txt",\n'
        '    log:\n'
        '        "logs/extensions/pictures.log",\n'
        '    shell:\n'
        '        "ls {input} > {output} 2> {log}"\n', encoding="utf-8")
    config = write_yaml(mine / "config.yaml", {"extensions": ["pair_pictures"]})
    before = sorted(p.relative_to(root) for p in (root / "results").rglob("*"))
    proc = snakemake("-n", "-s", root / "Snakefile", "-d", mine, "--configfile",
                     root / TEST_CONFIG, config, cwd=tmp_path, env=env, check=True)
    rules = {rule for rule, _ in planned_jobs(proc.output)}
    assert "pair_pictures" in rules and "paper_geometry" in rules   # a study of its own
    assert (mine / "results" / "config.yaml").is_file()
    assert sorted(p.relative_to(root) for p in (root / "results").rglob("*")) == before
