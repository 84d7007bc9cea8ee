"""FrictionCorrected: the friction change of the slice model added to a normal-load source."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.contact.source import FrictionCorrected, SliceCompliance
from pipeline.stiffness.mesh import FrictionModel, PairModel


@pytest.fixture(scope="module")
def model(helical_traction_pair):
    return PairModel.build(helical_traction_pair)


def test_dry_source_plus_friction_change_equals_friction_source(model):
    """Dry slices + (friction - dry) on the diagonal equal the slices with friction exactly."""
    dry = SliceCompliance(model, slices=12)
    wet = SliceCompliance(model, slices=12, friction=FrictionModel(mu=0.1))
    corrected = FrictionCorrected(dry, wet)
    for pos in model.pair.mesh_cycle(7):
        np.testing.assert_allclose(corrected.matrix(pos), wet.matrix(pos), rtol=1e-13, atol=0)
        change = corrected.friction_change(pos)
        pts = corrected.points(pos)
        approach = pts.s < model.pair.s_pitch
        # Yang et al. (2026): friction stiffens in approach (less compliance) and softens in recess
        assert np.all(change[approach] < 0) and np.all(change[~approach] > 0)


def test_mismatched_points_are_refused(model):
    """Sources with different slices cannot be combined."""
    with pytest.raises(ValueError, match="same number of slices"):
        FrictionCorrected(SliceCompliance(model, slices=10),
                          SliceCompliance(model, slices=12, friction=FrictionModel(mu=0.1))
                          ).matrix(model.pair.mesh_cycle(3)[1])
