"""``[contact.errors]`` of a gearbox file -> :class:`~pipeline.contact.tooth_errors.ToothErrors`.

Per-tooth errors of a pair's gears; with them ``gearpipe run`` adds the loaded contact
through a whole revolution (:mod:`pipeline.contact.revolution`)::

    [contact.errors]
    single_pitch_pinion_um = [1.5, -0.5, ...]   # f_pt of teeth 0 .. z1 - 1, summing to 0
    single_pitch_gear_um = [...]                 # f_pt of the gear's teeth
    eccentricity_pinion_um = 10.0                # runout: teeth centred e off the axis
    eccentricity_phase_pinion_deg = 90.0         # 90: teeth e behind along the line of action
    eccentricity_gear_um = 0.0
    eccentricity_phase_gear_deg = 0.0
    span = "hunting"     # LCM(z1, z2) mesh cycles; "pinion" / "gear": one revolution

Signs, tooth numbering and how each error becomes a gap: :mod:`pipeline.contact.tooth_errors`.
The deviations are given tooth by tooth (measured, or designed by the user's own script):
there is no generator of a random pattern from a tolerance (an ISO 1328-1 grade's f_pt),
because one seeded pattern is one gear of many, and its sidebands belong to the seed, not to
the tolerance; a tolerance study runs many patterns.
Every key left out is zero. Refused: a phase without its eccentricity; errors on a
planetary set, or on a pair on shafts (the revolution does not take their deflection);
``[contact] pitch_errors_um`` beside this table (it offsets the tooth pairs of one mesh
cycle: the per-tooth errors replace it).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from pipeline.config import tables as T
from pipeline.config.schema import read_table, restated
from pipeline.config.units import format_value, unit_of_key
from pipeline.contact.revolution import revolution_size
from pipeline.contact.tooth_errors import GearErrors, ToothErrors
from pipeline.geometry.pair import GearPair
from pipeline.validation import InputError

WHERE = "contact.errors"


def tooth_errors(doc: Mapping[str, Any], kind: str, pair: GearPair | None,
                 positions: int) -> ToothErrors | None:
    """The ``[contact.errors]`` table of ``doc`` (None without it), checked against the
    pair's tooth counts and the number of positions it asks for (``positions`` per mesh
    cycle)."""
    contact = doc.get("contact", {})
    if not isinstance(contact, Mapping) or "errors" not in contact:
        return None
    table = contact["errors"]
    values = read_table(table, T.ERRORS, WHERE)
    if kind != "pair" or pair is None:
        raise InputError("[contact.errors] belongs to a gear pair ([pinion] and [gear]); the "
                         "full-revolution contact is not built for a planetary set")
    shafts = [r for r in ("pinion", "gear") if isinstance(doc.get(r), Mapping)
              and "shaft" in doc[r]]
    if shafts:
        raise InputError(f"[contact.errors] with [{shafts[0]}.shaft]: the full-revolution "
                         "contact does not take the shafts' deflection; leave one of them out")
    if "pitch_errors_um" in contact:
        raise InputError("contact.pitch_errors_um offsets the tooth pairs of one mesh cycle; "
                         "beside [contact.errors] give each tooth's own deviation "
                         "(single_pitch_pinion_um, single_pitch_gear_um) instead")
    for who in ("pinion", "gear"):
        phase = f"eccentricity_phase_{who}_deg"
        if phase in table and not values.get(f"eccentricity_{who}"):
            raise InputError(f"{WHERE}.{phase} = "
                             f"{format_value(table[phase], unit_of_key(phase))} changes "
                             f"nothing without {WHERE}.eccentricity_{who}_um > 0")
    with restated(WHERE, T.ERRORS, table):
        gears = {who: GearErrors(values.get(f"single_pitch_{who}", ()),
                                 values.get(f"eccentricity_{who}", 0.0),
                                 values.get(f"eccentricity_phase_{who}", 0.0), name=who)
                 for who in ("pinion", "gear")}
        errors = ToothErrors(gears["pinion"], gears["gear"], values.get("span", "hunting"))
        errors.check_pair(pair)
    revolution_size(errors, pair, positions)
    return errors
