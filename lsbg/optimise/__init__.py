"""Each gear type at its best ease-off: a multi-objective optimisation of the pinion's relief.

In the spirit of Artoni, Gabiccini, Guiggiani & Kahraman (J. Mech. Des. 133,
2011, 121007): each tooth trace gets its own ease-off instead of one shared
crowning designed for neither (docs/optimise.md).

* :mod:`lsbg.optimise.space`: the design space, the ease-off coefficients of
  :class:`lsbg.tca.modification.FlankModification` within bounds;
* :mod:`lsbg.optimise.loaded`: the line model's loads point by point over a
  mesh cycle (the equilibrium of :func:`lsbg.tca.loaded.loaded_tca`);
* :mod:`lsbg.optimise.kinematics`: sliding and rolling speeds, relative curvature;
* :mod:`lsbg.optimise.friction`: friction laws, mesh power loss and efficiency;
* :mod:`lsbg.optimise.objectives`: the objectives and constraints of one design;
* :mod:`lsbg.optimise.search`: NSGA-II / NSGA-III (pymoo), hypervolume by generation;
* :mod:`lsbg.optimise.choice`: the rules that pick one design of a front;
* :mod:`lsbg.optimise.dataset`: the front as a CF dataset;
* :mod:`lsbg.optimise.checks`: the ``optimise`` section read and checked;
* :mod:`lsbg.optimise.run`: one trace's optimisation (``lsbg optimise``).
"""
