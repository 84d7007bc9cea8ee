"""FrictionCorrected: the slice model's relative friction change on a normal-load source."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pipeline.contact.source import FrictionCorrected, SliceCompliance
from pipeline.stiffness.mesh import FrictionModel, PairModel


@pytest.fixture(scope="module")
def model(helical_traction_pair):
    return PairModel.build(helical_traction_pair)


@pytest.mark.parametrize("coupling", [0.0, 0.2])
def test_dry_source_corrected_equals_friction_source(model, coupling):
    """Dry slices scaled by the friction ratio equal the slices with friction exactly, with
    or without slice coupling (its off-diagonal kappa sqrt(c_i c_j) scales congruently)."""
    dry = SliceCompliance(model, slices=12, coupling=coupling)
    wet = SliceCompliance(model, slices=12, friction=FrictionModel(mu=0.1), coupling=coupling)
    corrected = FrictionCorrected(dry, wet)
    for pos in model.pair.mesh_cycle(7):
        np.testing.assert_allclose(corrected.matrix(pos), wet.matrix(pos), rtol=1e-13, atol=0)
        ratio = corrected.friction_ratio(pos)
        pts = corrected.points(pos)
        approach = pts.s < model.pair.s_pitch
        # Yang et al. (2026): friction stiffens in approach (less compliance) and softens in recess
        assert np.all(ratio[approach] < 1) and np.all(ratio[~approach] > 1)


def test_a_singular_coupled_source_stays_semidefinite(model):
    """A semidefinite G of lower rank than its points (a 3D table read on slices finer than
    its face grid) stays semidefinite, keeps its rank and gets the slice model's relative
    change on its diagonal; the former additive change (the slices' c(mu) - c(0), which
    grows with the slice count) made it indefinite."""

    @dataclasses.dataclass(frozen=True)
    class LowRank:
        """Rank-4 Gram matrix on the slice points, scaled to 1e-8 m/N."""

        pair: object
        slices: SliceCompliance
        tip_contact: bool = False

        def points(self, position):
            return self.slices.points(position)

        def matrix(self, position):
            n = self.slices.points(position).s.size
            V = np.random.default_rng(3).standard_normal((n, 4))
            return 1e-8 * V @ V.T / 4

    wet = SliceCompliance(model, slices=30, friction=FrictionModel(mu=0.1))
    src = FrictionCorrected(LowRank(model.pair, wet), wet)
    pos = model.pair.mesh_cycle(7)[2]
    G0, G = src.base.matrix(pos), src.matrix(pos)
    ev = np.linalg.eigvalsh(G)
    assert ev[0] > -1e-12 * ev[-1]
    assert np.linalg.matrix_rank(G, tol=1e-10 * ev[-1]) == 4
    np.testing.assert_allclose(np.diag(G), np.diag(G0) * src.friction_ratio(pos), rtol=1e-13)
    dry = dataclasses.replace(wet, friction=FrictionModel(mu=0.0))
    additive = G0 + np.diag(wet.diagonal(pos) - dry.diagonal(pos))
    assert np.linalg.eigvalsh(additive)[0] < -1e-3 * ev[-1]


def test_mismatched_points_are_refused(model):
    """Sources with different slices cannot be combined."""
    with pytest.raises(ValueError, match="same number of slices"):
        FrictionCorrected(SliceCompliance(model, slices=10),
                          SliceCompliance(model, slices=12, friction=FrictionModel(mu=0.1))
                          ).matrix(model.pair.mesh_cycle(3)[1])
