"""The service life: the bevel gear rating of ISO 10300 and the life a stress ratio implies.

* :mod:`lsbg.rating.virtual`: the virtual cylindrical gears of ISO 10300-1
  (method B1) of a design (:func:`rating_geometry`);
* :mod:`lsbg.rating.factors`: the influence factors, one function each;
* :mod:`lsbg.rating.iso10300`: contact and root stress, permissible stresses,
  safety factors and rated torques (:func:`rate`);
* :mod:`lsbg.rating.life`: the Basquin lines behind ISO 6336's life factors and
  the life ratio of two stresses;
* :mod:`lsbg.rating.config`: the ``rating`` section of the study configuration;
* :mod:`lsbg.rating.dataset`: a design point's rating beside its FE stresses.
"""
