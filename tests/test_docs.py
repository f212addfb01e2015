"""Every ``lsbg`` command and option the README and docs/ name exists, and every
``--set section.key=value`` they name is a key of the configuration's schema."""

import re
from pathlib import Path

import pytest

from lsbg.cli import build_parser

REPO = Path(__file__).resolve().parents[1]
DOCS = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md")),
        *sorted((REPO / "workflow" / "extensions").glob("*.smk"))]


def commands():
    """{subcommand: its option strings}."""
    parser = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    return {name: {o for action in p._actions for o in action.option_strings}
            for name, p in sub.choices.items()}


def named_commands(text):
    """(command, [options]) of each lsbg command line in ``text``: inline code spans that
    start with ``lsbg COMMAND``, and code-block lines (with their continuation lines)."""
    found = []
    for span in re.findall(r"`(lsbg [^`]+)`", text):
        found.append(span)
    lines = text.splitlines()
    in_block = False
    for k, line in enumerate(lines):
        if line.strip().startswith("```"):
            in_block = not in_block
            continue
        stripped = line.strip().lstrip("#").strip() if not in_block else line.strip()
        if in_block and re.match(r"^(?:lsbg|\"lsbg)\s+(?:-v\s+)?[a-z]", stripped.strip('"')):
            command = stripped.strip('"')
            j = k
            while lines[j].rstrip().endswith("\\") and j + 1 < len(lines):
                j += 1
                command += " " + lines[j].strip()
            found.append(command)
    out = []
    for command in found:
        words = command.replace("\\", " ").split()
        words = [w for w in words[1:] if w not in ("-v", "--verbose")]
        if not words or not re.match(r"^[a-z][a-z-]*$", words[0]):
            continue
        out.append((words[0], [w.split("=")[0] for w in words[1:]
                               if re.match(r"^--[a-z][a-z-]*", w)]))
    return out


@pytest.mark.parametrize("path", DOCS, ids=[p.name for p in DOCS])
def test_every_named_command_and_option_exists(path):
    known = commands()
    named = named_commands(path.read_text(encoding="utf-8"))
    missing = [(cmd, opt) for cmd, options in named for opt in [None, *options]
               if cmd not in known or (opt is not None and opt not in known[cmd])]
    assert not missing, f"{path.name}: no such lsbg command or option: {missing}"


def test_the_docs_name_the_options_a_sweep_and_an_extension_need():
    """The README names what a user writing a sweep or a stage has to know."""
    named = {(cmd, opt) for path in DOCS
             for cmd, options in named_commands(path.read_text(encoding="utf-8"))
             for opt in options}
    for needed in [("simulate", "--set"), ("simulate", "--config"),
                   ("sweep-run", "--point"), ("sweep-combine", "--csv"),
                   ("sensitivity", "--case"), ("mesh-mode", "--out")]:
        assert needed in named, needed


def named_settings(text):
    """The ``section.key`` of each ``--set section.key=value`` in ``text`` (placeholders in
    capitals, ``contact.KEY=VALUE``, left out)."""
    keys = re.findall(r"--set\s+['\"]?([A-Za-z_]+(?:\.[A-Za-z_0-9]+)+)=", text)
    return [key for key in keys if not any(re.fullmatch(r"[A-Z_]+", part)
                                           for part in key.split("."))]


@pytest.mark.parametrize("path", DOCS, ids=[p.name for p in DOCS])
def test_every_named_setting_is_a_key_of_the_schema(path):
    from lsbg.config import ConfigError, load_schema, parse_override

    schema = load_schema()
    unknown = []
    for key in named_settings(path.read_text(encoding="utf-8")):
        try:
            parse_override(f"{key}=null", schema)
        except ConfigError as err:
            unknown.append(str(err))
    assert not unknown, f"{path.name}: {unknown}"


def test_the_old_per_key_options_are_named_nowhere():
    """Issue 35: one override grammar; the per-key options are gone from the docs too."""
    old = {"--contact-model", "--compliance", "--set-contact", "--set-tooth", "--set-rating",
           "--modification", "--misalignment", "--load-torque", "--pinion-speed", "--duration",
           "--trace", "--spiral-angle", "--design", "--phases", "--axes", "--case-steps"}
    named = [(path.name, cmd, opt) for path in DOCS
             for cmd, options in named_commands(path.read_text(encoding="utf-8"))
             for opt in options if opt in old]
    assert not named, named


def test_the_api_quick_start_runs(tmp_path, monkeypatch):
    """docs/api.md's ten lines: the paper's pair, its TCA and loaded TCA, a labelled plot."""
    import matplotlib

    matplotlib.use("Agg")
    text = (REPO / "docs" / "api.md").read_text(encoding="utf-8")
    code = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    assert len([line for line in code.splitlines() if line.strip()]) <= 12
    monkeypatch.chdir(tmp_path)
    scope = {}
    exec(compile(code, "docs/api.md", "exec"), scope)
    assert (tmp_path / "transmission_error.png").stat().st_size > 1000
    # the crowned pair: a parabolic unloaded TE of tens of urad, a larger loaded one
    assert 20 < scope["tca"].attrs["transmission_error_peak_to_peak_urad"] < 100
    assert (scope["ltca"].attrs["transmission_error_peak_to_peak_urad"]
            > scope["tca"].attrs["transmission_error_peak_to_peak_urad"])
    assert scope["axes"][0].axes.get_ylabel() == "transmission error [urad]"


def test_every_dataset_label_is_short():
    """xarray's plots label an axis with the variable's long_name: at most 40 characters,
    the full definition kept as its description."""
    import xarray as xr

    from lsbg.files import short_labels

    ds = xr.Dataset({"transmission_error": ("x", [1.0], {"units": "urad", "long_name": "x" * 90}),
                     "speed": ("x", [1.0], {"units": "deg/s", "long_name": "gear speed"})})
    short_labels(ds)
    assert ds["transmission_error"].attrs == {"units": "urad", "long_name": "transmission error",
                                              "description": "x" * 90}
    assert ds["speed"].attrs["long_name"] == "gear speed" and "description" not in ds["speed"].attrs


def recipes(text):
    """(code, shown output) of each ```python block of ``text`` followed by a ```text block."""
    return re.findall(r"```python\n((?:(?!```).)*)```\s*```text\n((?:(?!```).)*)```", text, re.S)


NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def test_the_api_recipes_print_what_they_show(tmp_path, monkeypatch, capsys):
    """docs/api.md's everyday questions (loaded TE on the uniform bed and with the FE
    compliance, a V-H map, a rating, a run) run from a copy of the study's configuration
    and print the figures shown under them: each shown line that carries a number is a
    line of the output with the same words and numbers within 0.5 %."""
    import shutil

    text = (REPO / "docs" / "api.md").read_text(encoding="utf-8")
    blocks = recipes(text)
    assert len(blocks) >= 4, "docs/api.md: the everyday questions' recipes are missing"
    (tmp_path / "workflow").mkdir()
    shutil.copy(REPO / "workflow" / "config.yaml", tmp_path / "workflow" / "config.yaml")
    monkeypatch.chdir(tmp_path)
    wrong = []
    for code, shown in blocks:
        exec(compile(code, "docs/api.md", "exec"), {})
        printed = capsys.readouterr().out.splitlines()
        for line in shown.splitlines():
            if not NUMBER.search(line) or line.strip() == "...":
                continue
            words = NUMBER.sub("#", line).split()
            numbers = [float(x) for x in NUMBER.findall(line)]
            match = [out for out in printed if NUMBER.sub("#", out).split() == words]
            if not any(all(abs(a - b) <= 5e-3 * max(abs(b), 1e-9) + 0.011
                           for a, b in zip(map(float, NUMBER.findall(out)), numbers))
                       for out in match):
                wrong.append((line, match))
    assert not wrong, wrong
