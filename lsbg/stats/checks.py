"""The ``statistics`` section checked before any job, against the run it will read.

:func:`statistics_problems` returns one line per problem, starting with the
user's key and value: the windows in order within the run, and enough samples
for what ``lsbg summary`` computes on them. Part of
:func:`lsbg.study.checks.check_config`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["AD_MIN_SAMPLES", "statistics_problems"]

#: Fewest samples of lsbg.stats.anderson_darling (the summary's normality test).
AD_MIN_SAMPLES = 3


def statistics_problems(config, record_fits=True):
    """The statistics windows against the run, and enough samples for the summary.

    ``lsbg summary`` keeps the samples after ``steady_state_after_s`` (the
    Anderson-Darling test needs 3), cuts the chart window (start excluded,
    stop included) into subgroups of ``subgroup_size`` (its sample count
    must be a whole multiple of it), and splits the full-rate record after
    the steady-state start into the sampling phases (3 samples each). These
    are counted here on the run's own record instants
    (:meth:`lsbg.dynamics.SimulationSettings.record_grid`) with the
    summary's selection rules.

    Parameters
    ----------
    config : dict
        The configuration, defaults filled in: its ``simulation``,
        ``statistics`` and ``engines`` sections.
    record_fits : bool, default True
        False when a run's record exceeds the memory limit (the resource
        guard's problem, :func:`lsbg.study.resources.run_cost_problems`):
        its instants are then not laid out here, only the windows checked.

    Returns
    -------
    list of str
    """
    from lsbg.dynamics import SimulationSettings
    from lsbg.stats import spectra

    simulation, statistics = config["simulation"], config["statistics"]
    duration, samples = simulation["duration_s"], simulation["samples"]
    steady = statistics["steady_state_after_s"]
    start, stop = statistics["control_chart_window_s"]
    size = statistics["subgroup_size"]
    problems = []
    if steady >= duration:
        problems.append(f"statistics.steady_state_after_s = {steady!r}: must be below "
                        f"simulation.duration_s = {duration!r}")
    if not steady <= start < stop <= duration * (1 + 1e-9):
        problems.append(f"statistics.control_chart_window_s = {[start, stop]!r}: needs "
                        f"statistics.steady_state_after_s = {steady!r} <= start < stop <= "
                        f"simulation.duration_s = {duration!r}")
    if problems or not record_fits:
        return problems
    # The output instants (SimulationSettings.sample_times), valid settings or not.
    time = np.linspace(0.0, duration, int(samples) + 1)
    where = f"simulation.samples = {samples!r} over simulation.duration_s = {duration!r}"
    # The summary's selections (lsbg.stats.steady_state, subgroups_from_window:
    # a time within 1e-9 of a sample spacing of an edge counts as on it),
    # counted here without importing lsbg.stats.normality (statsmodels: seconds per parse).
    tol = 1e-9 * float(np.median(np.diff(time)))
    kept = int(np.sum(time - steady > tol))
    if kept < AD_MIN_SAMPLES:
        problems.append(f"{where}: {kept} samples after statistics.steady_state_after_s = "
                        f"{steady!r}; the statistics (Anderson-Darling) need at least "
                        f"{AD_MIN_SAMPLES}")
    window = int(np.sum((time - start > tol) & (time - stop <= tol)))
    if window == 0 or window % size:
        problems.append(f"{where}: {window} samples in statistics.control_chart_window_s = "
                        f"{[start, stop]!r} (start excluded), which statistics.subgroup_size = "
                        f"{size!r} does not divide into whole subgroups")
    try:
        settings = SimulationSettings.from_config(simulation, engine=config["engines"]["sweep"])
    except ValueError:
        return problems  # the settings themselves: named by lsbg.dynamics.checks
    # The full-rate record and the part of it the summary reads, as
    # lsbg.dynamics.model and lsbg.aggregate.runs.full_rate_series select them.
    times = settings.record_grid()[1]
    full = times[times >= settings.full_rate_start - 0.5 * settings.full_rate_interval]
    spacing = full[1] - full[0] if full.size > 1 else 1.0
    try:
        spectra.sampling_phase_spread(full[full >= steady - 1e-6 * spacing],
                                      settings.full_rate, samples / duration)
    except ValueError as error:
        problems.append(f"{where}: simulation.full_rate_hz = {simulation['full_rate_hz']!r} "
                        f"after statistics.steady_state_after_s = {steady!r}: {error}")
    return problems
