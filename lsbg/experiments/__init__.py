"""Numerical experiments on the meshing model, each a set of runs with a question.

* :mod:`lsbg.experiments.sensitivity`: the model-form sensitivity cases at the
  paper's design point (a setting scaled or switched);
* :mod:`lsbg.experiments.verification`: convergence under the time step and
  tolerance, and the engines' agreement;
* :mod:`lsbg.experiments.speed`: the dynamic-factor curve over pinion speed;
* :mod:`lsbg.experiments.sweeps`: parameter sweeps of any setting (the
  configuration's ``sweeps`` section);
* :mod:`lsbg.experiments.point_checks`: what the reports check at a design
  point (conjugacy, loaded TCA, contact state, contact resonance:
  ``lsbg checks``);
* :mod:`lsbg.experiments.rating_sweep`: ISO 10300 at every design point of
  the sweep (``lsbg rate-sweep``).
"""
