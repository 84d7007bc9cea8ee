"""A mesh's rating under a load spectrum (ISO 6336-6): the Miner sum of each gear and mode.

Each bin is rated by :func:`~pipeline.rating.pair_rating.rate_pair` at its own torque and
speed, so that what depends on the load and the speed (K_v, K_Halpha, method C's K_Hbeta,
Z_v) is the bin's, with the application factor K_A = 1: the spectrum stands for the
loads K_A would cover (ISO 6336-6). The bin's contact and root stresses and each gear's
S-N line of that bin (:attr:`PairRating.curves <pipeline.rating.pair_rating.PairRating>`)
go to :func:`pipeline.rating.spectrum.rate_spectrum`, with each gear's load cycles per
revolution of the pinion (a sun or a ring one per planet). A planetary set's K_v is each
mesh's own here (the constant-load rating takes the larger of the two meshes').
"""

from __future__ import annotations

import dataclasses

from pipeline.geometry.pair import GearPair
from pipeline.rating.pair_rating import (
    GearRatingInputs,
    PairRating,
    RatingInputs,
    cycles_per_revolution,
    rate_pair,
)
from pipeline.rating.spectrum import (
    BinStress,
    LoadBin,
    LoadSpectrum,
    PairBinStress,
    SpectrumRating,
    rate_spectrum,
)


def _bin_stress(r: PairRating) -> PairBinStress:
    pitting = tuple(BinStress(r.contact.stress[k], r.curves[k][0]) for k in range(2))
    bending = tuple(None if r.bending[k] is None else
                    BinStress(r.bending[k].stress, r.curves[k][1]) for k in range(2))
    return PairBinStress(pitting=pitting, bending=bending)


def rate_pair_spectrum(pair: GearPair, spectrum: LoadSpectrum, inputs: RatingInputs,
                       gears: tuple[GearRatingInputs, GearRatingInputs], mesh: str = "pair",
                       planets: int = 1, double_helical: bool = False) -> SpectrumRating:
    """The Miner damage and the spectrum's safety factors of ``pair`` (module docstring);
    the bins' torque (N m) and speed (rpm) are the pinion's."""
    at_bin = dataclasses.replace(inputs, application_factor=1.0)

    def stress_at(b: LoadBin) -> PairBinStress:
        r = rate_pair(pair, b.torque, b.speed, dataclasses.replace(at_bin, life_hours=b.hours),
                      gears, mesh, planets, double_helical=double_helical)
        return _bin_stress(r)

    return rate_spectrum(spectrum, stress_at,
                         cycles_per_revolution=cycles_per_revolution(pair, mesh, planets))
