"""Load spectra of ISO 6336-6: the Palmgren-Miner damage sum and the spectrum's safety
factor of each gear and failure mode.

A spectrum is a list of bins (torque in N m and speed in rpm of the reference gear, hours
at that load). For each bin ``i`` of one gear and one failure mode (pitting, bending):

* load cycles ``N_i = n_i 60 h_i c`` with ``c`` the gear's load cycles per revolution of
  the reference gear (``1 / u`` for the wheel of a pair given at its pinion, times the
  number of contacts per revolution for a sun or a planet);
* the stress ``sigma_i`` (``sigma_H`` or ``sigma_F`` of ISO 6336-2/-3 at the bin's torque
  and speed) and the S-N line of the bin (:class:`~pipeline.rating.life.StrengthCurve`:
  ``sigma_Hlim`` or ``sigma_Flim Y_ST Y_M`` times the life factor and the influence
  factors, which may depend on the bin's speed, e.g. ``Z_v``), both given by the caller,
  so that this module knows nothing of the gear pair;
* the load cycles to failure ``N_Fi`` at ``sigma_i`` on that line and the damage ``N_i /
  N_Fi``.

The damage ``D = sum N_i / N_Fi``; the spectrum's safety factor ``S`` is the factor on the
stresses of every bin that makes ``D = 1`` (on stress, as ``S_H`` and ``S_F`` are: the
load factor of a pitting spectrum is ``S^2``). ``D(S)`` is monotone, and may jump (the
static limit, the flat end of the line), so ``S`` is found by bisection on ``ln S`` to the
last bits of a double. A single bin's ``S`` is the constant-load rating's ``S_H`` or
``S_F`` at that bin's load cycles, since both use the same line.

Stresses below the endurance limit: the S-N line is the rating's own life line (ISO
6336-6 takes the S-N curve of ISO 6336-2/-3): beyond the knee it follows the long-life
branch, down to 0.85 of the endurance strength at 10^10 cycles (ISO 6336-6's Annex C
counts its two lowest bins on that branch: ``Z_NT`` 0.96 and 0.91 give 1.9 x 10^8 and
1.31 x 10^9 cycles), and a stress at or below the line's value there does no damage (the
line is flat beyond 10^10); with optimum conditions (the branch stays at 1) no stress at
or below the endurance strength does damage. This keeps a single bin equal to the
constant-load rating; an elementary Miner sum (the finite-life slope continued below the
knee) would count those stresses more severely.

Checked against ISO 6336-6:2019, Annex C, Table C.2 as transcribed in the public repository
gfsReboucas/Drivetrain (``data/table_C2.csv``, commit 4a88df34): ``tests/
test_rating_spectrum.py``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from pipeline.rating.life import StrengthCurve
from pipeline.validation import InputError, check_range

BIN_KEYS = ("torque_Nm", "speed_rpm", "duration_h")
"""The keys of one bin as a user writes it (``[[rating.spectrum]]`` rows)."""


@dataclass(frozen=True)
class LoadBin:
    """One bin of a load spectrum; checked by the :class:`LoadSpectrum` that holds it.

    Attributes
    ----------
    torque : torque on the reference gear (the pinion of a pair), N m.
    speed : its speed, rpm.
    hours : time at this load, h.
    """

    torque: float
    speed: float
    hours: float

    @property
    def revolutions(self) -> float:
        """Revolutions of the reference gear in this bin (-)."""
        return self.speed * 60.0 * self.hours


@dataclass(frozen=True)
class LoadSpectrum:
    """A load spectrum: at least one bin, every torque, speed and time positive.

    Attributes
    ----------
    bins : the bins, in the user's order.
    key : the input's name, for the errors (``rating.spectrum[2].torque_Nm``).
    """

    bins: tuple[LoadBin, ...]
    key: str = "rating.spectrum"

    def __post_init__(self) -> None:
        if len(self.bins) == 0:
            raise InputError(f"{self.key} is empty: give at least one bin "
                             f"({', '.join(BIN_KEYS)})")
        for i, b in enumerate(self.bins):
            for name, value, unit in zip(BIN_KEYS, (b.torque, b.speed, b.hours),
                                         ("N m", "rpm", "h"), strict=True):
                check_range(f"{self.key}[{i}].{name}", value, 0.0, math.inf, lo_open=True,
                            unit=unit)

    @classmethod
    def from_rows(cls, rows: list[Mapping[str, float]], key: str = "rating.spectrum"
                  ) -> LoadSpectrum:
        """The spectrum of ``rows`` written as a user writes them (``torque_Nm``,
        ``speed_rpm``, ``duration_h``, every key required); an unknown key is an error."""
        bins = []
        for i, row in enumerate(rows):
            unknown = sorted(set(row) - set(BIN_KEYS))
            if unknown:
                raise InputError(f"{key}[{i}].{unknown[0]} is not a key of a spectrum bin "
                                 f"(known: {', '.join(BIN_KEYS)})")
            missing = [k for k in BIN_KEYS if k not in row]
            if missing:
                raise InputError(f"{key}[{i}].{missing[0]} is missing (a bin needs "
                                 f"{', '.join(BIN_KEYS)})")
            for name in BIN_KEYS:
                value = row[name]
                if isinstance(value, bool) or not isinstance(value, (int, float)):
                    raise InputError(f"{key}[{i}].{name} = {value!r}: expected a number")
            bins.append(LoadBin(row["torque_Nm"], row["speed_rpm"], row["duration_h"]))
        return cls(tuple(bins), key)

    @property
    def hours(self) -> float:
        """Total time, h."""
        return sum(b.hours for b in self.bins)


@dataclass(frozen=True)
class BinStress:
    """What one gear and failure mode see in one bin (given by the caller).

    Attributes
    ----------
    stress : sigma_H or sigma_F at the bin's torque and speed, Pa.
    curve : the S-N line at the bin's operating point (its speed-dependent factors).
    """

    stress: float
    curve: StrengthCurve


@dataclass(frozen=True)
class SpectrumDamage:
    """The Miner sum of one gear and failure mode over a spectrum (arrays of shape
    ``(n_bins,)``, in the spectrum's order).

    Attributes
    ----------
    cycles : load cycles N_i of the gear in each bin (-).
    stress : the bins' stresses, Pa.
    cycles_to_failure : N_Fi at those stresses (-; inf where the stress does no damage).
    damage : N_i / N_Fi (-).
    total : D, the sum of the damages (-).
    safety : the factor on every bin's stress that makes D = 1 (-).
    """

    cycles: np.ndarray
    stress: np.ndarray
    cycles_to_failure: np.ndarray
    damage: np.ndarray
    total: float
    safety: float


def _cycles_to_failure(stress: np.ndarray, curves: list[StrengthCurve], factor: float
                       ) -> np.ndarray:
    """N_Fi at ``factor`` times the stresses: one vectorised call per distinct curve (bins
    at one speed share theirs)."""
    out = np.empty(len(curves))
    groups: dict[StrengthCurve, list[int]] = {}
    for i, c in enumerate(curves):
        groups.setdefault(c, []).append(i)
    for c, idx in groups.items():
        out[idx] = c.cycles_to_failure(factor * stress[idx])
    return out


def _damage(cycles: np.ndarray, stress: np.ndarray, curves: list[StrengthCurve],
            factor: float) -> float:
    """``D`` with every stress times ``factor``."""
    n_f = _cycles_to_failure(stress, curves, factor)
    with np.errstate(divide="ignore"):
        return float(np.where(np.isinf(n_f), 0.0, cycles / n_f).sum())


def miner_damage(spectrum: LoadSpectrum, stress_at: Callable[[LoadBin], BinStress],
                 cycles_per_revolution: float = 1.0) -> SpectrumDamage:
    """The Palmgren-Miner sum of one gear and failure mode over ``spectrum``:
    ``stress_at`` maps a bin to the gear's stress and S-N line there;
    ``cycles_per_revolution``: the gear's load cycles per revolution of the reference
    gear (-)."""
    return _miner(spectrum, [stress_at(b) for b in spectrum.bins], cycles_per_revolution)


def _miner(spectrum: LoadSpectrum, rated: list[BinStress], cycles_per_revolution: float
           ) -> SpectrumDamage:
    check_range("rating.cycles_per_revolution", cycles_per_revolution, 0.0, 1e3,
                lo_open=True)
    cycles = np.array([b.revolutions * cycles_per_revolution for b in spectrum.bins])
    stress = np.array([r.stress for r in rated])
    for i, s in enumerate(stress):
        check_range(f"{spectrum.key}[{i}] stress", s, 0.0, math.inf, lo_open=True, unit="Pa")
    curves = [r.curve for r in rated]
    n_f = _cycles_to_failure(stress, curves, 1.0)
    with np.errstate(divide="ignore"):
        damage = np.where(np.isinf(n_f), 0.0, cycles / n_f)
    return SpectrumDamage(cycles, stress, n_f, damage, float(damage.sum()),
                          _unit_damage_factor(cycles, stress, curves))


def _unit_damage_factor(cycles: np.ndarray, stress: np.ndarray,
                        curves: list[StrengthCurve]) -> float:
    """The factor ``S`` on the stresses with ``D(S) = 1``: bisection on ``ln S`` (``D`` is
    nondecreasing in ``S`` and may jump)."""
    def total(ln_s: float) -> float:
        return _damage(cycles, stress, curves, math.exp(ln_s))

    lo, hi = -1.0, 1.0
    while total(lo) >= 1.0:
        lo *= 2.0
        if lo < -700.0:
            raise InputError("rating: the spectrum is damaged at any stress (a bin has "
                             "no load cycles to failure at any stress)")
    while total(hi) < 1.0:
        hi *= 2.0
        if hi > 700.0:
            raise InputError("rating: the spectrum does no damage at any stress")
    while True:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            return math.exp(hi)
        if total(mid) >= 1.0:
            hi = mid
        else:
            lo = mid


@dataclass(frozen=True)
class SpectrumRating:
    """The Miner sums of a pair over a spectrum; tuples are (pinion, wheel).

    Attributes
    ----------
    pitting, bending : the :class:`SpectrumDamage` of each gear (bending: None for a gear
        not rated in bending).
    """

    pitting: tuple[SpectrumDamage, SpectrumDamage]
    bending: tuple[SpectrumDamage | None, SpectrumDamage | None]

    @property
    def safety_pitting_min(self) -> float:
        return min(d.safety for d in self.pitting)

    @property
    def safety_bending_min(self) -> float:
        """The smaller S_F of the gears rated in bending (NaN when none is)."""
        rated = [d.safety for d in self.bending if d is not None]
        return min(rated) if rated else math.nan


@dataclass(frozen=True)
class PairBinStress:
    """What a pair sees in one bin: ``pitting`` and ``bending`` of (pinion, wheel) (bending
    None for a gear not rated in bending)."""

    pitting: tuple[BinStress, BinStress]
    bending: tuple[BinStress | None, BinStress | None]


def rate_spectrum(spectrum: LoadSpectrum, stress_at: Callable[[LoadBin], PairBinStress], *,
                  cycles_per_revolution: tuple[float, float],
                  bending_cycles_per_revolution: tuple[float, float] | None = None
                  ) -> SpectrumRating:
    """The Miner sums of both gears in pitting and bending: ``stress_at`` maps a bin to the
    :class:`PairBinStress`; ``cycles_per_revolution`` of (pinion, wheel) per revolution of
    the reference gear (``(1, 1 / u)`` for a pair given at its pinion), for the flanks and,
    unless ``bending_cycles_per_revolution`` says otherwise, for the roots."""
    rated = [stress_at(b) for b in spectrum.bins]  # one evaluation per bin
    root_cycles = bending_cycles_per_revolution or cycles_per_revolution

    def mode(name: str, k: int, c: float) -> SpectrumDamage | None:
        per_bin = [getattr(r, name)[k] for r in rated]
        return None if per_bin[0] is None else _miner(spectrum, per_bin, c)

    return SpectrumRating(
        (mode("pitting", 0, cycles_per_revolution[0]),
         mode("pitting", 1, cycles_per_revolution[1])),
        (mode("bending", 0, root_cycles[0]), mode("bending", 1, root_cycles[1])))
