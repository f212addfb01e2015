"""The runs and analyses of a study read back and gathered into datasets and tables.

* :mod:`lsbg.aggregate.runs`: run datasets read back (gear type, steady samples,
  theory);
* :mod:`lsbg.aggregate.combine`: the sweep dataset (``lsbg combine``);
* :mod:`lsbg.aggregate.summary`: the summary table (``lsbg summary``);
* :mod:`lsbg.aggregate.sweep_dataset`: a parameter sweep's runs as one dataset.
"""
