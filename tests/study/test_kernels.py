"""The workflow's first job (lsbg.study.kernels, ``lsbg kernels``): after it, from an empty
numba cache, a sweep's design point (``lsbg points``: geometry, loaded TCA, both models'
runs) and an unloaded TCA compile nothing, they load every kernel they call."""

import json
import os
import subprocess
import sys

import pytest

#: In a new process: a design point as the sweep's job makes it, then the unloaded TCA,
#: the block bootstrap; prints {kernel: [cache hits, cache misses]} of every kernel called.
DESIGN_POINT = """
import json, sys
from lsbg.cli import main
assert main(["points", "--config", "config.yaml", "--spiral-angles", "30", "--engine", "compiled",
             "--run", "point=point.nc", "--run", "line=line.nc", "--geometry-out", "pair",
             "--mesh-out", "mesh.nc", "--set", "simulation.duration_s=0.01",
             "--set", "simulation.samples=5", "--set", "simulation.ramp_time_s=0.004",
             "--set", "simulation.full_rate_after_s=0.004", "--set", "tca.loaded_positions=16"]) == 0
import numpy as np
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.stats.bootstrap import std_ci
from lsbg.tca.analysis import tooth_contact_analysis
from lsbg.tca.modification import FlankModification
tooth_contact_analysis(GearPair(GearPairDesign()), FlankModification.from_config(
    {"lengthwise_crowning_um": 25}), positions=8)
std_ci(np.cos(np.arange(50.0)), n_boot=100)
from lsbg.study.kernels import called_kernels
stats = {name.rsplit(".", 1)[1]: [sum(k.stats.cache_hits.values()),
                                  sum(k.stats.cache_misses.values())]
         for name, k in called_kernels().items()}
print(json.dumps(stats))
"""

#: The kernels' job (``lsbg kernels`` with this process's arguments); then prints every
#: signature of a kernel it compiled that has a literal argument type.
KERNELS_JOB = """
import json, sys
from lsbg.cli import main
code = main()
from lsbg.study.kernels import called_kernels
print(json.dumps([f"{name}{signature}" for name, kernel in called_kernels().items()
                  for signature in kernel.signatures if "Literal" in str(signature)]))
sys.exit(code)
"""


@pytest.mark.slow
def test_after_the_kernels_job_a_design_point_compiles_nothing(tmp_path):
    (tmp_path / "config.yaml").write_text(
        "flank_modification: {lengthwise_crowning_um: 25, profile_crowning_um: 5}\n",
        encoding="utf-8")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    first = subprocess.run([sys.executable, "-c", KERNELS_JOB, "kernels", "--config",
                            "config.yaml", "--out", "kernels.json"], cwd=tmp_path, env=env,
                           capture_output=True, text=True)
    assert first.returncode == 0, first.stderr
    # no kernel compiled a second time for a literal argument (numba types a counter that
    # starts as 0 as the literal 0 first): each costs seconds of compile from empty caches
    assert json.loads(first.stdout.splitlines()[-1]) == [], first.stdout
    record = json.loads((tmp_path / "kernels.json").read_text(encoding="utf-8"))
    assert record["history"] == "lsbg kernels --config config.yaml --out kernels.json"
    assert record["numba_cache"].startswith("numba-") and record["seconds"] > 0
    for kernel in ("contact.statics.static_mismatch", "contact.kernels.mesh_details",
                   "dynamics.compiled_engine.integrate", "tca.surface.point_separations",
                   "tca.surface.contact_search", "solid.render.rasterize"):
        assert record["kernels"].get(f"lsbg.{kernel}") == 1, kernel
    second = subprocess.run([sys.executable, "-c", DESIGN_POINT], cwd=tmp_path, env=env,
                            capture_output=True, text=True)
    assert second.returncode == 0, second.stderr
    stats = json.loads(second.stdout.splitlines()[-1])
    assert {"static_mismatch", "mesh_details", "integrate", "point_separations",
            "contact_search", "rasterize", "circular_block_stds"} <= set(stats), stats
    # every kernel the design point called came from the cache the first job filled
    assert all(hits >= 1 and misses == 0 for hits, misses in stats.values()), stats
