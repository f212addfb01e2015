"""The trace study's cells as a study plans them: their files, settings and jobs.

A mixin of :class:`lsbg.study.plan.Study` (which gives ``config``, ``optimise``,
``paper_spiral``, ``practice_traces`` and ``optimise_seeds``): the cells themselves are
:func:`lsbg.optimise.cells.trace_cells`' (docs/optimise.md, "Every cell").
"""

from __future__ import annotations

from functools import cached_property

from lsbg.study.points import FILES

__all__ = ["TraceStudyFiles"]


class TraceStudyFiles:
    """The trace study's cells of a :class:`lsbg.study.plan.Study`, the paper's first."""

    @cached_property
    def trace_cells(self):
        """The trace study's cells (:func:`lsbg.optimise.cells.trace_cells`), the paper's
        first; none without the optimisation."""
        if not self.optimise:
            return []
        from lsbg.optimise.cells import trace_cells

        return trace_cells(self.config)

    @property
    def other_cells(self):
        """The cells but the paper's, ``{label: cell}`` (their own rules'; the paper's
        files are the optimise rules')."""
        return {c["label"]: c for c in self.trace_cells if not c["paper"]}

    def cell_file(self, kind, trace, cell, seed=None):
        """A file of a cell's chain: ``kind`` one of practice_design, geometry, compliance,
        front, release, best_overlay, converged_front (``FILES["cell_<kind>"]``); the
        paper cell's are the practice and optimise rules' files, the LSBG's those of its
        angle's cell of the design's cutter."""
        by_label = {c["label"]: c for c in self.trace_cells}
        c = by_label[cell]
        if trace == "logarithmic":
            c = by_label[c["lsbg_cell"]]
        if kind == "practice_design":
            return (FILES["practice_design"] if c["spiral"] == self.paper_spiral else
                    FILES["cell_practice_design"].format(spiral=c["spiral"]))
        if c["paper"]:
            paper = {"geometry": "practice_geometry", "compliance": "practice_compliance",
                     "front": "optimise_front", "release": "optimise_release",
                     "best_overlay": "best_overlay",
                     "converged_front": "optimise_converged_front"}[kind]
            return FILES[paper].format(trace=trace, spiral=self.paper_spiral, seed=seed)
        return FILES[f"cell_{kind}"].format(trace=trace, cell=c["label"], seed=seed)

    def cell_trace_fronts(self, cell):
        """A cell's trace-fronts file: results/optimise/trace_fronts.nc for the paper's."""
        if cell == self.trace_cells[0]["label"]:
            return FILES["trace_fronts"]
        return FILES["cell_trace_fronts"].format(cell=cell)

    def cell_converged_fronts(self, cell):
        """The two traces' converged fronts a cell compares (the LSBG's first)."""
        return [self.cell_file("converged_front", t, cell) for t in self.practice_traces]

    @property
    def trace_study_jobs(self):
        """The jobs of the trace study's other cells, ``{rule: count}``
        (rules/trace_study.smk; the paper cell's are the optimise rules')."""
        others = self.other_cells.values()
        runs = {(t, c["lsbg_cell"] if t == "logarithmic" else c["label"])
                for c in others for t in self.practice_traces}
        runs = {(t, cell) for t, cell in runs if cell in self.other_cells}
        per_run = {"cell_geometry": 1, "cell_compliance": 1,
                   "cell_optimise": len(self.optimise_seeds), "cell_release": 1,
                   "cell_converged_front": 1}
        jobs = {"cell_practice_design": len({c["spiral"] for c in others
                                             if c["spiral"] != self.paper_spiral})}
        jobs.update({rule: n * len(runs) for rule, n in per_run.items()})
        jobs["cell_trace_fronts"] = len(others)
        return jobs

    def cell_settings(self, cell, trace):
        """The ``--set`` values of a cell's design point beyond the trace: its spiral angle,
        and an SBG's cutter radius unless it is the design's."""
        c = {x["label"]: x for x in self.trace_cells}[cell]
        settings = [f"design.spiral_angle_deg={c['spiral']}"]
        if trace != "logarithmic" and c["cutter_mm"] is not None:
            settings.append(f"design.cutter_radius_mm={c['cutter_mm']!r}")
        return settings
