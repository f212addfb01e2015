"""The gear pair: its design (the paper's Table 1 and what follows from it) and its exact flanks.

* :mod:`lsbg.gear.design`: :class:`GearPairDesign`, the design parameters and
  the quantities derived from them (pitch and base cones, cone distances,
  the mean point), SI inside;
* :mod:`lsbg.gear.plane`: the plane of action and the generating curve drawn
  in it, the field of contact and the contact lines;
* :mod:`lsbg.gear.geometry`: :class:`GearPair`, the exact flanks swept by
  that plane rolling on a base cone;
* :mod:`lsbg.gear.flank`: a member's flank in the coordinates the later
  stages use (plane of action, spheres about the apex) and the mesh cycle's
  pinion rotation;
* :mod:`lsbg.gear.vectors`: rotation and cross product of 3-vectors;
* :mod:`lsbg.gear.theory`: the rigid-gear predictions of Eq. 12-13.
"""
