"""The pair as a designer would make it: the practice design, its load curves, a load spectrum.

* :mod:`lsbg.practice.design`: the published pair shifted and thinned by stated
  rules (ISO 23509's x_hm1 by its c_ham or AGMA 209's, x_smn1), its tips relieved by the
  mesh's deflection, at its rated torque, as a configuration overlay;
* :mod:`lsbg.practice.load_curve`: the FE loaded TCA and ISO 10300 against torque;
* :mod:`lsbg.practice.spectrum`: the service life under a load spectrum (Miner's rule).
"""
