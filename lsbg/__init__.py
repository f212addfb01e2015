"""lsbg: logarithmic spiral bevel gears, from exact geometry to meshing statistics.

Physics inside the package is in SI units (m, kg, s, N, rad); the paper's units
(mm, deg, deg/s, N*s/mm) appear only at the edges: configuration, reports and
the ``units`` attributes of written datasets.
"""

__version__ = "0.1.0"
