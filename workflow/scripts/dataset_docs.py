"""docs/datasets.md from a finished study's results/: one file of each kind, its
dimensions and every coordinate and variable with its units and meaning.

    python workflow/scripts/dataset_docs.py results > docs/datasets.md

run on the tiny study's results (``snakemake -j2 --configfile workflow/config-test.yaml``).
"""
import sys
from pathlib import Path
import xarray as xr

KINDS = [
    ("runs/{trace}_beta{angle}_{model}_{engine}.nc", "runs/logarithmic_beta35_line_compiled.nc",
     "One meshing simulation (also `sensitivity/{trace}_beta{angle}_{case}.nc`, `practice/runs/`, `best/runs/`, `practice/sensitivity/`, `best/sensitivity/`)."),
    ("sweep.nc", "sweep.nc", "Every design point's runs and their summaries, on (contact model, trace, spiral angle)."),
    ("geometry/{trace}_beta{angle}/flanks.nc", "geometry/logarithmic_beta35/flanks.nc", "The exact flank surfaces of tooth 0 (also `practice/geometry/`)."),
    ("mesh/{trace}_beta{angle}.nc", "mesh/logarithmic_beta35.nc", "The loaded TCA on the uniform bed (line model)."),
    ("tca/{trace}_beta{angle}.nc", "tca/logarithmic_beta35.nc", "The unloaded TCA from the flank surfaces (also `practice/tca/`, `best/tca/`)."),
    ("vh/{trace}_beta{angle}.nc", "vh/logarithmic_beta35.nc", "The V-H map (also `vh/{trace}_beta{angle}_{case}.nc`, `practice/vh/`, `best/vh/`)."),
    ("tooth/{trace}_beta{angle}_compliance.nc", "tooth/logarithmic_beta35_compliance.nc", "The FE compliance of both members (also `practice/tooth/`)."),
    ("tooth/{trace}_beta{angle}_ltca.nc", "tooth/logarithmic_beta35_ltca.nc", "The FE loaded TCA (also `tooth/{trace}_beta{angle}_{case}_ltca.nc`, `practice/tooth/`, `best/tooth/`)."),
    ("tooth/{trace}_beta{angle}_envelope.nc", "tooth/logarithmic_beta35_envelope.nc", "The FE loaded TCA at the corners of the V-H envelope."),
    ("load_curves/{paper,practice}_{trace}_beta{angle}.nc", "load_curves/paper_logarithmic_beta35.nc", "The FE loaded TCA over a load range, with ISO 10300's stresses."),
    ("rating/{trace}_beta{angle}.nc", "rating/logarithmic_beta35.nc", "ISO 10300 method B1 and the FE stresses, per sensitivity case (also `practice/rating/`, `best/rating/`)."),
    ("rating_sweep.nc", "rating_sweep.nc", "ISO 10300 at every design point of the sweep."),
    ("optimise/{trace}_beta{angle}_seed{n}_front.nc", "optimise/logarithmic_beta35_seed1_front.nc", "An ease-off search: its final population and front (`reference_*`: the shared design)."),
    ("optimise/trace_fronts.nc", "optimise/trace_fronts.nc", "Trace against trace (`lsbg trace-fronts`; docs/optimise.md): the statistics of the traces' converged fronts in the paper's cell. Each other cell of the `trace_study` section writes `optimise/trace_fronts_{cell}.nc` with the same variables (its spiral angle and the SBG's cutter in the attributes `cell_spiral_angle_deg`, `cell_cutter_radius_mm`), its chain under `trace_study/{cell}/`."),
    ("verification/{trace}_beta{angle}_checks.nc", "verification/logarithmic_beta35_checks.nc", "The verification checks and their bounds."),
]


def meaning(v):
    text = v.attrs.get("description") or v.attrs.get("long_name") or ""
    return " ".join(str(text).split()).replace("|", "/")


def main(results):
    out = ["# The datasets the study writes", "",
           "Every NetCDF file of a study's `results/`, one of each kind, with its dimensions and",
           "every coordinate and variable: its name, `units` and meaning (the variable's",
           "`description`, else its `long_name`). Read from the tiny study's files",
           "(`snakemake -j2 --configfile workflow/config-test.yaml`); the default study's have",
           "the same variables on longer axes. Open one with `lsbg.open_dataset(path)` or",
           "`xarray.open_dataset(path)`; docs/usage.md says what each file is for. A parameter",
           "sweep (`sweeps:`) adds `results/sweeps/{name}.nc`, the runs' variables on the swept",
           "values, with each quantity's full-rate std by mesh-harmonic band",
           "(`{quantity}_full_rate_std_1_3`, `_4_7`, `_8_up`, `_below_1`, `_mode`), as",
           "`results/summary.csv` has them per run (docs/usage.md; docs/model.md, \"The",
           "fluctuation by frequency band\"). This page is made by",
           "`python workflow/scripts/dataset_docs.py results`.", ""]
    for pattern, example, what in KINDS:
        ds = xr.open_dataset(Path(results) / example)
        dims = ", ".join(f"{k} {n}" for k, n in ds.sizes.items())
        out += [f"## `results/{pattern}`", "", f"{what} Dimensions (tiny study): {dims}.", "",
                "| name | units | meaning |", "|---|---|---|"]
        for name, v in list(ds.coords.items()) + list(ds.data_vars.items()):
            kind = " (coordinate)" if name in ds.coords else ""
            out.append(f"| `{name}`{kind} | {v.attrs.get('units', '')} | {meaning(v)} |")
        out.append("")
    print("\n".join(out).rstrip())


main(sys.argv[1])
