"""The load distribution step of a run: what the load distribution report shows, computed
in the chain as a timed step (the report only renders it).

For every mesh with a loaded contact cycle: the load distribution over the flank
(:func:`pipeline.contact.distribution.load_distribution`: line load, K_Hbeta, Hertz
pressure, TE orders), the FE root stress of both gears under the cycle's loads
(:func:`pipeline.contact.root_stress.analyse_root_stress`, its FE tables from the run's
cache), and for a herringbone sun-planet mesh both halves from the contact through the
groove with the root stress under each
(:func:`pipeline.contact.herringbone_distribution.herringbone_distribution`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from pipeline.config import Gearbox
from pipeline.contact.distribution import LoadDistribution, load_distribution
from pipeline.contact.herringbone_distribution import (
    HerringboneDistribution,
    herringbone_distribution,
)
from pipeline.contact.root_stress import RootStress, analyse_root_stress
from pipeline.progress import Steps
from pipeline.run.chain import MeshStages, RunOptions, step_tag


@dataclass(frozen=True)
class DistributionStage:
    """The load distribution of one mesh.

    Attributes
    ----------
    distribution : over the flank and the cycle (N/m, Pa, m; -).
    root_stress : FE root stress of both gears (Pa).
    halves : both halves of a herringbone sun-planet mesh, or ``None``.
    half_roots : root stress under each half ("left", "right") and under the equal split
        ("equal split"), or ``None``.
    """

    distribution: LoadDistribution
    root_stress: RootStress
    halves: HerringboneDistribution | None = None
    half_roots: Mapping[str, RootStress] | None = None


def distribution_stages(box: Gearbox, meshes: Mapping[str, MeshStages], options: RunOptions,
                        log: Steps) -> dict[str, DistributionStage]:
    """The :class:`DistributionStage` of every mesh with a contact cycle (module docstring),
    one timed step per mesh."""
    def root(cycle, pair, operation):
        return analyse_root_stress(cycle, pair, operation, box.fe_source,
                                   cache=options.cache,
                                   show_progress=options.show_progress)

    out: dict[str, DistributionStage] = {}
    for name, st in meshes.items():
        if st.contact is None:
            continue
        with log.step(f"load distribution and root stress{step_tag(name)}"):
            actual, op = st.stiffness.actual, st.case.operation
            rs = root(st.contact, actual, op)
            halves = half_roots = None
            if st.herringbone is not None:
                hb = st.herringbone
                halves = herringbone_distribution(hb.cycle, hb.pair, hb.operation,
                                                  equal_split=st.contact)
                half_roots = {side: root(halves.half(side).cycle, hb.pair,
                                         halves.half(side).operation)
                              for side in ("left", "right")}
                half_roots["equal split"] = rs
            out[name] = DistributionStage(load_distribution(st.contact, actual, op), rs,
                                          halves, half_roots)
    return out
