"""Tables of the reports, built from runs, loaded TCAs and the sweep dataset.

One module per report topic; none imports matplotlib (the figures are in
:mod:`lsbg.figures`), and none runs a stage: they read the files the commands
wrote and tabulate them (what a stage computes for a report is a command's
file, ``lsbg checks`` and ``lsbg rate-sweep``):

* :mod:`lsbg.tables.paper`: the paper's reproduction (Tables 1 and 3, the
  fluctuation verdict under the point model, control charts);
* :mod:`lsbg.tables.line_model`: the line model's verdict (loaded TCA,
  full-rate fluctuations, model-form sensitivity, trends over spiral angle,
  the dynamic-factor curve);
* :mod:`lsbg.tables.contact_state`: bearing patterns, V-H maps and their
  sensitivities;
* :mod:`lsbg.tables.tooth`: the uniform bed against the tooth's own FE
  compliance (mesh stiffness, loaded TE, contact pressure, root stress);
* :mod:`lsbg.tables.verification`: engine agreement, convergence, pressure
  angles, and the checks of ``lsbg checks`` (conjugacy, loaded TCA, contact
  state, contact resonance);
* :mod:`lsbg.tables.finding`: the paper report's finding (its claims, cells
  and sentences).

Use them as ``from lsbg.tables import paper as paper_tables``.
"""
