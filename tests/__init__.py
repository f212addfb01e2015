"""lsbg's tests: one folder per package, one file per module (as pvlib lays them out)."""
