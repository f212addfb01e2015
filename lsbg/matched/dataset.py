"""The matched pairs and their answers as a CF dataset (results/optimise/matched_pairs.nc)."""

from __future__ import annotations

import numpy as np

from lsbg.matched.pairs import MATCH_OBJECTIVES
from lsbg.matched.run import ESTIMATES
from lsbg.matched.stability import BOUNDARIES, STABILITY_QUANTITIES
from lsbg.optimise.objectives import QUANTITIES
from lsbg.optimise.verdict import FE_QUANTITIES

__all__ = ["STATISTICS", "matched_pairs_dataset"]

#: The unit of each stability quantity's std, in STABILITY_QUANTITIES' order.
_STD_UNITS = {name: {"gear_speed": "deg/s", "tangential_force_outer": "N"}[name]
              for name in STABILITY_QUANTITIES}
#: The paired statistics' variables: name -> long name (all dimensionless).
STATISTICS = {
    "pairs": "pairs with both stds finite",
    "mean": "mean over the pairs of log std(SBG)/std(LSBG) (> 0: the LSBG calmer)",
    "median": "median over the pairs of the log std ratio",
    "positive": "share of the pairs whose log std ratio is > 0 (the LSBG calmer)",
    "wilcoxon_statistic": "Wilcoxon signed-rank statistic of the log std ratios",
    "wilcoxon_p": "its two-sided p (NaN: fewer than 2 pairs)",
    "low": "lower end of the percentile bootstrap interval of the mean over the pairs",
    "high": "upper end of that interval",
}


def matched_pairs_dataset(matched, converged, std, fe, statistics, attrs=None,
                          state_statistics=None):
    """The matched pairs' dataset.

    Parameters
    ----------
    matched : dict
        :func:`lsbg.matched.run.matched_designs`.
    converged : tuple of xarray.Dataset
        The two traces' converged fronts (the LSBG's first).
    std : numpy.ndarray
        (pairs, trace, estimate, boundary, quantity): the stds [deg/s, N] (NaN: not run).
    fe : dict
        ``{name of FE_QUANTITIES: (pairs, trace) array}`` (may be empty).
    statistics : dict
        :func:`lsbg.matched.run.ratio_statistics` of the log ratios.
    attrs : dict, optional
    state_statistics : dict, optional
        ``{figure: ratio_statistics of its (pairs, 1) log ratios}``: the contact state's
        and life's figures (the FE figures, the pattern's movement) over the pairs.

    Returns
    -------
    xarray.Dataset
        On ``pair``, ``trace``, ``estimate``, ``boundary``, ``quantity``.
    """
    import xarray as xr

    import lsbg

    one = "1"
    member = matched["member"]
    pt = ("pair", "trace")
    data = {
        "member": (pt, member, {"units": one, "long_name": "the design's member in its trace's "
                                                         "converged front dataset"}),
        "seed": (pt, _taken(converged, member, "seed", -1).astype(int), {
            "units": one, "long_name": "seed of the design's search"}),
        "individual": (pt, _taken(converged, member, "individual", -1).astype(int), {
            "units": one, "long_name": "the design's individual in its search's front dataset"}),
        "distance": (("pair",), matched["distance"], {
            "units": one, "long_name": "distance of the pair's designs in the normalised "
                                       f"{' and '.join(MATCH_OBJECTIVES)}"}),
    }
    for name in converged[0].attrs["objectives"].split():
        unit, text = QUANTITIES[name]
        data[name] = (pt, _taken(converged, member, name), {
            "units": unit, "long_name": f"{text}, at the converged positions"})
    dims = ("pair", "trace", "estimate", "boundary", "quantity")
    for q, (quantity, unit) in enumerate(_STD_UNITS.items()):
        data[f"std_{quantity}"] = (dims[:-1], std[..., q], {"units": unit, "long_name": (
            f"steady std of {quantity} by the estimate (NaN: no full run)")})
    with np.errstate(divide="ignore", invalid="ignore"):
        data["log_std_ratio"] = (dims[:1] + dims[2:], np.log(std[:, 1] / std[:, 0]), {
            "units": one, "long_name": "log std(SBG) / std(LSBG) of the pair (> 0: the LSBG "
                                       "calmer)"})
        data["proxy_error"] = (dims[:2] + dims[3:], std[:, :, 0] / std[:, :, 1] - 1, {
            "units": one, "long_name": "the proxy's std over the full run's less 1 (NaN: no "
                                       "full run)"})
    for name, values in fe.items():
        unit, text = FE_QUANTITIES[name]
        data[f"fe_{name}"] = (pt, values, {"units": unit, "long_name": text})
    for name, text in STATISTICS.items():
        data[f"ratio_{name}"] = (dims[2:], statistics[name], {"units": one, "long_name": text})
    for figure, stats in (state_statistics or {}).items():
        for name, text in STATISTICS.items():
            data[f"{figure}_ratio_{name}"] = ((), float(stats[name][0]), {
                "units": one, "long_name": text.replace("log std ratio", f"log {figure} ratio")
                .replace("log std(SBG)/std(LSBG)", f"log {figure} SBG/LSBG")
                .replace("the LSBG calmer", "the LSBG's lower")})
    traces = [str(d.attrs.get("design_trace")) for d in converged]
    base = {"Conventions": "CF-1.11",
            "title": "Matched designs of the two traces' converged fronts: stability, contact "
                     "state and life (docs/optimise.md, \"Matched designs\")",
            "source": f"lsbg {lsbg.__version__} (lsbg.matched)",
            "lsbg_version": lsbg.__version__, "traces": " ".join(traces),
            "match_objectives": " ".join(MATCH_OBJECTIVES),
            "pairs_found": int(member.shape[0]),
            "candidates": " ".join(str(int(n)) for n in matched["candidates"]),
            "assigned": int(matched["assigned"]), "dropped_by_caliper": int(matched["dropped"])}
    base.update(attrs or {})
    coords = {"pair": ("pair", np.arange(member.shape[0]), {
                  "units": one, "long_name": "matched pair, in the LSBG's order"}),
              "trace": ("trace", traces, {"units": one, "long_name": "tooth trace"}),
              "estimate": ("estimate", list(ESTIMATES), {
                  "units": one, "long_name": "proxy: the loaded TE through the linearised "
                                             "system (lsbg.matched.stability); full: the run"}),
              "boundary": ("boundary", list(BOUNDARIES), {
                  "units": one, "long_name": "simulation.boundary of the stds"}),
              "quantity": ("quantity", list(STABILITY_QUANTITIES), {
                  "units": one, "long_name": "run dataset variable of the std"})}
    return xr.Dataset(data, coords=coords, attrs=base)


def _taken(converged, member, name, fill=np.nan):
    """(pairs, 2) of variable ``name`` of each trace's converged front at ``member``."""
    out = np.full(member.shape, fill, float)
    for t, d in enumerate(converged):
        if member.shape[0]:
            out[:, t] = d[name].values[member[:, t]]
    return out
