"""The line model's bands in the field of contact (lsbg.contact.bands)."""

import numpy as np
import pytest

from lsbg.contact import ContactParameters, MeshContact
from lsbg.contact import kernels as k
from lsbg.contact.bands import band_points
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair


@pytest.fixture(scope="module")
def drive():
    contact = MeshContact(GearPair(GearPairDesign()), ContactParameters(model="line"))
    sides, table = contact.arrays[1], contact.arrays[2]
    bands = int(sides[0, k.S_ROWS])
    return table[0, :bands], sides[0, k.S_PSI_LO], sides[0, k.S_PSI_HI]


def test_a_line_wholly_in_the_field_acts_at_its_bands_centres(drive):
    band, _, _ = drive
    lo = np.minimum(band[:, k.B_THETA_IN], band[:, k.B_THETA_OUT]).min()
    hi = np.maximum(band[:, k.B_THETA_IN], band[:, k.B_THETA_OUT]).max()
    at = band_points(band, 0.0, lo - 1.0, hi + 1.0)
    assert at.inside.all() and (at.edge == 0).all()
    np.testing.assert_array_equal(at.fraction, 1.0)
    np.testing.assert_array_equal(at.rho, band[:, k.B_RHO])
    np.testing.assert_array_equal(at.length, band[:, k.B_LENGTH])


def test_the_fields_end_cuts_a_band_at_the_middle_of_its_inside_part(drive):
    band, psi_lo, psi_hi = drive
    # lines at turns across the whole mesh: every band inside acts within its inside part,
    # a band the field's ends cut is an edge, and its length is the part inside
    turns = np.linspace(psi_lo - 0.5, psi_hi + 0.5, 61)
    at = band_points(band, turns, psi_lo, psi_hi)
    assert at.rho.shape == (turns.size, len(band))
    ins = at.inside
    assert ins.any() and not ins.all()
    assert np.all(at.psi[ins] >= at.bottom[ins] - 1e-9)
    assert np.all(at.psi[ins] <= at.top[ins] + 1e-9)
    assert np.all((at.fraction[ins] > 0) & (at.fraction[ins] <= 1))
    cut = ins & (at.fraction < 1)
    assert cut.any() and np.all(at.edge[cut] != 0)
    np.testing.assert_allclose(at.length, at.fraction * band[:, k.B_LENGTH])
    # a line beyond the last turn in mesh carries nothing
    assert not band_points(band, turns, psi_lo, psi_hi, last=turns[0] - 1).inside.any()
