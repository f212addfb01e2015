"""Matched designs: the two traces' front members paired and compared design by design.

The fronts compared as sets (:mod:`lsbg.optimise.fronts`) say which trace's
searches reach further; the matched designs ask the paper's questions of
designs that are equally good on the search's terms (docs/optimise.md,
"Matched designs"):

* :mod:`lsbg.matched.pairs`: the LSBG's and the SBG's converged front members
  paired one to one on two objectives (pattern movement and contact pressure,
  normalised by the common box of ``lsbg trace-fronts``), a caliper dropping
  poor matches, and the paired statistics (Wilcoxon's signed-rank test and a
  bootstrap interval over the pairs) of a per-pair log ratio;
* :mod:`lsbg.matched.stability`: each design's stability, the driveline's and
  the prescribed pinion's, by a proxy (the loaded TE's mesh harmonics through
  the linearised system's frequency response) and by a full run;
* :mod:`lsbg.matched.run`: the pairs of two converged fronts, one design's
  answers, the statistics over the pairs' log std ratios;
* :mod:`lsbg.matched.stage`: ``lsbg matched-pairs``' work, every pair's designs
  answered (stability, the FE figures; the pattern's movement is the searches'
  objective, the ISO rating the design point's: it takes no ease-off);
* :mod:`lsbg.matched.dataset`: the pairs and their answers as a CF dataset;
* :mod:`lsbg.matched.checks`: the ``matched`` section's check beyond its schema.

SI inside; the objectives in :data:`lsbg.optimise.objectives.QUANTITIES`' units.
"""
