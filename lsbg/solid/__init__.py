"""The solid gears of a design point and its geometry directory on disk.

* :mod:`lsbg.solid.outline`: the section outlines of the gears on spheres
  about the apex, and the sampling of the solids;
* :mod:`lsbg.solid.solids`: the closed triangle meshes lofted through them;
* :mod:`lsbg.solid.polyhedra`: closed triangle meshes, their mass
  properties and binary STL;
* :mod:`lsbg.solid.mass`: the mass properties of the solids (mesh and
  quadrature);
* :mod:`lsbg.solid.urdf`: the pair for PyBullet; :mod:`lsbg.solid.render`:
  its picture;
* :mod:`lsbg.solid.step`: the exact solids as STEP (gmsh's OpenCASCADE);
* :mod:`lsbg.solid.export`: writes a design point's geometry directory;
* :mod:`lsbg.solid.directory`: its file names and manifest, reading it back.
"""
