"""One gearbox file -> :class:`Gearbox`: every stage's frozen inputs, in SI.

A gearbox file describes its gears, the meshes between them, the operating
point and optional tables per stage. Which gear tables it has says what it is:

* a **pair**: ``[pinion]`` and ``[gear]`` (``gear`` may be internal), with an optional
  ``[pair]`` (centre distance, assembly errors); one mesh;
* a **planetary set**: ``[sun]``, ``[planet]``, ``[ring]`` (internal), ``[carrier]``
  and ``[planetary]`` (number of planets, optional planet angles); the sun-planet and
  planet-ring meshes follow from the set, with the assembly checks of
  :class:`~pipeline.geometry.planetary.PlanetarySet`;
* a **single gear**: ``[gear]`` alone (FE of one gear, the relief groove);
* a **lumped model** from a publication that gives masses and stiffnesses but no
  tooth geometry: ``[lumped_model]`` (:mod:`pipeline.config.lumped`).

Each gear may hold its flank modifications, ``[<gear>.modifications]``
(:mod:`pipeline.config.modifications`); ``[contact]``'s tip relief, crowning and slope keys
are their short form, given per mesh as (pinion, gear). In a planetary set the sun-planet
mesh takes the sun's and the planet's tables, the planet-ring mesh the planet's and the
ring's: :meth:`Gearbox.mesh_contact` gives the contact options of each mesh, and every stage
reads them from it.

Stage tables: ``[operation]``, ``[stiffness]``, ``[contact]``, ``[fe]``,
``[groove]``, ``[dynamics]`` (with ``[dynamics.response]``, ``[dynamics.sweep]``
and an optional ``[dynamics.mesh_stiffness]``). Keys carry their unit in their
name; see :mod:`pipeline.config.tables` for every key. What follows from the
geometry is derived, never typed: base radii, operating pressure angles,
contact ratios and mesh period (:class:`GearPair`), masses and inertias of the
gear bodies (:class:`GearBody`; override with ``mass_kg``, ``inertia_kgm2`` in
the gear's table), planet positions and meshing phases (:class:`PlanetarySet`;
override the positions with ``planet_angles_deg``), the mesh stiffness of the
dynamics (override with ``[dynamics.mesh_stiffness]``).

Unknown tables and keys, wrong types and out-of-range values are refused with
one line naming the key as written, the value in the file's unit and the
allowed range in that unit. So is a key that would change nothing: one the chosen
method, model or source never reads (``n_harmonics`` of a Floquet response, bearings of a
torsional pair, ``slice_coupling`` of an FE compliance, ...), or one another table
overrides (a ``[dynamics]`` groove stiffness beside the ``[groove]`` FE the dynamics use).
Pitch errors for tooth pairs that never mesh in the analysed mesh cycle are kept and
named in one :class:`~pipeline.validation.InputWarning` line per mesh.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pipeline.config import tables as T
from pipeline.config.modifications import TABLE as MODIFICATIONS_TABLE
from pipeline.config.modifications import gear_modifications
from pipeline.config.rating import rating_options
from pipeline.config.schema import (
    MAX_NAME_CHARS,
    MAX_TEXT_CHARS,
    Scope,
    build,
    check_text,
    read_table,
    restated,
    unknown,
)
from pipeline.config.shafts import pin_layout, shaft_layout
from pipeline.config.signals import signal_from_table
from pipeline.config.toml_file import InputFile, parse_input, read_input_file
from pipeline.config.tooth_errors import tooth_errors
from pipeline.config.units import format_value, unit_of_key
from pipeline.contact.herringbone import SUN_LOAD_SIDE, HerringboneOptions
from pipeline.contact.modifications import GearModification, flank_frames
from pipeline.contact.options import ContactOptions
from pipeline.contact.separations import (
    FlankModifications,
    meshing_pairs,
    reach_in_pitches,
)
from pipeline.contact.tooth_errors import ToothErrors
from pipeline.dynamics.options import (
    PairDynamicsOptions,
    PlanetaryDynamicsOptions,
    ResponseOptions,
    SweepOptions,
)
from pipeline.fem.groove.spec import GrooveSpec
from pipeline.fem.settings import FE2DSettings, FE3DSettings
from pipeline.geometry.assembly_errors import AssembledPair, AssemblyErrors, assemble
from pipeline.geometry.body import GearBody
from pipeline.geometry.gear import GearSpec, Material
from pipeline.geometry.pair import GearPair
from pipeline.geometry.planetary import PlanetarySet
from pipeline.geometry.profile import tooth_profile
from pipeline.operation import OperatingPoint
from pipeline.rating.options import RatingOptions
from pipeline.shaft.layout import ShaftLayout
from pipeline.stiffness.options import StiffnessOptions
from pipeline.validation import InputError, InputWarning, check_range

if TYPE_CHECKING:
    from pipeline.dynamics.assembly import DynamicModel

PAIR_ROLES = ("pinion", "gear")
PLANETARY_ROLES = ("sun", "planet", "ring")
MESH_GEARS = {"mesh": PAIR_ROLES, "sun_planet": ("sun", "planet"),
              "planet_ring": ("planet", "ring")}
"""The gear tables of each mesh, (pinion, gear) of its :class:`GearPair`."""
EXTERNAL_ROLES = ("pinion", "sun", "planet")
"""Gear tables that describe external gears only."""
STAGE_TABLES = ("operation", "stiffness", "contact", "fe", "groove", "herringbone",
                "dynamics", "rating")
TABLES = PAIR_ROLES + PLANETARY_ROLES + ("carrier", "pair", "planetary", "lumped_model") \
    + STAGE_TABLES
TOP_KEYS = ("name", "description")


@dataclass(frozen=True)
class Carrier:
    """The planet carrier as a rigid body: mass (kg) and polar moment (kg m^2)."""

    mass: float
    inertia: float

    def __post_init__(self) -> None:
        check_range("carrier.mass", self.mass, 0.0, 1e7, lo_open=True, unit="kg")
        check_range("carrier.inertia", self.inertia, 0.0, 1e7, lo_open=True, unit="kg m^2")


@dataclass(frozen=True)
class Gearbox:
    """A gearbox as described by one file: the frozen inputs of every stage (SI).

    Attributes
    ----------
    name : label (the ``name`` key, else the file stem); outputs go by the file stem.
    kind : "pair", "planetary", "gear" (one gear) or "lumped".
    gears : the gears by their table name ("pinion", "gear", "sun", "planet", "ring").
    bodies : the gears as rigid bodies (mass properties derived or overridden), same keys.
    pair : the nominal pair (kind "pair"), or ``None``.
    assembly_errors : centre displacements of the pair (zero without ``[pair]`` errors).
    planetary : the planetary set (kind "planetary"), or ``None``.
    carrier : the carrier body (kind "planetary"), or ``None``.
    operation : load and speed of the driving gear.
    stiffness, contact : options of those stages (defaults when the table is absent).
    fe : the FE model of the gears (``[fe]``): ``FE3DSettings`` when ``[contact]
        compliance = "fe3d"``, else ``FE2DSettings`` (the ``"fe2d"`` source's and
        ``gearpipe fe``'s model); its ``slices`` are the contact's.
    groove : relief-groove analysis of a herringbone gear (``[groove]``), or ``None``.
    herringbone : how a herringbone sun's halves are loaded and held in the sun-planet
        contact through its groove (``[herringbone]``, planetary sets with a ``[groove]``).
    dynamics : options of the pair's or the planetary set's dynamic model (``[dynamics]``),
        or ``None``.
    lumped : a lumped dynamic model given directly (``[lumped_model]``), or ``None``.
    rating : the ISO 6336 rating's inputs (``[rating]``), or ``None`` (no rating).
    shafts : the gears' shafts by role (``[<gear>.shaft]``): (model, layout); a planet's
        is its pin.
    planet_bearing_stiffness : radial stiffness of the bearing between a planet and its pin
        (``[planet.shaft]``), N/m; ``inf``: rigid.
    pinion_rotation : "clockwise" or "counterclockwise", the pinion's sense of rotation seen
        from the end its shafts' positions grow towards (``[operation] pinion_rotation``;
        with the driver it picks the flanks that load the shafts).
    errors : per-tooth errors of a pair's gears (``[contact.errors]``,
        :mod:`pipeline.config.tooth_errors`), or ``None``.
    gear_modifications : a planetary set's flank modifications by gear table ("sun",
        "planet", "ring"; the ``[<gear>.modifications]`` given), which :meth:`mesh_contact`
        puts on each mesh; empty for a pair, whose ``contact`` holds its gears' already.
    source : the file it was read from (text, hash) or ``None`` when built in Python.
    tables : names of the tables the file gave (which stages it asks for).
    """

    name: str
    kind: str
    gears: Mapping[str, GearSpec]
    bodies: Mapping[str, GearBody]
    pair: GearPair | None = None
    assembly_errors: AssemblyErrors = field(default_factory=AssemblyErrors)
    planetary: PlanetarySet | None = None
    carrier: Carrier | None = None
    operation: OperatingPoint = field(default_factory=OperatingPoint)
    stiffness: StiffnessOptions = field(default_factory=StiffnessOptions)
    contact: ContactOptions = field(default_factory=ContactOptions)
    fe: FE2DSettings | FE3DSettings = field(default_factory=FE2DSettings)
    groove: GrooveSpec | None = None
    herringbone: HerringboneOptions = field(default_factory=HerringboneOptions)
    dynamics: PairDynamicsOptions | PlanetaryDynamicsOptions | None = None
    lumped: DynamicModel | None = None
    rating: RatingOptions | None = None
    shafts: Mapping[str, tuple[str, ShaftLayout]] = field(default_factory=dict)
    planet_bearing_stiffness: float = math.inf
    pinion_rotation: str = "clockwise"
    errors: ToothErrors | None = None
    gear_modifications: Mapping[str, GearModification] = field(default_factory=dict)
    source: InputFile | None = field(default=None, compare=False, repr=False)
    tables: tuple[str, ...] = ()

    @property
    def fe_source(self) -> FE2DSettings | FE3DSettings | None:
        """``fe`` when ``[contact] compliance`` is an FE source (``"fe2d"``, ``"fe3d"``),
        else None: what the loaded contact's tables and cache keys depend on."""
        return None if self.contact.compliance == "analytical" else self.fe

    @property
    def pinion(self) -> GearSpec:
        """The pinion of a pair."""
        return self.require_pair().pinion

    @property
    def gear(self) -> GearSpec:
        """The gear of a pair, or the single gear of a one-gear file."""
        if "gear" not in self.gears:
            raise InputError(f"{self.name}: the file has no [gear] table")
        return self.gears["gear"]

    @property
    def actual_pair(self) -> GearPair:
        """The pair as installed: at the centre distance the assembly errors give."""
        return self.require_pair() if self.assembled is None else self.assembled.actual

    @cached_property
    def assembled(self) -> AssembledPair | None:
        """The assembly-error geometry, or ``None`` without errors."""
        return assemble(self.require_pair(), self.assembly_errors)

    @property
    def fe_groove_in_dynamics(self) -> bool:
        """True when the dynamic model joins the herringbone sun's halves by the 3D FE of the
        ``[groove]`` table: a planetary set with a herringbone sun, a ``[groove]`` table and
        ``[dynamics] excitation = "contact"`` without an explicit ``sun_mesh_stiffness``
        (the sun meshes are then excited left/right from the contact through that groove,
        :mod:`pipeline.run.dynamics`); ``[dynamics]`` groove keys are refused then."""
        d = self.dynamics
        return (self.kind == "planetary" and self.planetary.sun.herringbone
                and self.groove is not None and isinstance(d, PlanetaryDynamicsOptions)
                and d.excitation == "contact" and d.sun_mesh_stiffness is None)

    def contact_meshes(self) -> tuple[tuple[str, GearPair], ...]:
        """The meshes the contact stage analyses, by name ("mesh"; "sun_planet",
        "planet_ring"), as installed; a herringbone pair stands for its helical halves, which
        share its transverse geometry. Empty for a single gear or a lumped model."""
        if self.kind == "pair":
            return (("mesh", self.actual_pair),)
        if self.kind == "planetary":
            ps = self.planetary
            return (("sun_planet", ps.sun_planet), ("planet_ring", ps.planet_ring))
        return ()

    @staticmethod
    def mesh_gears(mesh: str) -> tuple[str, str]:
        """The gear tables of mesh ``mesh``, (pinion, gear): ("pinion", "gear"), ("sun",
        "planet") or ("planet", "ring")."""
        return MESH_GEARS[mesh]

    def mesh_contact(self, mesh: str) -> ContactOptions:
        """The contact options of mesh ``mesh`` (a name of :meth:`contact_meshes`): ``contact``
        with the modifications of the mesh's two gears as its pinion's and gear's flanks.

        A pair's is ``contact`` itself. In a planetary set the sun-planet mesh's pinion flank
        is the sun's ``[sun.modifications]`` and its gear flank the planet's; the planet-ring
        mesh's pinion flank is the planet's (the same table: a planet is modified alike on
        both flanks, the one that meshes with the sun and the one that meshes with the ring)
        and its gear flank the ring's. Without per-gear tables both meshes take ``contact``
        (its short form, if any, applies to each mesh as (pinion, gear)).
        """
        if mesh not in MESH_GEARS or (mesh == "mesh") != (self.kind == "pair"):
            raise InputError(f"{self.name}: no mesh {mesh!r} in a {_KIND_TEXT[self.kind]} "
                             f"(its meshes: {', '.join(n for n, _ in self.contact_meshes())})")
        if not self.gear_modifications:
            return self.contact
        flanks = [self.gear_modifications.get(role) for role in MESH_GEARS[mesh]]
        mods = dataclasses.replace(self.contact.modifications, pinion_flank=flanks[0],
                                   gear_flank=flanks[1])
        return dataclasses.replace(self.contact, modifications=mods)

    def require_pair(self) -> GearPair:
        """The pair; a clear error when the file describes something else."""
        if self.pair is None:
            raise InputError(f"{self.name}: this needs a gear pair ([pinion] and [gear] tables); "
                             f"the file describes a {_KIND_TEXT[self.kind]}")
        return self.pair

    def to_dict(self) -> dict[str, Any]:
        """The parsed document (what determines the numbers), for records and hashes."""
        return {} if self.source is None else dict(self.source.document)


_KIND_TEXT = {"pair": "gear pair", "planetary": "planetary set", "gear": "single gear",
              "lumped": "lumped dynamic model"}


def _material(table: Any, where: str) -> Material:
    return build(Material, table, T.MATERIAL, where)


def _gear(doc: Mapping[str, Any], role: str) -> tuple[GearSpec, GearBody]:
    table = doc[role]
    if not isinstance(table, Mapping):
        raise InputError(f"{role} = {table!r}: expected a table [{role}]")
    keys = T.GEAR + T.BODY
    values = read_table(table, keys, role, subtables=("material", "shaft",
                                                      MODIFICATIONS_TABLE))
    body_fields = {k.target for k in T.BODY}
    body = {k: values.pop(k) for k in list(values) if k in body_fields}
    internal = values.get("internal", False)
    if internal and role in EXTERNAL_ROLES:
        raise InputError(f"{role}.internal = true: the {role} of a "
                         f"{'gear pair' if role == 'pinion' else 'planetary set'} is an "
                         "external gear; leave internal out (only [gear] of a pair and [ring] "
                         "can be internal)")
    for name, ok in (("rim_outer_radius_mm", internal), ("bore_radius_mm", not internal)):
        if name in table and not ok:
            right = "rim_outer_radius_mm" if internal else "bore_radius_mm"
            what = ("an internal gear's outer rim radius" if internal
                    else "an external gear's bore radius")
            raise InputError(f"{role}.{name} = {format_value(table[name], unit_of_key(name))}: "
                             f"[{role}] is {'an internal' if internal else 'an external'} gear;"
                             f" give {what} as {right} instead")
    if internal and "rim_outer_radius_mm" not in table:
        raise InputError(f"[{role}] is an internal gear and needs the key 'rim_outer_radius_mm' "
                         "(outer radius of the ring's rim)")
    values.setdefault("name", role)
    if values.get("helix_angle", 0.0) > 0 and "hand" not in values:
        values["hand"] = "right"
    if "material" in table:
        values["material"] = _material(table["material"], f"{role}.material")
    if body.get("mass") is not None and body.get("inertia") is not None:
        for name in ("web_width_mm", "rim_inner_radius_mm", "hub_radius_mm"):
            # the web shapes the derived mass and inertia, and a rating's C_R and K_v
            if name in table and "rating" not in doc:
                raise InputError(f"{role}.{name} = {format_value(table[name], unit_of_key(name))}"
                                 f" changes nothing: [{role}] gives both mass_kg and "
                                 "inertia_kgm2, and without [rating] those are the only "
                                 "quantities the web shapes")
        material = table.get("material", {})
        if isinstance(material, Mapping) and "density_kg_m3" in material:
            # warned, not refused: a material is stated whole, though here only its
            # elastic constants act
            rho = format_value(material["density_kg_m3"], unit_of_key("density_kg_m3"))
            warnings.warn(f"{role}.material.density_kg_m3 = {rho} changes nothing: [{role}] "
                          "gives both mass_kg and inertia_kgm2, the only quantities the density "
                          "sets", InputWarning, stacklevel=3)
    with restated(role, keys, table, also=_gear_scopes({role: table}, {role: values["name"]})):
        gear = GearSpec(**values)
        tooth_profile(gear)  # a flank the rack cuts away entirely is refused now (about 1 ms)
        return gear, GearBody(gear, **body)


def _gear_scopes(tables: Mapping[str, Any], names: Mapping[str, str]) -> dict[str, Scope]:
    """The gear tables by the prefixes the geometry's messages use: each gear's role and
    its ``name`` (``gear.module``, ``Sun gear.teeth``)."""
    out = {}
    for role, table in tables.items():
        scope = Scope(role, T.GEAR + T.BODY, table if isinstance(table, Mapping) else ())
        out[names.get(role, role)] = scope
        out[role] = scope
    return out


def _check_tables(doc: Mapping[str, Any]) -> None:
    if "model" in doc or "parameters" in doc:
        raise InputError(
            "this is a dynamics file of the old format (top-level 'model' and [parameters]): "
            "describe the gears instead ([pinion] and [gear], or [sun], [planet], [ring], "
            "[carrier], [planetary]) and put the model options in [dynamics], as in "
            "workflows/configs/spur_pair_assembly_errors.toml; a published lumped model without "
            "gear geometry goes into a [lumped_model] table (workflows/configs/"
            "lin_parker_planetary.toml)")
    for k, v in doc.items():
        if isinstance(v, Mapping):
            if k not in TABLES:
                raise unknown(k, TABLES, "table")
        elif k not in TOP_KEYS:
            if k in TABLES:
                raise InputError(f"{k} = {v!r}: expected a table [{k}]")
            raise unknown(k, TOP_KEYS + TABLES, "top-level key")
        elif not isinstance(v, str):
            raise InputError(f"{k} = {v!r}: expected a string in quotes")
        else:
            check_text(k, v, MAX_TEXT_CHARS if k == "description" else MAX_NAME_CHARS)


def _kind(doc: Mapping[str, Any]) -> str:
    has = {r for r in PAIR_ROLES + PLANETARY_ROLES + ("carrier", "planetary", "lumped_model")
           if r in doc}
    if "lumped_model" in has:
        if has - {"lumped_model"}:
            raise InputError("[lumped_model] describes a model without gear tables; remove "
                             f"{', '.join(f'[{t}]' for t in sorted(has - {'lumped_model'}))}")
        return "lumped"
    planetary = has & set(PLANETARY_ROLES + ("carrier", "planetary"))
    if planetary:
        missing = [t for t in PLANETARY_ROLES + ("carrier", "planetary") if t not in doc]
        if missing or "pinion" in doc or "gear" in doc:
            raise InputError("a planetary set needs [sun], [planet], [ring], [carrier] and "
                             "[planetary] (and no [pinion] or [gear]); missing: "
                             f"{', '.join(f'[{t}]' for t in missing) or 'none'}")
        return "planetary"
    if "pinion" in doc:
        if "gear" not in doc:
            raise InputError("a gear pair needs a [gear] table beside [pinion]")
        return "pair"
    if "gear" in doc:
        return "gear"
    raise InputError("the file describes no gears: give [pinion] and [gear] (a pair), "
                     "[sun], [planet], [ring], [carrier] and [planetary] (a planetary set), "
                     "[gear] (one gear) or [lumped_model]")


def _only_with(table: Mapping[str, Any], where: str, keys: tuple[str, ...], choice: str,
               allowed: tuple[str, ...], actual: Any) -> None:
    """Refuse ``keys`` of ``table`` that act only when ``choice`` is one of ``allowed``."""
    if actual in allowed:
        return
    for k in keys:
        if k in table:
            shown = " or ".join(f'"{a}"' for a in allowed)
            now = f'"{actual}"' if isinstance(actual, str) else f"{actual:g}"
            raise InputError(f"{where}.{k} = {format_value(table[k], unit_of_key(k))} applies "
                             f"to {choice} = {shown} only; this table's {choice} is {now}"
                             + ("" if choice in table else " (the default)"))


def _stiffness(doc: Mapping[str, Any]) -> StiffnessOptions:
    """``[stiffness]``; the roughness and viscosity act only in the EHL friction model."""
    table = doc.get("stiffness", {})
    opts = build(StiffnessOptions, table, T.STIFFNESS, "stiffness")
    _only_with(table, "stiffness", ("roughness_um", "viscosity_mPas"), "friction", ("ehl",),
               opts.friction)
    return opts


def _operation(doc: Mapping[str, Any]) -> tuple[OperatingPoint, str]:
    """``[operation]``: the operating point and the pinion's sense of rotation (which flanks
    its shafts load, :mod:`pipeline.shaft.misalignment`)."""
    table = doc.get("operation", {})
    values = read_table(table, T.OPERATION, "operation")
    rotation = values.pop("pinion_rotation", "clockwise")
    with restated("operation", T.OPERATION, table):
        return OperatingPoint(**values), rotation


def contact_options_from_table(table: Mapping[str, Any] | None) -> ContactOptions:
    """:class:`ContactOptions` from a parsed ``[contact]`` table (or ``None``: defaults)."""
    table = {} if table is None else table
    keys = T.CONTACT + T.MODIFICATIONS
    values = read_table(table, keys, "contact", subtables=("errors",))
    mod_fields = {k.target for k in T.MODIFICATIONS}
    mods = {k: values.pop(k) for k in list(values) if k in mod_fields}
    with restated("contact", keys, table):
        opts = ContactOptions(modifications=FlankModifications(**mods), **values)
    # the FE sources have their own coupling across the face; the slice coupling would only
    # shape the analytical slices, which they use for the friction change on the diagonal
    _only_with(table, "contact", ("slice_coupling",), "compliance", ("analytical",),
               opts.compliance)
    return opts


def _with_gear_modifications(contact: ContactOptions, doc: Mapping[str, Any], kind: str,
                             roles: tuple[str, ...], base: Path | None
                             ) -> tuple[ContactOptions, dict[str, GearModification]]:
    """``contact`` with a pair's ``[pinion.modifications]`` and ``[gear.modifications]`` as
    its flanks; a planetary set's ``[<gear>.modifications]`` by gear table instead (put on
    each mesh by :meth:`Gearbox.mesh_contact`), ``contact`` unchanged."""
    given = [r for r in roles if isinstance(doc[r], Mapping) and MODIFICATIONS_TABLE in doc[r]]
    if not given:
        return contact, {}
    if kind not in ("pair", "planetary"):
        raise InputError(f"[{given[0]}.{MODIFICATIONS_TABLE}] is read for gears in mesh (a "
                         "pair or a planetary set); this file describes a "
                         f"{_KIND_TEXT[kind]}")
    flanks = {r: gear_modifications(doc, r, base) for r in given}
    if kind == "planetary":
        return contact, flanks
    mods = dataclasses.replace(contact.modifications,
                               **{f"{r}_flank": flanks.get(r) for r in PAIR_ROLES})
    with restated("contact", T.CONTACT + T.MODIFICATIONS, doc.get("contact", {})):
        return dataclasses.replace(contact, modifications=mods), {}


def _fe(doc: Mapping[str, Any], contact: ContactOptions) -> FE2DSettings | FE3DSettings:
    """``[fe]`` -> the FE model of the gears: ``FE3DSettings`` for ``[contact] compliance
    = "fe3d"``, else ``FE2DSettings``, each key setting the field of its name.

    A key the model does not have (:data:`~pipeline.config.tables.FE_MODEL_KEYS`) is
    refused rather than ignored, naming the compliance it applies to.
    """
    table = doc.get("fe", {})
    values = read_table(table, T.FE, "fe")
    accepted = T.FE_MODEL_KEYS[contact.compliance]
    written = {key.field or key.name: key.name for key in T.FE}
    for k in values:
        if k not in accepted:
            used = [c for c, keys in T.FE_MODEL_KEYS.items() if k in keys]
            raise InputError(f"fe.{written.get(k, k)} applies to [contact] compliance = "
                             f"{' or '.join(repr(c) for c in used)} only; this file's contact "
                             f"compliance is {contact.compliance!r}")
    three_d = contact.compliance == "fe3d"
    if three_d and "teeth" in values:
        values["body"] = "sector"  # a tooth count in 3D asks for a sector, not the whole gear
    with restated("fe", T.FE, table):
        fe = (FE3DSettings if three_d else FE2DSettings)(**values)
    return dataclasses.replace(fe, slices=contact.slices)


def _groove(doc: Mapping[str, Any], gears: Mapping[str, GearSpec],
            planetary: PlanetarySet | None, operation: OperatingPoint) -> GrooveSpec | None:
    """``[groove]``. In a planetary set it is the sun's groove, the one the sun-planet contact
    and the dynamic model join the sun's halves through, so ``gear`` can only be the sun
    (the groove of another gear: a single-gear file); ``planets`` (the tooth-force coupling's)
    defaults to ``[planetary] planets`` and must equal it, ``torque_Nm`` (the twist reported
    by ``gearpipe groove``) likewise to ``[operation] torque_Nm``, the sun's. ``planets``
    sets only the ``"tooth_forces"`` coupling and is refused with another coupling."""
    if "groove" not in doc:
        return None
    table = doc["groove"]
    values = read_table(table, T.GROOVE, "groove")
    role = values.pop("gear_role", None)
    if role is None:
        role = next((r for r, g in gears.items() if g.herringbone), "sun" if "sun" in gears
                    else "gear")
    if role not in gears:
        raise InputError(f'groove.gear = "{role}" is not one of '
                         f"{', '.join(map(repr, gears))} (the gear tables of this file)")
    if planetary is not None and role != "sun":
        raise InputError(f"groove.gear = \"{role}\": a planetary set's [groove] is the sun's "
                         "(its halves are joined through it in the contact and the dynamics); "
                         f"analyse the {role}'s groove from a file with that gear alone")
    coupling = values.get("coupling", "distributed")
    _only_with(table, "groove", ("planets",), "coupling", ("tooth_forces",), coupling)
    if planetary is not None:  # [operation] holds the sun's torque, the one the run applies
        torque = values.setdefault("sun_torque", operation.torque)
        if not math.isclose(torque, operation.torque, rel_tol=1e-9):
            raise InputError(f"groove.torque_Nm = {torque:.6g} N m contradicts operation."
                             f"torque_Nm = {operation.torque:.6g} N m, the sun's torque of this "
                             "planetary set: leave groove.torque_Nm out (it follows [operation])")
    if planetary is not None and coupling == "tooth_forces":
        n = values.setdefault("planets", planetary.n_planets)
        if n != planetary.n_planets:
            raise InputError(f"groove.planets = {n} contradicts planetary.planets = "
                             f"{planetary.n_planets}: leave groove.planets out (it follows "
                             "the set)")
    scopes = _gear_scopes({role: doc[role]}, {role: gears[role].name})
    with restated("groove", T.GROOVE, table, also=scopes):
        return GrooveSpec(gear=gears[role], **values)


def _herringbone(doc: Mapping[str, Any], kind: str, gears: Mapping[str, GearSpec]
                 ) -> HerringboneOptions:
    if "herringbone" not in doc:
        return HerringboneOptions()
    if kind != "planetary" or not gears["sun"].herringbone or "groove" not in doc:
        raise InputError("[herringbone] applies to a planetary set with a herringbone sun and "
                         "its [groove] table (the sun-planet contact through the groove)")
    table = doc["herringbone"]
    if isinstance(table, Mapping) and table.get("sun_axial") == "free":
        # a free sun finds its own axial position on no support
        _only_with(table, "herringbone", ("axial_slide_mm", "axial_support_stiffness_N_per_m"),
                   "sun_axial", ("held",), "free")
    return build(HerringboneOptions, table, T.HERRINGBONE, "herringbone")


_METHOD_KEYS = {"n_harmonics": ("harmonic_balance",), "segments": ("floquet", "time"),
                "periods": ("time",)}
"""Keys of ``[dynamics.response]`` / ``[dynamics.sweep]`` -> the methods that read them."""


def _solver_options(factory, table: Any, keys, where: str):
    """A response or sweep table; a key its ``method`` does not read is refused."""
    opts = build(factory, table, keys, where)
    for key, methods in _METHOD_KEYS.items():
        _only_with(table, where, (key,), "method", methods, opts.method)
    return opts


def _dynamics_keys_act(table: Mapping[str, Any], opts: Any, herringbone: bool) -> None:
    """Refuse ``[dynamics]`` keys the chosen model would not read.

    A pair's bearings with ``dofs = "torsional"`` (no lateral motion to support); the
    ``excitation`` when explicit mesh stiffness tables replace every mesh excitation (a
    pair's also needs ``friction = false``: otherwise the excitation gives the friction
    terms); a planetary set's herringbone keys when its gears are not herringbone (refused
    here, before the static stages run, rather than when the model is built).
    """
    if isinstance(opts, PairDynamicsOptions):
        _only_with(table, "dynamics", ("bearing_stiffness_N_per_m", "bearing_damping_Ns_per_m"),
                   "dofs", ("lateral_torsional",), opts.dofs)
        replaced = "mesh_stiffness" in table and not opts.friction
        why = "[dynamics.mesh_stiffness] replaces the mesh excitation and friction = false"
    else:
        replaced = "sun_mesh_stiffness" in table and "ring_mesh_stiffness" in table
        why = ("[dynamics.sun_mesh_stiffness] and [dynamics.ring_mesh_stiffness] replace both "
               "mesh excitations")
        if not herringbone:
            given = {k.target: k.name for k in T.DYNAMICS_PLANETARY}
            for name in opts.herringbone_keys:
                key = given[name]
                value = table[key]
                shown = (f'"{value}"' if isinstance(value, str)
                         else format_value(value, unit_of_key(key)))
                raise InputError(f"dynamics.{key} = {shown} applies to a herringbone set; this "
                                 "planetary set has no herringbone gears")
    if replaced and "excitation" in table:
        raise InputError(f'dynamics.excitation = "{opts.excitation}" does nothing: {why}; '
                         "leave it out")


def _dynamics(doc: Mapping[str, Any], base: Path | None, kind: str, herringbone: bool = False
              ) -> PairDynamicsOptions | PlanetaryDynamicsOptions | None:
    """``[dynamics]``: a pair's options, or a planetary set's (its own keys); keys the model
    would not read are refused (:func:`_dynamics_keys_act`)."""
    if "dynamics" not in doc:
        return None
    table = doc["dynamics"]
    planetary = kind == "planetary"
    keys = T.DYNAMICS_PLANETARY if planetary else T.DYNAMICS
    subtables = T.DYNAMICS_PLANETARY_SUBTABLES if planetary else T.DYNAMICS_SUBTABLES
    values = read_table(table, keys, "dynamics", subtables=subtables)
    values["response"] = _solver_options(ResponseOptions, table.get("response", {}),
                                         T.RESPONSE, "dynamics.response")
    values["sweep"] = _solver_options(SweepOptions, table.get("sweep", {}), T.SWEEP,
                                      "dynamics.sweep")
    for name in subtables:
        if name.endswith("mesh_stiffness") and name in table:
            values[name] = signal_from_table(table[name], f"dynamics.{name}", base)
    with restated("dynamics", keys, table):
        opts = (PlanetaryDynamicsOptions if planetary else PairDynamicsOptions)(**values)
    _dynamics_keys_act(table, opts, herringbone)
    return opts


def _shafts(doc: Mapping[str, Any], gears: Mapping[str, GearSpec]
            ) -> tuple[dict[str, tuple[str, ShaftLayout]], float]:
    """``[<gear>.shaft]`` of each gear that has one (:mod:`pipeline.config.shafts`) and the
    radial stiffness of a planet's bearing on its pin (N/m, ``inf`` rigid); a ring has none
    (it is the housing's); a planet's is its pin (:func:`~pipeline.config.shafts.pin_layout`).
    The shafts of a planetary set are built for spur gears only
    (:mod:`pipeline.run.planetary_shafts`)."""
    out: dict[str, tuple[str, ShaftLayout]] = {}
    k_planet = math.inf
    for role, gear in gears.items():
        table = doc[role].get("shaft") if isinstance(doc[role], Mapping) else None
        if table is None:
            continue
        if gear.internal:
            raise InputError(f"[{role}.shaft]: an internal gear is held by the housing, not a "
                             "shaft")
        if role in ("sun", "planet") and (gear.herringbone or gear.is_helical):
            kind = "herringbone" if gear.herringbone else "helical"
            raise InputError(f"[{role}.shaft]: shafts and pins of a {kind} planetary set are "
                             "not built (its axial forces on the sun and the pins); they take "
                             "spur sets")
        if role == "planet":
            model, layout, k_planet = pin_layout(table, gear, "planet.shaft")
            out[role] = (model, layout)
        else:
            out[role] = shaft_layout(table, gear, f"{role}.shaft")
    return out, k_planet


def gearbox_from_dict(doc: Mapping[str, Any], name: str = "gearbox",
                      base: Path | None = None, source: InputFile | None = None) -> Gearbox:
    """Build a :class:`Gearbox` from a parsed TOML document.

    Parameters
    ----------
    doc : the parsed file.
    name : label when the file has no ``name`` key.
    base : folder that relative paths in the file are relative to.
    source : the file it was read from (kept for run records).
    """
    _check_tables(doc)
    kind = _kind(doc)
    roles = {"pair": PAIR_ROLES, "planetary": PLANETARY_ROLES, "gear": ("gear",),
             "lumped": ()}[kind]
    gears, bodies = {}, {}
    for role in roles:
        gears[role], bodies[role] = _gear(doc, role)
    kw: dict[str, Any] = {}
    gear_scopes = _gear_scopes({r: doc[r] for r in roles}, {r: g.name for r, g in gears.items()})
    if kind == "pair":
        values = read_table(doc.get("pair", {}), T.PAIR, "pair")
        cd = values.pop("centre_distance", None)
        with restated("pair", T.PAIR, doc.get("pair", {}), also=gear_scopes):
            kw["assembly_errors"] = AssemblyErrors(**values)
            kw["pair"] = GearPair(gears["pinion"], gears["gear"], cd)
    elif "pair" in doc:
        raise InputError(f"[pair] belongs to a gear pair; this file describes a "
                         f"{_KIND_TEXT[kind]}")
    if kind == "planetary":
        kw["carrier"] = build(Carrier, doc["carrier"], T.CARRIER, "carrier")
        values = read_table(doc["planetary"], T.PLANETARY, "planetary")
        with restated("planetary", T.PLANETARY, doc["planetary"], also=gear_scopes):
            kw["planetary"] = PlanetarySet(gears["sun"], gears["planet"], gears["ring"],
                                           **values)
    if kind == "lumped":
        from pipeline.config.lumped import lumped_model

        for t in ("operation", "stiffness", "contact", "fe", "groove"):
            if t in doc:
                raise InputError(f"[{t}] needs gear geometry; a [lumped_model] file has none "
                                 "(its load, speed and stiffness are keys of [lumped_model])")
        extra = [k for k in doc.get("dynamics", {}) if k not in ("response", "sweep")]
        if extra:
            raise InputError(f"dynamics.{extra[0]}: a [lumped_model] file takes only "
                             "[dynamics.response] and [dynamics.sweep]; the model's own keys "
                             "go into [lumped_model]")
        kw["lumped"] = lumped_model(doc["lumped_model"], base)
    contact, gear_mods = _with_gear_modifications(
        contact_options_from_table(doc.get("contact")), doc, kind, roles, base)
    shafts, k_planet = _shafts(doc, gears)
    fe = _fe(doc, contact)
    operation, rotation = _operation(doc)
    box = Gearbox(
        name=str(doc.get("name", name)),
        kind=kind,
        gears=gears,
        bodies=bodies,
        operation=operation,
        stiffness=_stiffness(doc),
        contact=contact,
        fe=fe,
        groove=_groove(doc, gears, kw.get("planetary"), operation),
        herringbone=_herringbone(doc, kind, gears),
        dynamics=_dynamics(doc, base, kind,
                           kind == "planetary" and gears["sun"].herringbone),
        rating=rating_options(doc, kind, roles,
                              frozenset(r for r, g in gears.items() if g.internal)),
        shafts=shafts,
        planet_bearing_stiffness=k_planet,
        pinion_rotation=rotation,
        errors=tooth_errors(doc, kind, kw.get("pair"), contact.positions),
        gear_modifications=gear_mods,
        source=source,
        tables=tuple(k for k in doc if isinstance(doc[k], Mapping)),
        **kw,
    )
    if kind == "pair":
        with restated("pair", T.PAIR, doc.get("pair", {}), also=gear_scopes):
            box.actual_pair  # noqa: B018 - the displaced pair must still mesh (cached)
    if (box.kind == "pair" and set(box.shafts) == {"pinion", "gear"}
            and "bearing_stiffness_N_per_m" in doc.get("dynamics", {})):
        raise InputError("dynamics.bearing_stiffness_N_per_m changes nothing: both gears sit "
                         "on shafts ([pinion.shaft], [gear.shaft]), whose bearings and "
                         "bending give the dynamic model's supports")
    if box.kind == "planetary":
        for role in ("sun", "planet"):
            key = f"{role}_bearing_stiffness_N_per_m"
            if role in box.shafts and key in doc.get("dynamics", {}):
                what = ("the sun sits on [sun.shaft], whose bearings and bending" if
                        role == "sun" else "the planets sit on pins ([planet.shaft]), whose "
                        "supports, bending and planet bearing")
                raise InputError(f"dynamics.{key} changes nothing: {what} give the dynamic "
                                 f"model's {role} support")
    if "pinion_rotation" in doc.get("operation", {}) and not (box.kind == "pair"
                                                              and box.shafts):
        raise InputError(f'operation.pinion_rotation = "{rotation}" sets which flanks load '
                         "a pair's shafts; this file has no [pinion.shaft] or [gear.shaft]")
    drives = ((("drive_inertia_kgm2", "pinion", "motor"),
               ("load_inertia_kgm2", "gear", "driven machine")) if box.kind == "pair"
              else (("drive_inertia_kgm2", "sun", "motor"),))
    for key, role, what in drives:
        if key in doc.get("dynamics", {}) and role not in box.shafts:
            raise InputError(f"dynamics.{key} needs [{role}.shaft]: the {what} is tied to the "
                             f"{role} by its shaft's torsion")
    _check_groove_sources(box, doc)
    _check_relief_lengths(box, doc)
    _check_fe3d_meshes(box, doc)
    _check_pitch_errors(box)
    return box


def _check_fe3d_meshes(box: Gearbox, doc: Mapping[str, Any]) -> None:
    """The 3D compliance source's limits on the meshes it would model, before any meshing
    (:meth:`~pipeline.contact.fe3d_source.FE3DCompliance.check_pair`); a herringbone mesh
    is modelled by its helical halves, checked when they are built."""
    if box.contact.compliance != "fe3d":
        return
    from pipeline.contact.fe3d_source import FE3DCompliance

    meshes = box.contact_meshes()
    contact = {"contact": Scope("contact", T.CONTACT, doc.get("contact", {}))}
    with restated("fe", T.FE, doc.get("fe", {}), also=contact):
        for name, pair in meshes:
            if not (pair.pinion.herringbone or pair.gear.herringbone):
                FE3DCompliance.check_pair(pair, box.fe, name if len(meshes) > 1 else "")


def _check_relief_lengths(box: Gearbox, doc: Mapping[str, Any]) -> None:
    """Each tip relief length at most the path of contact of every analysed mesh (the
    shortest one's, named when there are several); each gear's per-gear modifications inside
    its active flank and face width in every mesh it takes part in, in the words of its own
    table (a planet's in both of its meshes)."""
    meshes = box.contact_meshes()
    if not meshes:
        return
    for mesh, pair in meshes:
        mods = box.mesh_contact(mesh).modifications
        if mods.has_short_form:
            continue
        for role, given, flank, frame in zip(
                MESH_GEARS[mesh], (mods.pinion_flank, mods.gear_flank), mods.flanks,
                flank_frames(pair), strict=True):
            if given is None:
                continue
            table = doc[role].get(MODIFICATIONS_TABLE, {})
            with restated(f"{role}.{MODIFICATIONS_TABLE}", T.GEAR_MODIFICATIONS, table):
                flank.check_fits(dataclasses.replace(frame, role=role),
                                 mesh if len(meshes) > 1 else "")
    name, pair = min(meshes, key=lambda m: m[1].path_length)
    with restated("contact", T.CONTACT + T.MODIFICATIONS, doc.get("contact", {})):
        box.contact.modifications.check_fits(pair, name if len(meshes) > 1 else "")


PITCH_ERRORS_KEY = "pitch_errors_um"
GROOVE_DYNAMICS_KEYS = ("groove_torsional_stiffness_Nm_per_rad",
                        "groove_lateral_stiffness_N_per_m")
"""``[dynamics]`` keys of a herringbone sun's groove that the ``[groove]`` FE replaces."""


def _list_text(values: tuple[float, ...], key: str) -> str:
    """SI values of a list key in the file's unit, as written: ``[0, 4, 2, ...] um``."""
    u = unit_of_key(key)
    shown = ", ".join(f"{u.from_si(v):.6g}" for v in values[:6])
    return f"[{shown}{', ...' if len(values) > 6 else ''}]" + (f" {u.label}" if u.label else "")


def _check_pitch_errors(box: Gearbox) -> None:
    """``[contact] pitch_errors_um`` against the meshes it applies to.

    Entry k offsets tooth pair k of the analysed mesh cycle (:mod:`pipeline.contact.
    separations`). A list longer than the tooth count of the mesh's smaller gear cannot be
    tooth pairs of one mesh (pairs k and k + z share a tooth of that gear): refused. Entries
    of pairs that never reach the path of contact during the cycle (k >= epsilon_alpha,
    :func:`~pipeline.contact.separations.meshing_pairs`) are kept but change nothing: one
    warning per mesh names them. They are not refused, because a list of the right length
    for one mesh of a planetary set may be too long only for the other, and making them act
    would need an analysis over more than one mesh cycle.
    """
    errors = box.contact.modifications.pitch_errors
    key = f"contact.{PITCH_ERRORS_KEY}"
    meshes = box.contact_meshes()
    for name, pair in meshes:
        fewer = min((pair.pinion, pair.gear), key=lambda g: g.teeth)
        if len(errors) > fewer.teeth:
            where = f" of the {name} mesh" if len(meshes) > 1 else ""
            raise InputError(
                f"{key} = {_list_text(errors, PITCH_ERRORS_KEY)} has {len(errors)} entries, "
                f"more than the {fewer.teeth} teeth of the {fewer.name}{where}: entry k offsets "
                f"tooth pair k of the mesh cycle, and pairs k and k + {fewer.teeth} would share "
                f"a tooth (allowed: at most {fewer.teeth} entries)")
    tip = box.contact.tip_contact
    for name, pair in meshes:
        n = meshing_pairs(pair, tip)
        if len(errors) > n:
            pairs = "tooth pair k = 0 meshes" if n == 1 else f"tooth pairs k = 0 to {n - 1} mesh"
            where = f" of the {name} mesh" if len(meshes) > 1 else ""
            reach = (f"pair k touches when k < {reach_in_pitches(pair):.4g}, the path of "
                     "contact and the tip zone past its end in base pitches" if tip else
                     f"pair k meshes when k < transverse contact ratio "
                     f"{pair.transverse_contact_ratio:.4g}")
            warnings.warn(
                f"{key}[{n}:] = {_list_text(errors[n:], PITCH_ERRORS_KEY)} change nothing: "
                f"only {pairs} in the analysed mesh cycle{where} ({reach})",
                InputWarning, stacklevel=3)


def _check_groove_sources(box: Gearbox, doc: Mapping[str, Any]) -> None:
    """One groove per herringbone sun in the dynamics.

    When the model takes the ``[groove]`` table's FE (:attr:`Gearbox.fe_groove_in_dynamics`),
    a typed ``[dynamics]`` groove stiffness is refused, not overridden nor preferred: the
    left/right sun-mesh excitations come from the contact through the FE groove and carry
    its static twist in their transmission errors, so a different groove spring in the same
    model would contradict them. The sun's load side follows ``[herringbone] torque_entry``
    (where that contact took the torque out); a ``sun_load_side`` that says otherwise is
    refused, the same side is accepted.
    """
    if not box.fe_groove_in_dynamics:
        return
    table = doc["dynamics"]
    for name in GROOVE_DYNAMICS_KEYS:
        if name in table:
            raise InputError(
                f"dynamics.{name} = {format_value(table[name], unit_of_key(name))} contradicts "
                "the [groove] table: with excitation = \"contact\" the sun's halves are joined "
                "by the groove's 3D FE stiffness (the left/right sun-mesh excitations carry its "
                "static twist); remove this key, or the [groove] table to use it")
    entry = box.herringbone.torque_entry
    side = SUN_LOAD_SIDE[entry]
    if "sun_load_side" in table and box.dynamics.sun_load_side != side:
        given = "" if "torque_entry" in doc.get("herringbone", {}) else " (the default)"
        raise InputError(
            f"dynamics.sun_load_side = \"{box.dynamics.sun_load_side}\" contradicts "
            f"herringbone.torque_entry = \"{entry}\"{given}: with the [groove] table and "
            "excitation = \"contact\" the sun is loaded where the contact through the groove "
            f"takes its torque out (sun_load_side = \"{side}\"); give the same side in both "
            "or leave sun_load_side out")


def load_gearbox(path: str | Path) -> Gearbox:
    """Read a gearbox file (relative paths inside are relative to it)."""
    f = read_input_file(path)
    return gearbox_from_dict(f.document, name=f.path.stem, base=f.path.parent, source=f)


def gearbox_from_text(text: str, name: str = "gearbox") -> Gearbox:
    """Build a :class:`Gearbox` from TOML text (tests, notebooks)."""
    src = parse_input(text.encode("utf-8"), name)
    return gearbox_from_dict(src.document, name=name, source=src)


__all__ = ["Carrier", "Gearbox", "contact_options_from_table", "gearbox_from_dict",
           "gearbox_from_text", "load_gearbox"]
