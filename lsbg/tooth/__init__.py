"""The tooth itself: finite-element compliance, local contact, and the LTCA on them."""
