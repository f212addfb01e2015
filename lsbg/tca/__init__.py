"""Contact state: flank modification, assembly displacements and the tooth
contact analysis from the real surfaces (:mod:`lsbg.tca.analysis`)."""
