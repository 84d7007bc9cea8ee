"""Mesh settings of a gear sector or whole gear: one type for 2D, its 3D extension.

:class:`SectorSettings` describes the mesh of the transverse section (``teeth``
consecutive teeth, or ``teeth = z`` for the whole gear): element sizes on the loaded
teeth, the other teeth and the body, the grading distance, the profile polyline and the
inner radius. :mod:`pipeline.fem.sector2d` meshes it in 2D. :class:`SectorSettings3D`
adds what the swept solid needs (loft sections along the helix, the herringbone half)
and is meshed by :mod:`pipeline.fem.sector3d`. The fields and their checks are written
once; the scaled settings differ between 2D and 3D (a 3D P2 model at the 2D flank size
m_n / 12 would have millions of unknowns), so each type has its own factories.

Nothing here imports scikit-fem or Gmsh: the size estimators
(:mod:`pipeline.fem.sector2d_size`, :mod:`pipeline.fem.sector3d_size`), the outline
(:mod:`pipeline.fem.outline2d`) and the grading fields read the settings without the
mesh builders. Lengths in m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from pipeline.fem.settings import GRADED_BODY, GRADED_GROWTH, GRADED_TOOTH
from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError, check_int_range, check_range

# Whole-gear 3D element sizes in normal modules (over sqrt(refinement)), and the grading
# distance in body sizes (SectorSettings3D.whole_gear; measured in pipeline.fem.whole3d).
WHOLE_TOOTH, WHOLE_BODY, WHOLE_GRADING = 2.0, 8.0, 1.5
WHOLE_THIN = 2.0  # largest cell of a whole gear in face widths
WHOLE_NEAR = 1.5  # read, unloaded neighbours of a loaded tooth, in flank sizes
WHOLE_REACH = 2.0  # teeth kept beyond the loaded and near ones: this many rim depths along the
# root circle (SectorSettings3D.whole_gear; measured in pipeline.fem.whole3d)


@dataclass(frozen=True)
class SectorSettings:
    """Mesh settings of a sector (or, ``teeth = z``, a whole gear); meshed in 2D.

    Attributes
    ----------
    teeth : consecutive teeth in the sector (>= 1, < z/2, or z for the whole gear).
    size_flank : element size on the outline of the loaded teeth, m.
    size_body : largest element size (rim, body far from the outline), m.
    grading : distance from the outline at which the size reaches ``size_body``, m (it is
        ``size_flank`` up to ``size_flank / 2`` away, then grows linearly; the same growth
        rate holds from the outline of the other teeth).
    profile_points : involute points of the profile polyline (the fillet gets as many).
    inner_radius : bore (hub) radius of the mesh, m; None uses
        :func:`pipeline.fem.outline2d.inner_radius`.
    loaded : sector teeth meshed at ``size_flank`` (whole outline: both flanks and
        fillets), or None for all teeth.
    size_tooth : element size on the outline of the other teeth, m (``size_flank`` ..
        ``size_body``; None: ``size_flank``); from there the size grows at the same rate.
    """

    teeth: int = 3
    size_flank: float = 1e-4
    size_body: float = 1e-3
    grading: float = 3e-3
    profile_points: int = 60
    inner_radius: float | None = None
    loaded: tuple[int, ...] | None = None
    size_tooth: float | None = None

    def __post_init__(self) -> None:
        check_int_range("sector.teeth", self.teeth, 1, 1000)
        check_range("sector.size_flank", self.size_flank, 1e-7, 1.0, unit="m")
        check_range("sector.size_body", self.size_body, self.size_flank, 10.0, unit="m")
        check_range("sector.grading", self.grading, 0.0, 10.0, unit="m")
        check_int_range("sector.profile_points", self.profile_points, 8, 10000)
        if self.loaded is not None:
            loaded = tuple(sorted({int(k) for k in self.loaded}))
            if not loaded:
                raise InputError("sector.loaded: give at least one tooth, or None for all")
            for k in loaded:
                check_int_range("sector.loaded", k, 0, self.teeth - 1)
            object.__setattr__(self, "loaded", loaded)
        if self.size_tooth is not None:
            check_range("sector.size_tooth", self.size_tooth, self.size_flank, self.size_body,
                        unit="m")

    @classmethod
    def for_gear(cls, gear: GearSpec, teeth: int = 3, refinement: float = 1.0
                 ) -> SectorSettings:
        """2D settings scaled by the module: flank size m_n / (12 refinement), body
        m_n / 2.5 (every tooth at the flank size)."""
        check_range("sector.refinement", refinement, 0.05, 100.0)
        m = gear.module
        return cls(teeth=teeth, size_flank=m / (12.0 * refinement),
                   size_body=max(m / 2.5 / math.sqrt(refinement), m / (12.0 * refinement)),
                   grading=1.2 * m, profile_points=max(60, int(40 * refinement)))

    @classmethod
    def graded(cls, gear: GearSpec, teeth: int, loaded: tuple[int, ...],
               refinement: float = 1.0, *, tooth: float = GRADED_TOOTH,
               body: float = GRADED_BODY, growth: float = GRADED_GROWTH) -> SectorSettings:
        """2D settings graded from the ``loaded`` teeth: flank size m_n / (12 refinement)
        on their outline, ``tooth`` m_n on the other teeth, growing at ``growth`` (m of size
        per m of distance) up to ``body`` m_n (:mod:`pipeline.fem.sector2d`, "Graded
        meshes")."""
        check_range("sector.refinement", refinement, 0.05, 100.0)
        check_range("sector.tooth", tooth, 0.01, 10.0, unit="m_n")
        check_range("sector.body", body, tooth, 100.0, unit="m_n")
        check_range("sector.growth", growth, 0.01, 2.0)
        m = gear.module
        h = m / (12.0 * refinement)
        return cls(teeth=teeth, size_flank=h, size_body=max(body * m, h),
                   grading=0.5 * h + max(body * m - h, 0.0) / growth,
                   profile_points=max(60, int(40 * refinement)), loaded=tuple(loaded),
                   size_tooth=min(max(tooth * m, h), max(body * m, h)))


@dataclass(frozen=True)
class SectorSettings3D(SectorSettings):
    """Mesh settings of a 3D sector or whole gear: the section's settings, swept.

    Attributes
    ----------
    (those of :class:`SectorSettings`, on the tooth sides: flank, fillet, tip land), and
    loft_sections : transverse sections the helical solid is lofted through (>= 2;
        a spur sector needs 2).
    half : herringbone gears only: 0 the first helical half (the gear's hand), 1 the
        second (opposite hand); each is ``face_width / 2`` wide.
    near : teeth (not loaded) whose sides are meshed at ``size_near``: whole-gear
        neighbours of a loaded tooth that are read but not loaded.
    size_near : element size on the sides of the ``near`` teeth, m (``size_flank`` ..
        ``size_body``; None: ``size_flank``).
    reach : whole gears only: the teeth more than ``reach`` teeth from every loaded or
        near tooth are left out (the rim ends at the root circle there,
        :mod:`pipeline.fem.whole3d`); None keeps every tooth.
    """

    size_flank: float = 1e-3
    size_body: float = 3e-3
    profile_points: int = 40
    loft_sections: int = 7
    half: int = 0
    near: tuple[int, ...] = ()
    size_near: float | None = None
    reach: int | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        check_int_range("sector.loft_sections", self.loft_sections, 2, 100)
        check_int_range("sector.half", self.half, 0, 1)
        near = tuple(sorted({int(k) for k in self.near}))
        for k in near:
            check_int_range("sector.near", k, 0, self.teeth - 1)
            if self.loaded is None or k in self.loaded:
                raise InputError(f"sector.near: tooth {k} is loaded (near teeth are the "
                                 "other read teeth)")
        object.__setattr__(self, "near", near)
        if self.size_near is not None:
            check_range("sector.size_near", self.size_near, self.size_flank, self.size_body,
                        unit="m")
        if self.reach is not None:
            check_int_range("sector.reach", self.reach, 1, 1000)

    @classmethod
    def for_gear(cls, gear: GearSpec, teeth: int = 3, refinement: float = 1.0, half: int = 0
                 ) -> SectorSettings3D:
        """Settings scaled by the module: tooth sides m_n / (3 refinement), body m_n.

        Coarser than 2D (m_n / 12): a 3D P2 model at that size would have millions
        of DOFs. z 50, m_n 3 mm, 3 teeth x 20 mm: 56k DOF at refinement 1, 114k at
        1.5. The 3D load patches of :mod:`pipeline.fem.influence` need refinement >= 2
        for their near field to be resolved (see there).
        """
        check_range("sector.refinement", refinement, 0.05, 20.0)
        m = gear.module
        sf = m / (3.0 * refinement)
        beta = gear.helix_angle
        # ~8 sections per angular pitch of twist: the loft then strays ~3e-7 rad from the
        # exact helix (measured at the tip land, z 30, beta 15 deg)
        turn = (math.tan(beta) * meshed_width(gear) / gear.reference_radius * gear.teeth
                / (2 * math.pi))
        return cls(teeth=teeth, size_flank=sf, size_body=max(m / math.sqrt(refinement), sf),
                   grading=1.5 * m, profile_points=max(30, int(30 * refinement)),
                   loft_sections=2 if beta == 0 else max(5, int(math.ceil(8 * turn)) + 1),
                   half=half)

    @classmethod
    def whole_gear(cls, gear: GearSpec, loaded, refinement: float = 1.0, half: int = 0,
                   near=()) -> SectorSettings3D:
        """Whole-gear settings (``teeth = z``) graded from the ``loaded`` teeth.

        The loaded teeth's sides get the sector's flank size ``m_n / (3 refinement)``;
        the other teeth ``WHOLE_TOOTH m_n / sqrt(refinement)``; the body grows to
        ``WHOLE_BODY m_n / sqrt(refinement)`` over ``WHOLE_GRADING`` times that distance
        (a growth rate Gmsh meshes with well-shaped cells). The teeth farther than
        ``WHOLE_REACH`` rim depths from the loaded ones along the root circle are left
        out (``reach``, :func:`whole_reach`). The ``near`` teeth (read, not loaded)
        get ``WHOLE_NEAR`` flank sizes. See :mod:`pipeline.fem.whole3d` for the
        measured DOF counts and their effect on the tables.
        """
        s = cls.for_gear(gear, 1, refinement, half)
        m, root = gear.module, math.sqrt(refinement)
        # a thin gear (face < 1.5 body sizes) keeps its cells <= 2 face widths: flat
        # cells spanning the face would be poorly shaped
        body = max(min(WHOLE_BODY * m / root, WHOLE_THIN * meshed_width(gear)), s.size_flank)
        near = tuple(near)
        return replace(s, teeth=gear.teeth, loaded=tuple(loaded), near=near,
                       size_near=min(WHOLE_NEAR * s.size_flank, body) if near else None,
                       size_tooth=min(max(WHOLE_TOOTH * m / root, s.size_flank), body),
                       size_body=body, grading=WHOLE_GRADING * body,
                       reach=whole_reach(gear, s))


def whole_reach(gear: GearSpec, settings: SectorSettings) -> int | None:
    """Teeth a whole gear keeps on each side of its loaded teeth (``reach``): those within
    :data:`WHOLE_REACH` rim depths (root radius minus inner radius) along the root circle,
    at least 2; None (every tooth) when that is more than half the gear."""
    from pipeline.fem.outline2d import inner_radius

    depth = gear.root_radius - inner_radius(gear, settings)
    pitch = 2 * math.pi * gear.root_radius / gear.teeth
    reach = max(2, math.ceil(WHOLE_REACH * depth / pitch))
    return None if 2 * reach >= gear.teeth else reach


def far_teeth(settings: SectorSettings3D, z: int) -> set[int]:
    """The teeth a whole gear of ``z`` teeth leaves out: more than ``settings.reach``
    teeth (counted round the gear) from every loaded or near tooth; none if ``reach`` or
    ``loaded`` is None."""
    if settings.reach is None or settings.loaded is None:
        return set()
    kept = (*settings.loaded, *settings.near)
    return {k for k in range(z)
            if min(min(abs(k - j), z - abs(k - j)) for j in kept) > settings.reach}


def meshed_width(gear: GearSpec) -> float:
    """Meshed face width, m: ``face_width``, half of it for a herringbone half."""
    return gear.face_width / 2 if gear.herringbone else gear.face_width
