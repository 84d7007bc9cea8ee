"""Case of a planetary set's per-gear flank modifications
(``workflows/configs/planetary_modifications.toml``): each mesh is the pair of its two
gears.

The sun-planet mesh is the pair sun + planet and the planet-ring mesh the internal pair
planet + ring, each gear with its own ``[<gear>.modifications]`` table, at the set's centre
distance and loaded like the mesh (its pinion's torque and speed relative to the carrier):
the same contact options and every array of the loaded cycle equal bit for bit, on rigid
supports, through the run's static stages (:func:`pipeline.run.chain.mesh_stages`). The
gap at the ends of each path of contact is the sum of both flanks' amounts as defined
(ISO 21771:2007, 7.3: tip relief C_a reached at the active tip, the ring's smaller
diameter).
"""

from __future__ import annotations

import copy
import dataclasses
import tomllib
import warnings

import numpy as np

from pipeline.validation import PhysicsWarning
from pipeline.verification.context import Context
from pipeline.verification.display import UM
from pipeline.verification.model import Outcome, Quantity

EXAMPLE = "configs/planetary_modifications.toml"
"""The set's gearbox file, under a source checkout's ``workflows/``."""
GEARS = ("sun", "planet", "ring")
MESHES = {"sun_planet": ("sun", "planet"), "planet_ring": ("planet", "ring")}
END_GAPS = {"sun_planet": ((17e-6, 16e-6), (22e-6, 21e-6)),
            "planet_ring": ((12e-6, 17e-6), (16e-6, 21e-6))}
"""Gap at the start and the end of each path, at mid-face and at face 1 (m): sun-planet
start = the planet's tip relief 15 um + its profile crowning 2 um, end = the sun's 14 um +
the planet's 2 um; planet-ring start = the ring's 10 um + 2 um, end = the planet's 15 + 2
um; at face 1 the sun's lead crowning adds 5 um, the ring's end relief 4 um."""


def _example(context: Context) -> dict:
    path = context.reference_dir.parent / EXAMPLE
    if not path.is_file():
        raise FileNotFoundError(f"{path} is missing (it is in a source checkout's workflows/)")
    return tomllib.loads(path.read_text(encoding="utf-8"))


def mesh_pair_doc(doc: dict, mesh: str) -> dict:
    """The two gears of ``mesh`` ("sun_planet" or "planet_ring") of the planetary gearbox
    file ``doc`` (a parsed TOML) as a pair file: the first as [pinion], the second as
    [gear], each with its own [<gear>.modifications] table; the set's other tables as
    they are, its carrier and planetary tables left out. The equivalent pair the mesh is
    checked against (module docstring)."""
    pinion, gear = MESHES[mesh]
    out = {k: copy.deepcopy(v) for k, v in doc.items()
           if k not in GEARS + ("carrier", "planetary")}
    out["pinion"], out["gear"] = copy.deepcopy(doc[pinion]), copy.deepcopy(doc[gear])
    out["name"] = f"{doc['name']}_{mesh}"
    return out


def _stages(box, options) -> dict:
    """The run's static stages of ``box``, quietly: the set's thin rims and tip-corner
    contact warn alike for the mesh and its pair, and the comparison is between them."""
    from pipeline.progress import Steps
    from pipeline.run.chain import mesh_stages

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PhysicsWarning)
        return mesh_stages(box, options, Steps("", enabled=False))


def _differences(a, b) -> tuple[int, float]:
    """How many arrays of two loaded cycles are not equal bit for bit (NaN equal to NaN),
    and the largest |difference| of the transmission errors (m)."""
    from pipeline.contact.cycle_io import cycle_arrays

    x, y = cycle_arrays(a), cycle_arrays(b)
    if x.keys() != y.keys():
        return max(len(x), len(y)), float("nan")
    unequal = sum(not np.array_equal(x[k], y[k], equal_nan=x[k].dtype.kind in "fc")
                  for k in x)
    te = np.abs(np.asarray(a.transmission_error) - np.asarray(b.transmission_error)).max()
    return int(unequal), float(te)


def case_planetary_meshes_are_their_pairs(context: Context) -> Outcome:
    """Each mesh of a planetary set with per-gear modifications against the pair of its two
    gears: contact options and loaded cycle bit for bit; the gaps at the path ends."""
    from pipeline.cache.folder import Cache
    from pipeline.config.gearbox import gearbox_from_dict
    from pipeline.contact.modifications import modification_gap
    from pipeline.geometry.pair import GearPair
    from pipeline.run.chain import RunOptions

    doc = _example(context)
    # no cache: a pair whose tables share the mesh's cache key would read the mesh's own
    # cycle back, and the comparison would echo it
    options = RunOptions(show_progress=False, cache=Cache.off())
    box = gearbox_from_dict(doc)
    stages = _stages(box, options)
    plain = copy.deepcopy(doc)
    for g in GEARS:
        plain[g].pop("modifications")
    bare = _stages(gearbox_from_dict(plain), options)
    bit = "bit for bit: the same computation"
    q = []
    for mesh in MESHES:
        pair_box = gearbox_from_dict(mesh_pair_doc(doc, mesh))
        pair = GearPair(pair_box.gears["pinion"], pair_box.gears["gear"],
                        box.planetary.carrier_radius)
        pair_box = dataclasses.replace(pair_box, pair=pair,
                                       operation=stages[mesh].case.operation)
        alone = _stages(pair_box, options)["mesh"]
        unequal, te = _differences(stages[mesh].contact, alone.contact)
        same_options = pair_box.mesh_contact("mesh") == box.mesh_contact(mesh)
        change = abs(np.ptp(stages[mesh].contact.transmission_error)
                     - np.ptp(bare[mesh].contact.transmission_error))
        q += [Quantity(f"{mesh}: contact options unequal to the pair's (1 if so)", "-", 0.0,
                       0.0 if same_options else 1.0, "absolute", 0.0, bit),
              Quantity(f"{mesh}: arrays of the loaded cycle unequal to the pair's", "-", 0.0,
                       unequal, "absolute", 0.0, bit),
              Quantity(f"{mesh}: largest |TE - the pair's TE|", "m", 0.0, te, "absolute",
                       0.0, bit, UM),
              Quantity(f"{mesh}: TE peak-to-peak change by the modifications", "m", 1e-6,
                       change, "lower_bound", 0.0, "the modifications act: more than 1 um "
                                                   "(as the tests ask)", UM)]
    for mesh, pair in box.contact_meshes():
        flanks = box.mesh_contact(mesh).modifications.flanks
        ends = np.array([pair.s_start, pair.s_end])
        for where, z, values in zip(("mid-face", "face 1"), (0.5 * pair.face_width, 0.0),
                                    END_GAPS[mesh], strict=True):
            gap = modification_gap(pair, ends, np.full(2, z), flanks)
            q += [Quantity(f"{mesh}: gap at the path's {end}, {where}", "m", want, float(g),
                           "absolute", 1e-15, "round-off (the tests' 1e-15 m)", UM)
                  for end, want, g in zip(("start", "end"), values, gap, strict=True)]
    inputs = (("set", f"workflows/{EXAMPLE}: sun, planet, ring (internal), rigid supports"),
              ("sun", "tip relief 14 um from d 122 mm (parabolic), lead crowning 5 um"),
              ("planet", "tip relief 15 um over 4 mm (linear), profile crowning 2 um"),
              ("ring", "tip relief 10 um from d 237 mm (linear), end reliefs 4 um on both "
                       "faces"),
              ("pairs", "sun + planet and planet + ring at the carrier radius, loaded like "
                        "each mesh (torque and speed relative to the carrier)"))
    return Outcome("Exact: a planetary mesh is the pair of its two gears (the same "
                   "computation); the gaps are the modifications' amounts as defined "
                   "(ISO 21771:2007, 7.3)", inputs, tuple(q))
