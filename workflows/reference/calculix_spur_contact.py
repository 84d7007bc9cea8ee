"""Independent FE contact reference for a spur pair: CalculiX, plane strain, surface contact.

A reference model that is *not* part of the product: it checks gearpipe's loaded tooth
contact (``[contact] compliance = "fe2d"``) against a finite-element contact analysis that
shares nothing with it but the tooth profile and the boundary conditions.

Model
-----
* **Geometry.** Both whole gears in their transverse plane, outlines from the exact tooth
  profile (:func:`pipeline.geometry.profile.tooth_profile`: involute, trochoidal fillet,
  root and tip circles, a sharp tip corner), placed at the pair's operating centre distance
  (zero backlash for the demo pair). Pinion centre at the origin, gear centre at
  ``(0, a_w)`` (the frame of :class:`pipeline.geometry.TransverseLayout`).
* **Mesh** (its own, through the project's Gmsh fence :func:`pipeline.fem.gmsh_session`):
  6-node triangles, element size ``size_contact`` on the contact-side flank and tip land of
  the ``fine`` teeth of each gear (five per gear: every tooth that can touch at any
  position, with a pitch to spare), ``size_fine`` on the rest of their outline,
  ``size_tooth`` on the other teeth, growing by ``growth`` (m per m of distance) into the
  body up to ``size_body``. Whole gears: every tooth of both gears and the whole rim down
  to the bore are in the model, so nothing depends on where a sector is cut.
* **Elements.** CalculiX CPE6 (plane strain, quadratic; expanded internally into one layer
  of C3D15 wedges with the out-of-plane displacement tied), thickness = the face width b,
  so reaction forces are those of the whole face width. Linear elastic, E and nu of the
  gears' materials, small displacements (no NLGEOM: the rotations are ~3e-4 rad).
* **Contact.** Surface-to-surface penalty contact, frictionless, linear pressure-overclosure
  with slope ``penalty`` (Pa/m), one contact pair per tooth pair (the teeth of one pair
  touch only each other). Surfaces: the driven flank (root middle over fillet and involute
  to the tip corner) and the tip land of each tooth. So every flank that can touch does,
  including each tip corner against the mate's flank or fillet beyond the nominal path of
  contact. Slave surface (``slave = "corner"``): the tooth whose tip corner touches beyond
  the path (the pinion's past its end), else the gear's: a sharp corner on the master side
  is under-resolved (the slave integration points of the smooth flank straddle it), which
  made the stiffness 3 % low where the pinion's corner carries load (position 19 at
  100 N m: 276.8 against 285.2 N/um with the corner as slave; the first committed run,
  gear always slave, is kept as ``runs["full_slave_gear"]``). The coast flanks (which
  touch too at zero backlash, unloaded) are left out: the driving rotation opens them.
  The control run (``contact="nominal"``) gives contact surfaces only to the tooth pairs
  whose nominal roll ``s0 + k p_b`` lies on the path of contact ``[s_start, s_end]``
  (whole flanks): a pair beyond either end cannot touch, as in gearpipe's loaded contact
  with ``[contact] tip_contact = false``.
* **Boundary conditions** (as the project's 2D FE source, ``pipeline.fem.sector2d``: the
  bore circle clamped): the gear's bore nodes fixed; the pinion's bore nodes prescribed to
  the rigid rotation ``u = theta (y, -x)`` (clockwise, driving) about the pinion centre.
  This is a rigid hub coupled kinematically to the centre, whose rotation theta is the
  reference degree of freedom under displacement control; the driving torque is minus the
  moment of the bore reactions about the centre. The pinion turns clockwise, its right
  flanks (in its own frame, tooth on +y) drive the gear's right flanks.
* **Load steps.** Four static steps per position: rotations ``(1 -+ step)`` times an
  estimate of the loaded TE at each torque (gearpipe's, scaled by the ratio found at the
  previous position), so each torque is bracketed by two load levels 4 % apart.
* **Outputs per position and torque T.** Loaded transmission error ``TE = r_b1 theta(T)``
  (m along the line of action; the unloaded rotation is 0: the gears are placed in rigid
  flank contact), linear in the two bracketing steps. Mesh stiffness ``k = dP/dTE``,
  ``P = T / r_b1``: the secant of those two steps. Tooth pair loads: the contact forces on
  each gear tooth, ``-K u`` summed over its contact-side nodes (``K`` of the same mesh,
  :class:`InternalForces`; every other free node carries no load), as their moment about
  the gear centre over r_b2, an equivalent load along the line of action (they add up to P
  within 0.1 %: ``load_split_closure``). Where a pair touches: the radius range of its
  loaded gear nodes; a loaded pair whose nominal roll ``s0 + k p_b`` lies outside
  ``[s_start, s_end]`` touches beyond the path, at a tip corner (``pair_beyond_path``).

Mesh positions are gearpipe's: the roll coordinate ``s0`` of the leading tooth pair
(:meth:`pipeline.geometry.GearPair.mesh_cycle`), and tooth pair ``k`` is at ``s0 + k p_b``.

Convergence (demo pair, ``size_contact`` 0.2 / 0.1 / 0.05 mm, the rest of the mesh fixed;
``convergence_rows``). Positions 9, 18, 21 of 24 (gear always slave: double contact near
the pitch point, the last double-contact position with the leaving pair 0.04 mm before the
end of the path, and single contact with the leaving pair's tip corner just closing at
340 N m):

====  ======  ==========================  ==========================  ================
pos.  torque  TE (um) 0.2 / 0.1 / 0.05 mm   k (N/um) 0.2 / 0.1 / 0.05   0.1 -> 0.05 mm
====  ======  ==========================  ==========================  ================
9     100     4.795 / 4.829 / 4.835       297.1 / 299.7 / 299.3       +0.12 %, -0.13 %
9     340     15.997 / 16.017 / 16.022    307.2 / 307.4 / 307.4       +0.03 %, -0.01 %
18    100     4.955 / 4.995 / 4.999       286.4 / 288.8 / 288.8       +0.07 %, 0.00 %
18    340     16.522 / 16.532 / 16.539    297.9 / 296.6 / 296.6       +0.04 %, +0.02 %
21    100     6.432 / 6.441 / 6.441       228.4 / 227.6 / 227.2       0.00 %, -0.16 %
21    340     20.719 / 20.773 / 20.773    267.0 / 264.2 / 273.7       0.00 %, see below
====  ======  ==========================  ==========================  ================

The change from 0.2 to 0.1 mm is 4-10 times the change from 0.1 to 0.05 mm in TE (the
contact zone, 0.14 mm wide at 100 N m, is resolved from 0.1 mm on), so the committed 0.1 mm
mesh is within about 0.15 % of the converged TE and stiffness wherever the stiffness is a
derivative and no corner carries load. Where a tip corner is just closing (position 21 at
340 N m) T(theta) has a kink and the secant stiffness over the 4 % load interval depends on
where the interval falls: 262-274 N/um over the runs, whose intervals differ. At the same
four rotations (``convergence_same_steps``) the 0.2 / 0.05 mm meshes give torques +0.14 to
+0.23 % / -0.06 to +0.01 % off the 0.1 mm one (TE within 0.01 % at 0.05 mm), and the secant
stiffness there -1.2 / +1.0 % at 340 N m, +0.36 / -0.14 % at 100 N m.

Where a tip corner carries about a third of the load (positions 19 and 23, the corner tooth
as slave) the corner's local deformation converges more slowly (a sharp corner's local
approach grows without bound as the contact narrows; the mesh blunts it at its element
size): 0.2 / 0.1 / 0.05 mm give TE -1.0 / 0 / +0.48 % (100 N m) and -0.5 / 0 / +0.10 %
(340 N m) of the 0.1 mm value, stiffness +0.6 / 0 / -0.4 to -0.6 % (100 N m) and -0.2 to
-0.7 / 0 / -0.2 to -0.4 % (340 N m). gearpipe's corner model (Hertz of a 0.05 m_n = 0.15 mm
corner radius, :mod:`pipeline.geometry.tip_contact`) lies within 0.5 % of the 0.1 and the
0.05 mm meshes there. The rest of the mesh (positions 9 and 21, both torques):
``size_fine`` 0.25 mm and growth 0.3 (24k instead of 16.6k nodes per gear) change TE by
+0.06 to +0.08 % and k by -0.05 to -0.23 %; a finer far field (``size_tooth`` 0.75 mm,
``size_body`` 2.5 mm, growth 0.3: 38k nodes per gear) TE by +0.06 to +0.08 % and k by
-0.04 to -0.22 %. Penalty 4e17 instead of 1e17 Pa/m (the overclosure, 5-8 nm at 340 N m, is
0.04 % of the TE): TE -0.02 % at both torques, k +0.12 % (100 N m) and -0.66 % (340 N m,
the closing corner; position 21). The committed data use 0.1 mm and 1e17 Pa/m.

Against gearpipe's FE-enriched loaded contact (``compare``, :func:`gearpipe_at_reference`:
24 positions, frictionless, Weber local contact, the stiffness as the secant over the
reference's own two load steps; the numbers are gearpipe / CalculiX - 1). With tip contact
(the default) against every flank: TE within 1.23 % at every position and both torques
(the largest at the start of the path, position 0, 100 N m; within 0.25 % in double contact
away from the transitions and within 0.2 % where a corner carries 20-33 % of the load),
stiffness within 1.46 % except at position 21 at 340 N m, -2.3 %, where the leaving pair's
corner closes between the two load steps (it carries 70 N of 4820 N in the reference, 60 N
in gearpipe) and the secant straddles the kink: at the reference's own rotations
(:func:`gearpipe_torques_at_rotations`) gearpipe's torques lie within 0.2 % of the
reference's at every step of positions 19-23, -0.03 and +0.09 % at the two steps around
position 21's 340 N m, a 0.12 % difference the 4.6 % step turns into the 2.3 % of the
secant. A load sweep there (``sweep``: 11 rotations over +-10 % of the loaded TE, on the
committed 0.1 mm and on a 0.05 mm mesh, ``reference["load_sweeps"]``,
:func:`sweep_comparison`) resolves it: two corners close inside the committed interval
(the pinion's, pair 1, and the gear's, pair -1), in the same 2 % step intervals in both
models; torques within -0.08 to +0.22 % at every rotation; the secant over every interval
without a closure (the tangent stiffness on each side of them) within 0.8 %; each corner
closes 0.10 to 0.15 um of rotation (0.5 to 0.7 % of the TE) later in gearpipe (the finer
reference mesh closes 0.01 / 0.03 um earlier; gearpipe's closure moves by less than 0.02
um with its own mesh, grid and patch), so a secant over an interval holding a closure is
up to 4.8 % low. At a closing contact the tangent stiffness has two values; the model
agrees with each. Over the cycle at 340 N m: mean stiffness
302.8 against 302.5 N/um, minimum 291.3 against 291.7, fluctuation (max - min) / mean 5.5
against 5.2 %, TE peak to peak 4.886 against 4.865 um; at 100 N m 287.8 against 286.6 N/um
and 1.603 against 1.613 um. A tip corner touches beyond the path at 7 of the 48 position
and load cases, carrying 1.5-33 % of the load. Contact confined to the path
(``tip_contact = false``) against the control run: TE within 1.3 %, stiffness within
1.5 % at the ends of the path, 0.3 % in single contact; over the cycle at 340 N m 291.2
against 290.3 N/um, fluctuation 24.5 % in both, TE peak to peak 5.07 against 5.10 um. The
corner model's radius moves gearpipe's TE where a corner carries load (positions 19, 20,
22, 23, both torques) to at most +0.58 / +0.28 / 0.16 / 0.16 / -0.82 % of the reference's
for 0.05 / 0.1 / 0.15 (the default) / 0.2 / 1 mm.

Tips rounded by design (``run --tip-rounding 0.3``: both gears' tips rounded by 0.3 mm,
``tip_rounding_mm``; the reference meshes the same rounded profile, each rounding as a
curve of its own, three 0.1 mm elements along it; ``reference["rounded"]``, 8 of the
rounded pair's 24 positions, eps_alpha 1.663): gearpipe within 0.77 % in TE and 0.90 % in
stiffness at all 16 position-load cases, the roundings carrying 20-44 % of the load at 5
of them. Where a contact patch spans a rounding's tangency with the involute (positions
0 and 16) the correction of :mod:`pipeline.contact.tangency` matters: -0.01 and -0.04 %
at 100 N m, where the rounding's Hertz alone gave -0.65 and +1.42 %. The first rounded run
drew the involute and the arc as one spline, which bulged 55 nm off the profile at the
tangency and made the reference 3.2 % stiffer in TE there at 100 N m (the run was redone;
``provenance["updates"]``).

A second pair (``run --gearbox hcr_spur_pair.toml``, ``assemble-pair``:
``hcr_spur_pair_reference.json``): the transverse section of the traction helical pair made
spur (z 31/104, m 7.35 mm, eps_alpha 2.05, two or three pairs on the path), 13 of its 24
positions, 2000 and 6031 N m, its own meshes (0.1 mm on the contact flanks, 1 / 3 / 10 mm
elsewhere; two degenerate curved elements at each root cusp straightened, see
``_straighten_invalid``): gearpipe with tip contact within 0.96 % in TE and 0.79 % in
stiffness at all 26 cases, where the corners carry up to 24 % of the load at 4 positions
and keep three pairs in contact longer; confined to the nominal path it is off by up to
17.6 % in TE and 16.4 % in stiffness there. 280 s of CalculiX per position.

Cost (the shared 2-core machine, one CalculiX thread per run, two to four runs side by
side): 16.6k nodes per gear (0.1 mm); CalculiX needed 23 contact iterations for the first
load step and 8 for the next (measured at one position); 60-170 s per position, up to 350 s
where the steps had to be re-aimed; 5900 s of CalculiX for the 2 x 24 committed positions
and 2100 s for the convergence runs, about 65 min of wall time.

Regenerate: the commands of :data:`REGENERATE` (``run`` appends to a JSON-lines log,
``assemble`` writes ``demo_pair_reference.json`` with its provenance: CalculiX and Gmsh
versions, settings, mesh sizes, date, commands, wall time), then ``compare`` prints the
table against gearpipe and writes the figure.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

from pipeline.geometry import GearPair, GearSpec
from pipeline.geometry.profile import tooth_profile

HERE = Path(__file__).resolve().parent
DATA = HERE / "demo_pair_reference.json"
HCR_DATA = HERE / "hcr_spur_pair_reference.json"
"""The second pair's reference (``assemble-pair``): ``hcr_spur_pair.toml``."""
CONTACT_KINDS = ("full", "nominal")
SLAVES = ("corner", "gear", "pinion")


# ---------------------------------------------------------------------------------------
# settings and meshes
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ReferenceSettings:
    """Mesh, contact and load-step settings of the reference model.

    Attributes
    ----------
    size_contact : element size on the contact-side flank and tip land of the teeth that
        can touch, m.
    size_fine : element size on the rest of the outline of those teeth, m.
    size_tooth : element size on the outline of the other teeth, m.
    size_body : largest element size in the body, m.
    growth : growth of the element size with the distance from the outline (m per m).
    penalty : slope of the linear pressure-overclosure law, Pa/m.
    profile_points : involute points of the tooth profile polyline (fillet gets as many).
    step : half the relative spacing of the two load steps around each estimated rotation
        (-); the stiffness is the secant between them.
    slave : which tooth of each pair carries CalculiX's slave surface (the other the
        master): ``"corner"`` the tooth whose tip corner touches beyond the path of
        contact (the pinion's past its end), else the gear's; ``"gear"`` or ``"pinion"``
        always that gear's (module docstring: a master corner is under-resolved).
    """

    size_contact: float = 0.1e-3
    size_fine: float = 0.5e-3
    size_tooth: float = 1.5e-3
    size_body: float = 5.0e-3
    growth: float = 0.6
    penalty: float = 1.0e17
    profile_points: int = 80
    step: float = 0.02
    slave: str = "corner"

    def __post_init__(self) -> None:
        if self.slave not in SLAVES:
            raise ValueError(f"reference.slave = {self.slave!r} must be one of {SLAVES}")
        for name in ("size_contact", "size_fine", "size_tooth", "size_body", "growth", "penalty",
                     "step"):
            if not getattr(self, name) > 0:
                raise ValueError(f"reference.{name} = {getattr(self, name)!r} must be > 0")
        if not (self.size_contact <= self.size_fine <= self.size_tooth <= self.size_body):
            raise ValueError("reference sizes must satisfy size_contact <= size_fine <= "
                             "size_tooth <= size_body (m)")


@dataclass(frozen=True, eq=False)
class GearMesh:
    """A whole-gear 6-node triangle mesh in the gear's own frame (tooth 0 on +y).

    Attributes
    ----------
    nodes : (n, 2) node coordinates, m.
    tri : (m, 6) node indices (corner nodes, then mid-edge nodes of edges 1-2, 2-3, 3-1).
    bore : (nb,) indices of the nodes on the bore circle.
    faces : (k, 3) element index, CalculiX face number (1..3) and tooth index of the
        outline edges of the fine teeth on the contact side (right flank and tip land).
    face_radius : (k, 2) smallest and largest radius of each of those edges, m.
    face_kind : (k,) 0 fillet / root, 1 involute, 2 tip land.
    fine : tooth indices meshed at ``size_contact`` (tooth j centred at pi/2 + 2 pi j / z).
    """

    nodes: np.ndarray
    tri: np.ndarray
    bore: np.ndarray
    faces: np.ndarray
    face_radius: np.ndarray
    face_kind: np.ndarray
    fine: tuple[int, ...]


def _rotate(xy: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return xy @ np.array([[c, s], [-s, c]])


def _tooth_pieces(gear: GearSpec, points: int) -> list[tuple[str, np.ndarray]]:
    """The outline of the tooth on +y, counter-clockwise, as named pieces, each (n, 2) in m:
    the right flank (root middle -> tip corner), the tip land (right -> left corner) and the
    left flank (tip corner -> root middle). A rounded tip's arcs are pieces of their own
    (``"right_rounding"`` after the right flank's involute, ``"left_rounding"`` before the
    left flank's), so the splines through the points do not smooth the curvature jump at
    the tangency (one spline through both bulged 55 nm off the profile there)."""
    from pipeline.geometry.profile import TIP_ROUNDING

    prof = tooth_profile(gear, points)
    right = np.column_stack([prof.x, prof.y])
    ra = float(np.hypot(*right[-1]))
    half = math.atan2(right[-1, 0], right[-1, 1])
    t = np.linspace(half, -half, 17)
    tip = np.column_stack([ra * np.sin(t), ra * np.cos(t)])
    mirror = np.array([-1.0, 1.0])
    arc = np.flatnonzero(np.asarray(prof.kind) == TIP_ROUNDING)
    if arc.size == 0:
        return [("right", right), ("tip", tip), ("left", right[::-1] * mirror)]
    k = int(arc[0]) - 1  # the tangency point ends the involute and starts the arc
    flank, rounding = right[:k + 1], right[k:]
    return [("right", flank), ("right_rounding", rounding), ("tip", tip),
            ("left_rounding", rounding[::-1] * mirror), ("left", flank[::-1] * mirror)]


def gear_mesh(gear: GearSpec, fine: tuple[int, ...], settings: ReferenceSettings) -> GearMesh:
    """Mesh the whole gear (every tooth, bore circle) in Gmsh; module docstring, "Mesh"."""
    from pipeline.fem.gmsh_session import gmsh_session, size_from_fields

    z = gear.teeth
    pieces = _tooth_pieces(gear, settings.profile_points)
    fine_set = {j % z for j in fine}
    with gmsh_session() as gmsh:
        geo = gmsh.model.geo
        first = prev = None
        loop, contact_curves, fine_curves, other_curves, side = [], [], [], [], {}
        for j in range(z):
            ang = 2.0 * math.pi * j / z
            for name, piece in pieces:
                pts = _rotate(piece, ang)
                if prev is None:
                    first = prev = geo.addPoint(*pts[0], 0.0)
                closing = j == z - 1 and name == "left"
                tags = [prev] + [geo.addPoint(x, y, 0.0) for x, y in pts[1:-1]]
                tags.append(first if closing else geo.addPoint(*pts[-1], 0.0))
                c = geo.addSpline(tags)
                prev = tags[-1]
                loop.append(c)
                side[c] = (j, name)
                if j not in fine_set:
                    other_curves.append(c)
                elif name.startswith("left"):
                    fine_curves.append(c)
                else:
                    contact_curves.append(c)
        r_in = gear.bore_radius
        centre = geo.addPoint(0.0, 0.0, 0.0)
        circ = [geo.addPoint(r_in * math.cos(a), r_in * math.sin(a), 0.0)
                for a in (0.0, 2 * math.pi / 3, 4 * math.pi / 3)]
        arcs = [geo.addCircleArc(circ[i], centre, circ[(i + 1) % 3]) for i in range(3)]
        geo.addPlaneSurface([geo.addCurveLoop(loop), geo.addCurveLoop(arcs)])
        geo.synchronize()
        fld = gmsh.model.mesh.field
        fields = []
        for curves, size, sampling in ((contact_curves, settings.size_contact, 1500),
                                       (fine_curves, settings.size_fine, 300),
                                       (other_curves, settings.size_tooth, 40)):
            dist = fld.add("Distance")
            fld.setNumbers(dist, "CurvesList", curves)
            fld.setNumber(dist, "Sampling", sampling)
            thr = fld.add("Threshold")
            fld.setNumber(thr, "InField", dist)
            fld.setNumber(thr, "SizeMin", size)
            fld.setNumber(thr, "SizeMax", settings.size_body)
            fld.setNumber(thr, "DistMin", 0.5 * size)
            fld.setNumber(thr, "DistMax", 0.5 * size + (settings.size_body - size)
                          / settings.growth)
            fields.append(thr)
        size_from_fields(gmsh, fields)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.LcIntegrationPrecision", 1e-5)
        gmsh.model.mesh.generate(2)
        gmsh.model.mesh.setOrder(2)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        lookup = np.zeros(int(tags.max()) + 1, dtype=np.int64)
        lookup[tags.astype(np.int64)] = np.arange(tags.size)
        xy = coords.reshape(-1, 3)[:, :2]
        _, conn = gmsh.model.mesh.getElementsByType(9)
        tri = lookup[conn.astype(np.int64)].reshape(-1, 6)
        edge_blocks = []
        for c, (j, name) in side.items():
            if j not in fine_set or name.startswith("left"):
                continue
            _, en = gmsh.model.mesh.getElementsByType(8, c)
            e = lookup[en.astype(np.int64)].reshape(-1, 3)
            edge_blocks.append((j, name, e))
        bore_edges = []
        for c in arcs:
            _, en = gmsh.model.mesh.getElementsByType(8, c)
            bore_edges.append(lookup[en.astype(np.int64)].reshape(-1, 3))
    used = np.unique(tri)
    renum = -np.ones(xy.shape[0], dtype=np.int64)
    renum[used] = np.arange(used.size)
    nodes = xy[used].copy()
    tri = renum[tri]
    bore = np.unique(renum[np.vstack(bore_edges)])
    # orient every triangle counter-clockwise (CalculiX needs positive Jacobians)
    p = nodes[tri[:, :3]]
    area = ((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
            - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    flip = area < 0
    tri[flip] = tri[flip][:, [0, 2, 1, 5, 4, 3]]
    _straighten_invalid(nodes, tri)
    faces, radius, kind = _outline_faces(gear, nodes, tri, edge_blocks, renum)
    return GearMesh(nodes, tri, bore, faces, radius, kind, tuple(sorted(fine_set)))


GAUSS_CPE6 = ((1 / 6, 1 / 6), (2 / 3, 1 / 6), (1 / 6, 2 / 3))
"""In-plane integration points of CalculiX's CPE6 (its C3D15 wedges), where it checks the
Jacobian."""


def _min_jacobian(nodes: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """Smallest Jacobian determinant of each 6-node triangle over the integration points
    :data:`GAUSS_CPE6` (m^2)."""
    x = nodes[tri]
    out = np.full(len(tri), np.inf)
    for xi, eta in GAUSS_CPE6:
        lam = 1.0 - xi - eta
        d_xi = np.array([1 - 4 * lam, 4 * xi - 1, 0, 4 * (lam - xi), 4 * eta, -4 * eta])
        d_eta = np.array([1 - 4 * lam, 0, 4 * eta - 1, -4 * xi, 4 * xi, 4 * (lam - eta)])
        a, b = x.transpose(0, 2, 1) @ d_xi, x.transpose(0, 2, 1) @ d_eta
        out = np.minimum(out, a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    return out


FOLDED = 0.1
"""A 6-node triangle whose smallest Jacobian determinant at an integration point is below
this share of its straight triangle's (twice its area) is folded or degenerate (a curved
midside node on a corner: CalculiX refuses it); the committed demo meshes' smallest share
is 0.40, a tall-dedendum pair's degenerate root elements 1e-12."""


def _straighten_invalid(nodes: np.ndarray, tri: np.ndarray) -> int:
    """Put the midside nodes of every folded triangle (:data:`FOLDED`) at the middle of their
    straight edges (in place); returns how many. Gmsh's curved second-order nodes can fold a
    small element where two root fillets meet at the root circle in a cusp (a pair with a
    tall dedendum); there a straight edge is the outline to within the element's sagitta,
    far from the contact flanks."""
    p = nodes[tri[:, :3]]
    straight = ((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    bad = np.flatnonzero(_min_jacobian(nodes, tri) < FOLDED * straight)
    for e in bad:
        for m, (i, j) in zip(tri[e, 3:], ((0, 1), (1, 2), (2, 0)), strict=True):
            nodes[m] = 0.5 * (nodes[tri[e, i]] + nodes[tri[e, j]])
    if bad.size and (_min_jacobian(nodes, tri[bad]) < FOLDED * straight[bad]).any():
        raise RuntimeError(f"{bad.size} folded elements stay folded with straight edges")
    return int(bad.size)


def _outline_faces(gear: GearSpec, nodes: np.ndarray, tri: np.ndarray, edge_blocks: list,
                   renum: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Element faces (element, CalculiX face number, tooth), their radius range (m) and kind
    of the contact-side outline edges ``edge_blocks`` ((tooth, piece name, Gmsh edges))."""
    corner_key = {}
    for e_idx, t in enumerate(tri):
        for f, (a, b) in enumerate(((t[0], t[1]), (t[1], t[2]), (t[2], t[0])), start=1):
            corner_key[(min(a, b), max(a, b))] = (e_idx, f)
    prof = tooth_profile(gear, 60)
    r_form = prof.form_radius
    faces, radius, kind = [], [], []
    for j, name, e in edge_blocks:
        e = renum[e]
        for a, b, _m in e:
            e_idx, f = corner_key[(min(a, b), max(a, b))]
            r = np.hypot(*nodes[[a, b]].T)
            faces.append((e_idx, f, j))
            radius.append((r.min(), r.max()))
            kind.append(2 if name == "tip" else (1 if r.min() >= r_form * (1 - 1e-9) else 0))
    return np.array(faces), np.array(radius), np.array(kind)


# ---------------------------------------------------------------------------------------
# placement of the pair at a mesh position
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Placement:
    """Rigid placement of both gears at one mesh position.

    Attributes
    ----------
    s0 : roll coordinate of the leading tooth pair, m.
    pinion_angle : counter-clockwise rotation of the pinion's own frame, rad.
    gear_angle : counter-clockwise rotation of the gear's own frame (about its centre), rad.
    pinion_tooth, gear_tooth : dicts tooth pair index k -> tooth index of each gear.
    """

    s0: float
    pinion_angle: float
    gear_angle: float
    pinion_tooth: dict
    gear_tooth: dict


def _roll_of_pinion_tooth0(pair: GearPair) -> float:
    """Roll coordinate (m) where tooth 0's right flank crosses the line of action, unrotated.

    The right flank's involute leaves the base circle at the clockwise angle psi_b from +y
    (half the tooth's angular thickness there) and unwinds clockwise; the line of action
    touches the base circle at T1, at the counter-clockwise angle alpha_wt from +y, so the
    flank meets it at ``s = r_b1 (psi_b + alpha_wt)``.
    """
    p = pair.pinion
    return p.base_radius * (p.half_tooth_angle(p.base_radius) + pair.operating_pressure_angle)


def placement(pair: GearPair, s0: float) -> Placement:
    """Rotations that put tooth pair k at roll ``s0 + k p_b`` (pinion tooth 0 within half a
    pitch of the centre line). The gear starts with a tooth space on -y (pinion tooth 0 in
    it, flanks touching on both sides at zero backlash) and turns by the ratio."""
    if pair.gear.internal or pair.pinion.is_helical:
        raise ValueError("the CalculiX reference models external spur pairs only "
                         f"(gear.internal = {pair.gear.internal}, helix angle "
                         f"{math.degrees(pair.pinion.helix_angle):.6g} deg)")
    pb, rb1 = pair.base_pitch, pair.pinion.base_radius
    s_ref = _roll_of_pinion_tooth0(pair)
    k0 = round((s_ref - s0) / pb)
    delta = (s0 + k0 * pb - s_ref) / rb1  # clockwise rotation of the pinion, rad
    z1, z2 = pair.pinion.teeth, pair.gear.teeth
    gear0 = -math.pi - math.pi / z2
    # the gear tooth whose right flank meets pinion tooth 0's right flank
    mate0 = _mate_of_tooth0(pair, gear0)
    pinion_tooth = {k: k0 - k for k in range(k0 - 2, k0 + 3)}
    gear_tooth = {k: mate0 - (k0 - k) for k in pinion_tooth}
    return Placement(s0, -delta, gear0 + delta * z1 / z2, pinion_tooth, gear_tooth)


def _mate_of_tooth0(pair: GearPair, gear0: float) -> int:
    """Gear tooth index whose right-flank pitch point is nearest pinion tooth 0's."""
    a = pair.operating_centre_distance
    rp = tooth_profile(pair.pinion, 40)
    rg = tooth_profile(pair.gear, 40)
    p_mid = np.array([rp.x[-20], rp.y[-20]])
    best, arg = math.inf, 0
    for j in range(pair.gear.teeth):
        q = _rotate(np.array([[rg.x[-20], rg.y[-20]]]), gear0 + 2 * math.pi * j / pair.gear.teeth)
        d = float(np.hypot(*(q[0] + np.array([0.0, a]) - p_mid)))
        if d < best:
            best, arg = d, j
    return arg


def fine_teeth(pair: GearPair) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """Teeth of pinion and gear meshed fine: pairs k0-2 .. k0+2 of every placement."""
    pin, gea = set(), set()
    for s0 in np.linspace(pair.s_start, pair.s_start + pair.base_pitch, 9):
        pl = placement(pair, float(s0))
        pin |= set(pl.pinion_tooth.values())
        gea |= set(pl.gear_tooth.values())
    z1, z2 = pair.pinion.teeth, pair.gear.teeth
    return tuple(sorted({j % z1 for j in pin})), tuple(sorted({j % z2 for j in gea}))


# ---------------------------------------------------------------------------------------
# CalculiX input deck
# ---------------------------------------------------------------------------------------
def _contact_faces(mesh: GearMesh, teeth: set[int]) -> np.ndarray:
    """Rows of ``mesh.faces`` of the contact-side outline of ``teeth``."""
    return np.flatnonzero(np.isin(mesh.faces[:, 2], sorted(teeth)))


def contact_pairs(pair: GearPair, place: Placement, contact: str) -> list[int]:
    """Tooth pairs k given contact surfaces: every pair of the placement (``"full"``), or
    those whose roll ``s0 + k p_b`` lies on the nominal path ``[s_start, s_end]``
    (``"nominal"``: a pair beyond either end cannot touch, as in gearpipe)."""
    if contact not in CONTACT_KINDS:
        raise ValueError(f"contact = {contact!r} must be one of {CONTACT_KINDS}")
    ks = sorted(place.pinion_tooth)
    if contact == "full":
        return ks
    s = place.s0 + np.array(ks) * pair.base_pitch
    on = (s >= pair.s_start - 1e-12) & (s <= pair.s_end + 1e-12)
    return [k for k, o in zip(ks, on, strict=True) if o]


def _surface_tag(k: int) -> str:
    """Surface-name suffix of tooth pair ``k`` (CalculiX names take no minus sign)."""
    return f"M{-k}" if k < 0 else f"K{k}"


def write_inp(path: Path, pair: GearPair, meshes: tuple[GearMesh, GearMesh], place: Placement,
              rotations: np.ndarray, settings: ReferenceSettings, contact: str = "full"
              ) -> dict:
    """Write the CalculiX deck of one mesh position; returns the node-set bookkeeping.

    ``rotations`` (n,) are the pinion rotations (rad, clockwise = driving) of the n static
    steps, in increasing order.
    """
    pm, gm = meshes
    touching = contact_pairs(pair, place, contact)
    a = pair.operating_centre_distance
    xy1 = _rotate(pm.nodes, place.pinion_angle)
    xy2 = _rotate(gm.nodes, place.gear_angle) + np.array([0.0, a])
    n1, e1 = len(xy1), len(pm.tri)
    lines = ["** gearpipe reference: spur pair, plane strain, surface-to-surface contact",
             "*NODE, NSET=NALL"]
    xy = np.vstack([xy1, xy2])
    lines += [f"{i + 1}, {x:.12e}, {y:.12e}" for i, (x, y) in enumerate(xy)]
    for name, tri, off in (("EPINION", pm.tri, 0), ("EGEAR", gm.tri, n1)):
        lines.append(f"*ELEMENT, TYPE=CPE6, ELSET={name}")
        first = 1 if off == 0 else e1 + 1
        lines += [f"{first + i}, " + ", ".join(str(v + 1 + off) for v in t)
                  for i, t in enumerate(tri)]

    def nset(name: str, ids: np.ndarray) -> None:
        lines.append(f"*NSET, NSET={name}")
        ids = np.asarray(ids) + 1
        lines.extend(", ".join(str(v) for v in ids[i:i + 12]) for i in range(0, ids.size, 12))

    nset("PBORE", pm.bore)
    nset("GBORE", gm.bore + n1)
    surf_nodes = {}
    for label, mesh, gear, teeth, off, eoff in (
            ("P", pm, pair.pinion, set(place.pinion_tooth.values()), 0, 0),
            ("G", gm, pair.gear, set(place.gear_tooth.values()), n1, e1)):
        teeth = {t % gear.teeth for t in teeth}
        table = place.pinion_tooth if label == "P" else place.gear_tooth
        for k in touching:  # one surface per tooth of a pair that may touch
            rows = _contact_faces(mesh, {table[k] % gear.teeth})
            lines.append(f"*SURFACE, NAME=S{label}{_surface_tag(k)}, TYPE=ELEMENT")
            lines += [f"{mesh.faces[r, 0] + 1 + eoff}, S{mesh.faces[r, 1]}" for r in rows]
        # nodes of the contact-side outline of every fine tooth, per tooth (loads, locations)
        for j in sorted(teeth):
            rows_j = np.flatnonzero(mesh.faces[:, 2] == j)
            el = mesh.tri[mesh.faces[rows_j, 0]]
            f = mesh.faces[rows_j, 1] - 1
            loc = np.array([[0, 1, 3], [1, 2, 4], [2, 0, 5]])[f]
            ids = np.unique(np.take_along_axis(el, loc, axis=1)) + off
            surf_nodes[f"{label}{j}"] = ids
            nset(f"N{label}{j}", ids)
    for k, mat in (("PINION", pair.pinion.material), ("GEAR", pair.gear.material)):
        lines += [f"*MATERIAL, NAME=M{k}", "*ELASTIC",
                  f"{mat.youngs_modulus:.6e}, {mat.poisson_ratio:.6f}",
                  f"*SOLID SECTION, ELSET=E{k}, MATERIAL=M{k}", f"{pair.face_width:.6e}"]
    lines += ["*SURFACE INTERACTION, NAME=SI", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
              f"{settings.penalty:.6e}"]
    for k in touching:  # the teeth of one pair touch only each other
        tag = _surface_tag(k)
        pinion_slave = settings.slave == "pinion" or (
            settings.slave == "corner" and place.s0 + k * pair.base_pitch > pair.s_end)
        lines += ["*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE",
                  f"SP{tag}, SG{tag}" if pinion_slave else f"SG{tag}, SP{tag}"]
    lines += ["*BOUNDARY", "GBORE, 1, 2"]
    bore_xy = xy1[pm.bore]
    for theta in rotations:
        # clockwise rigid rotation of the bore by theta (small): u = -theta (-y, x)
        u = theta * np.column_stack([bore_xy[:, 1], -bore_xy[:, 0]])
        lines += ["*STEP, INC=200", "*STATIC, DIRECT", "1., 1.", "*BOUNDARY"]
        for node, (ux, uy) in zip(pm.bore + 1, u, strict=True):
            lines += [f"{node}, 1, 1, {ux:.12e}", f"{node}, 2, 2, {uy:.12e}"]
        lines += ["*NODE PRINT, NSET=PBORE, FREQUENCY=1000", "RF"]
        lines += ["*NODE FILE, FREQUENCY=1000", "U", "*END STEP"]
    path.write_text("\n".join(lines) + "\n")
    gear_ids = np.unique(np.concatenate([v for k, v in surf_nodes.items() if k.startswith("G")]))
    return {"pinion_nodes": n1, "surface_nodes": surf_nodes, "xy": xy,
            "surface_nodes_gear": gear_ids - n1}


def ccx_version(ccx: str = "ccx") -> str:
    """``ccx -v`` text ("Version 2.20"), or raises FileNotFoundError without CalculiX."""
    exe = shutil.which(ccx)
    if exe is None:
        raise FileNotFoundError(f"CalculiX executable {ccx!r} not found on PATH")
    out = subprocess.run([exe, "-v"], capture_output=True, text=True, timeout=60).stdout
    m = re.search(r"Version\s+([\w.]+)", out)
    return m.group(1) if m else out.strip()


def run_ccx(deck: Path, ccx: str = "ccx", threads: int = 1) -> float:
    """Run CalculiX on ``deck`` (``job.inp`` -> ``job.dat``, ``job.frd``); wall time, s."""
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), CCX_NPROC_EQUATION_SOLVER=str(threads))
    t0 = time.perf_counter()
    proc = subprocess.run([ccx, "-i", deck.stem], cwd=deck.parent, capture_output=True,
                          text=True, env=env)
    wall = time.perf_counter() - t0
    if proc.returncode != 0 or "*ERROR" in proc.stdout:
        tail = "\n".join(proc.stdout.splitlines()[-25:])
        raise RuntimeError(f"CalculiX failed on {deck} (exit {proc.returncode}):\n{tail}")
    return wall


def parse_dat(path: Path) -> list[dict[str, dict[int, np.ndarray]]]:
    """Forces of every ``*NODE PRINT`` block in a CalculiX ``.dat`` file, per step end.

    Returns one dict per output time: set name -> {node id: (fx, fy, fz)} in N.
    """
    out: list[dict[str, dict[int, np.ndarray]]] = []
    current = None
    block = None
    header = re.compile(r"forces \(fx,fy,fz\) for set (\S+) and time\s+(\S+)")
    for line in path.read_text().splitlines():
        m = header.search(line)
        if m:
            t = float(m.group(2))
            if current is None or current["__time"] != t or m.group(1) in current:
                current = {"__time": t}
                out.append(current)
            block = current.setdefault(m.group(1), {})
            continue
        parts = line.split()
        if block is not None and len(parts) == 4:
            try:
                block[int(parts[0])] = np.array([float(v) for v in parts[1:]])
            except ValueError:
                block = None
        elif parts:
            block = None
    for d in out:
        d.pop("__time")
    return out


# ---------------------------------------------------------------------------------------
# one mesh position
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class PositionResult:
    """Reference results at one mesh position and its load steps.

    Attributes
    ----------
    s0 : roll coordinate of the leading tooth pair, m.
    displacement : (n,) imposed pinion rotation of each step as arc on the base circle, m.
    torque : (n,) driving torque of each step (moment of the bore reactions), N m.
    pairs : (K,) tooth pair indices k (pair k at roll s0 + k p_b).
    pair_load : (n, K) equivalent load of each pair along the line of action (its moment
        about the gear centre over r_b2), N.
    pressure_load : (n,) sum of pair_load over the step's P = T / r_b1 (-): the closure of
        the internal-force split (1 if the gear's contact forces balance the pinion torque).
    radius_min, radius_max : (n, K) smallest / largest gear radius of the pair's loaded
        nodes (NaN if unloaded), m.
    wall : CalculiX wall time, s.
    """

    s0: float
    displacement: np.ndarray
    torque: np.ndarray
    pairs: np.ndarray
    pair_load: np.ndarray
    pressure_load: np.ndarray
    radius_min: np.ndarray
    radius_max: np.ndarray
    wall: float


def parse_frd_displacements(path: Path, n_nodes: int) -> list[np.ndarray]:
    """Nodal displacements (``*NODE FILE`` U) of a CalculiX ``.frd`` file, per output time:
    arrays (n_nodes, 2) in m, rows in node-id order (id 1 first)."""
    out = []
    lines = path.read_text().splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith(" -4  DISP"):
            u = np.zeros((n_nodes, 2))
            i += 1
            while not lines[i].startswith(" -3"):
                ln = lines[i]
                if ln.startswith(" -1"):
                    nid = int(ln[3:13])
                    if nid <= n_nodes:
                        u[nid - 1] = float(ln[13:25]), float(ln[25:37])
                i += 1
            out.append(u)
        i += 1
    return out


@dataclass(frozen=True, eq=False)
class InternalForces:
    """Internal nodal forces ``f = K u`` of one gear's mesh (plane strain, thickness b).

    The contact forces on a tooth are minus the internal forces summed over its contact
    surface nodes (every other free node is in equilibrium with no load). ``K`` is
    assembled here with scikit-fem's P2 elasticity form on the CalculiX mesh; it is only
    used to split the load between tooth pairs and to find where they touch.
    """

    stiffness: object
    dof: np.ndarray  # (n_nodes, 2) dof index of each node's x, y displacement

    @classmethod
    def build(cls, mesh: GearMesh, nodes_xy: np.ndarray, gear: GearSpec, width: float
              ) -> InternalForces:
        from scipy.spatial import cKDTree
        from skfem import Basis, ElementTriP2, ElementVector, MeshTri2
        from skfem.models.elasticity import lame_parameters, linear_elasticity

        m = MeshTri2(nodes_xy.T.copy(), mesh.tri.T.copy())
        basis = Basis(m, ElementVector(ElementTriP2()))
        lam, mu = lame_parameters(gear.material.youngs_modulus, gear.material.poisson_ratio)
        K = width * linear_elasticity(lam, mu).assemble(basis).tocsr()
        locs = basis.doflocs.T
        tree = cKDTree(locs)
        dof = np.zeros((len(nodes_xy), 2), dtype=np.int64)
        _, idx = tree.query(nodes_xy, k=2)
        for c in range(2):
            # the two dofs at a node: x first in scikit-fem's vector element
            dof[:, c] = np.sort(idx, axis=1)[:, c]
        return cls(K, dof)

    def forces(self, u: np.ndarray) -> np.ndarray:
        """(n_nodes, 2) internal forces in N for nodal displacements u (n_nodes, 2) in m."""
        x = np.zeros(self.stiffness.shape[0])
        x[self.dof[:, 0]] = u[:, 0]
        x[self.dof[:, 1]] = u[:, 1]
        f = self.stiffness @ x
        return np.column_stack([f[self.dof[:, 0]], f[self.dof[:, 1]]])


def solve_position(pair: GearPair, meshes: tuple[GearMesh, GearMesh], s0: float,
                   displacements: np.ndarray, settings: ReferenceSettings, *,
                   contact: str = "full", ccx: str = "ccx", threads: int = 1,
                   workdir: Path | None = None) -> PositionResult:
    """Run CalculiX at mesh position ``s0`` (m) for the pinion rotations ``displacements``
    (m of arc on the pinion base circle, increasing) and read the results."""
    place = placement(pair, s0)
    rb1, rb2 = pair.pinion.base_radius, pair.gear.base_radius
    with tempfile.TemporaryDirectory(dir=workdir) as tmp:
        deck = Path(tmp) / "gears.inp"
        info = write_inp(deck, pair, meshes, place, np.asarray(displacements) / rb1, settings,
                         contact)
        wall = run_ccx(deck, ccx, threads)
        forces = parse_dat(deck.with_suffix(".dat"))
        disp = parse_frd_displacements(deck.with_suffix(".frd"), len(info["xy"]))
    n = len(displacements)
    if len(forces) != n or len(disp) != n:
        raise RuntimeError(f"CalculiX wrote {len(forces)} force and {len(disp)} displacement "
                           f"blocks for {n} steps at s0 = {s0 * 1e3:.6g} mm")
    xy = info["xy"]
    pm, gm = meshes
    n1 = info["pinion_nodes"]
    torque = np.empty(n)
    for i, f in enumerate(forces):
        ids = np.array(list(f["PBORE"]))
        F = np.array(list(f["PBORE"].values()))
        p = xy[ids - 1]
        # the driving torque is minus the moment of the bore reactions (clockwise drive)
        torque[i] = float(np.sum(p[:, 0] * F[:, 1] - p[:, 1] * F[:, 0]))
    torque = -torque
    ks = np.array(sorted(place.gear_tooth))
    centre = np.array([0.0, pair.operating_centre_distance])
    gear_xy = xy[n1:]
    internal = InternalForces.build(gm, gear_xy, pair.gear, pair.face_width)
    pair_load = np.zeros((n, ks.size))
    rmin = np.full((n, ks.size), np.nan)
    rmax = np.full((n, ks.size), np.nan)
    for i in range(n):
        f = -internal.forces(disp[i][n1:])  # contact forces on the gear's nodes, N
        fmax = np.abs(f[info["surface_nodes_gear"]]).max()
        for c, k in enumerate(ks):
            ids = info["surface_nodes"][f"G{place.gear_tooth[k] % pair.gear.teeth}"] - n1
            r = gear_xy[ids] - centre
            # the load on the driven gear turns it counter-clockwise; f = -K u is the
            # force the gear's nodes exert on the pinion side, so the sign flips once more
            pair_load[i, c] = -float(np.sum(r[:, 0] * f[ids, 1] - r[:, 1] * f[ids, 0])) / rb2
            loaded = np.hypot(*f[ids].T) > 1e-3 * fmax
            if loaded.any():
                rad = np.hypot(*r[loaded].T)
                rmin[i, c], rmax[i, c] = rad.min(), rad.max()
    closure = pair_load.sum(axis=1) / (torque / rb1)
    return PositionResult(float(s0), np.asarray(displacements, float), torque, ks, pair_load,
                          closure, rmin, rmax, wall)


# ---------------------------------------------------------------------------------------
# a mesh cycle at given torques
# ---------------------------------------------------------------------------------------
LOADED_SHARE = 3e-3
"""A tooth pair is loaded when it carries more than this share of P: the load split by
``K u`` has a noise of about +-2 N (0.1 % of P at 100 N m) on the teeth out of contact."""


def pair_flags(pair: GearPair, s0: float, pairs, loads, torque: float
               ) -> tuple[np.ndarray, np.ndarray]:
    """(loaded, beyond): tooth pairs carrying more than ``LOADED_SHARE`` of P, and those of
    them whose nominal roll ``s0 + k p_b`` (m) lies outside ``[s_start, s_end]``."""
    loads = np.asarray(loads, dtype=float)
    s_k = s0 + np.asarray(pairs) * pair.base_pitch
    loaded = loads > LOADED_SHARE * torque / pair.pinion.base_radius
    beyond = loaded & ((s_k < pair.s_start - 1e-12) | (s_k > pair.s_end + 1e-12))
    return loaded, beyond


def _at_torque(res: PositionResult, pair: GearPair, torque: float, lo: int, hi: int) -> dict:
    """TE, stiffness, pair loads at ``torque`` (N m) from the steps ``lo`` and ``hi``
    (linear inter-/extrapolation; the stiffness is their secant)."""
    rb1 = pair.pinion.base_radius
    d, t = res.displacement, res.torque
    w = (torque - t[lo]) / (t[hi] - t[lo])
    te = d[lo] + w * (d[hi] - d[lo])
    k = (t[hi] - t[lo]) / rb1 / (d[hi] - d[lo])
    loads = res.pair_load[lo] + w * (res.pair_load[hi] - res.pair_load[lo])
    near = lo if abs(w) < abs(1 - w) else hi
    loaded, beyond = pair_flags(pair, res.s0, res.pairs, loads, torque)
    return {"transmission_error_m": float(te), "mesh_stiffness_N_per_m": float(k),
            "pair_load_N": loads.tolist(), "pair_loaded": loaded.tolist(),
            "pair_beyond_path": beyond.tolist(),
            "gear_contact_radius_min_m": np.where(loaded, res.radius_min[near], np.nan).tolist(),
            "gear_contact_radius_max_m": np.where(loaded, res.radius_max[near], np.nan).tolist(),
            "bracket_torque_Nm": [float(t[lo]), float(t[hi])],
            "load_split_closure": float(res.pressure_load[near])}


MAX_ATTEMPTS = 4
BRACKET = 0.02  # a torque may lie this share of itself outside its two load steps


def _bracketed(step_torque: np.ndarray, torque: float) -> bool:
    """True when the two steps nearest ``torque`` (N m) enclose it, up to ``BRACKET``."""
    lo, hi = np.sort(step_torque[np.argsort(np.abs(step_torque - torque))[:2]])
    return lo - BRACKET * torque <= torque <= hi + BRACKET * torque


def _aim(d: np.ndarray, t: np.ndarray, torque: float) -> float:
    """Rotation (arc on the base circle, m) expected to give ``torque`` (N m): linear
    through the two steps seen that enclose it most tightly, or the two nearest."""
    order = np.argsort(t)
    d, t = d[order], t[order]
    k = int(np.searchsorted(t, torque))
    i, j = (k - 1, k) if 0 < k < t.size else ((0, 1) if k == 0 else (t.size - 2, t.size - 1))
    return float(d[i] + (torque - t[i]) * (d[j] - d[i]) / (t[j] - t[i]))


def reference_cycle(pair: GearPair, positions: np.ndarray, torques: tuple[float, ...],
                    settings: ReferenceSettings, estimate: np.ndarray, *,
                    contact: str = "full", ccx: str = "ccx", threads: int = 1,
                    log: Path | None = None) -> tuple[list[dict], dict]:
    """Reference results at each roll coordinate of ``positions`` (m) and torque (N m).

    ``estimate`` (n_positions, n_torques) is a first guess of the loaded TE (m); the load
    steps are placed at ``(1 -+ step)`` times it, corrected position by position by the
    ratio found at the previous one. A torque that its two nearest steps miss by more than
    ``BRACKET`` of itself is aimed at again (:func:`_aim`) and the position rerun. Each
    finished position is appended to ``log`` (JSON lines) when given. Returns one dict
    per position (keys of :func:`_at_torque` per torque under ``"torques"``, the raw steps,
    the wall time, the attempts) and the mesh sizes.
    """
    fp, fg = fine_teeth(pair)
    meshes = (gear_mesh(pair.pinion, fp, settings), gear_mesh(pair.gear, fg, settings))
    ratio = np.ones(len(torques))
    out = []
    for i, s0 in enumerate(positions):
        guess = np.asarray(estimate[i], dtype=float) * ratio
        seen_d, seen_t, wall = [], [], 0.0
        for attempts in range(1, MAX_ATTEMPTS + 1):  # noqa: B007 (read after the loop)
            steps = np.sort(np.concatenate([guess * (1 - settings.step),
                                            guess * (1 + settings.step)]))
            res = solve_position(pair, meshes, float(s0), steps, settings, contact=contact,
                                 ccx=ccx, threads=threads)
            wall += res.wall
            seen_d += res.displacement.tolist()
            seen_t += res.torque.tolist()
            missed = [j for j, T in enumerate(torques) if not _bracketed(res.torque, T)]
            if not missed:
                break
            # a contact that opens or closes between the estimate and the torque makes
            # T(theta) kinked: aim again from every step seen so far
            for j in missed:
                guess[j] = _aim(np.array(seen_d), np.array(seen_t), torques[j])
        else:
            raise RuntimeError(f"s0 = {s0 * 1e3:.6g} mm: no load steps bracket the torques "
                               f"{torques} N m after {MAX_ATTEMPTS} attempts")
        entry = {"s0_m": float(s0), "wall_s": wall, "attempts": attempts,
                 "pairs": res.pairs.tolist(),
                 "step_displacement_m": res.displacement.tolist(),
                 "step_torque_Nm": res.torque.tolist(), "torques": []}
        for j, T in enumerate(torques):
            order = np.argsort(np.abs(res.torque - T))
            lo, hi = sorted(order[:2].tolist())
            entry["torques"].append(_at_torque(res, pair, T, lo, hi))
            ratio[j] = entry["torques"][-1]["transmission_error_m"] / estimate[i][j]
        out.append(entry)
        if log is not None:
            with open(log, "a") as fh:
                fh.write(json.dumps(entry) + "\n")
    return out, {"pinion_nodes": len(meshes[0].nodes), "gear_nodes": len(meshes[1].nodes),
                 "pinion_elements": len(meshes[0].tri), "gear_elements": len(meshes[1].tri),
                 "fine_teeth_pinion": list(fp), "fine_teeth_gear": list(fg)}


# ---------------------------------------------------------------------------------------
# gearpipe's loaded contact at the same positions, and the comparison
# ---------------------------------------------------------------------------------------
def demo_pair_text(tip_contact: bool = True, tip_rounding_mm: float = 0.0) -> str:
    """The demo pair (``workflows/default_case.py``) with the FE-enriched loaded contact,
    frictionless (the reference is frictionless); ``tip_contact`` False confines gearpipe's
    contact to the nominal path (the control run's counterpart); ``tip_rounding_mm`` rounds
    the tips of both gears by design (``tip_rounding_mm`` of each gear table; the reference
    meshes the same rounded profile, :func:`pipeline.geometry.profile.tooth_profile`)."""
    from workflows.default_case import DEMO_PAIR

    pair = DEMO_PAIR
    if tip_rounding_mm:
        for table in ("[pinion]\n", "[gear]\n"):
            pair = pair.replace(table, f"{table}tip_rounding_mm = {tip_rounding_mm!r}\n", 1)
    return ('name = "reference"\n' + pair + '[contact]\ncompliance = "fe2d"\n'
            + ("" if tip_contact else "tip_contact = false\n"))


def _demo_source(text: str, cache):
    from pipeline.cache.folder import DEFAULT_CACHE
    from pipeline.config.gearbox import gearbox_from_text
    from pipeline.contact.compliance import compliance_source

    box = gearbox_from_text(text, name="reference")
    src = compliance_source(box.pair, box.operation, box.contact, box.stiffness, box.fe_source,
                            cache=DEFAULT_CACHE if cache is None else cache)
    return box, src


def gearpipe_cycle(text: str, positions: np.ndarray, torques: tuple[float, ...],
                   cache=None) -> dict:
    """gearpipe's loaded contact (the gearbox ``text``'s ``[contact]`` and ``[fe]``) at the
    roll coordinates ``positions`` (m) and driving torques (N m); FE tables from ``cache``
    (:class:`pipeline.cache.folder.Cache`, default the project's).

    Returns ``transmission_error_m`` and ``mesh_stiffness_N_per_m`` (tangent) of shape
    (n_torques, n_positions), ``pair_index`` (K,) and ``pair_load_N`` (n_torques,
    n_positions, K).
    """
    from pipeline.contact.ltca import loaded_mesh_cycle

    box, src = _demo_source(text, cache)
    te, k, loads = [], [], []
    for T in torques:
        cyc = loaded_mesh_cycle(src, T / box.pair.pinion.base_radius, box.contact.modifications,
                                box.contact.local_contact, positions=np.asarray(positions))
        te.append(cyc.transmission_error)
        k.append(cyc.mesh_stiffness)
        loads.append(cyc.pair_loads)
    return {"transmission_error_m": np.array(te), "mesh_stiffness_N_per_m": np.array(k),
            "pair_index": np.asarray(cyc.pair_index), "pair_load_N": np.array(loads)}


def gearpipe_at_reference(reference: dict, run: str = "full", cache=None,
                          entries: list[dict] | None = None, text: str | None = None) -> dict:
    """gearpipe like for like with a reference run (``"full"``: :func:`demo_pair_text` with
    tip contact; ``"nominal"``: without): at every position and torque T the loaded TE at
    T, and the mesh stiffness as the secant over the two load steps that bracket T in the
    reference (``bracket_torque_Nm``), as the reference defines it (a tangent differs
    from that secant where a tip corner closes between the steps). Returns
    ``transmission_error_m`` and ``mesh_stiffness_N_per_m`` of shape (n_torques,
    n_positions). ``entries`` and ``text`` (the gearbox) replace the run's, e.g. the
    rounded-tip run (:func:`rounded_run`)."""
    from pipeline.contact.ltca import loaded_mesh_cycle

    box, src = _demo_source(demo_pair_text(run == "full") if text is None else text, cache)
    rb1 = box.pair.pinion.base_radius
    entries = reference["runs"][run] if entries is None else entries
    te = np.empty((len(reference["torques_Nm"]), len(entries)))
    k = np.empty_like(te)

    def loaded_te(torque: float, s0: float) -> float:
        cyc = loaded_mesh_cycle(src, torque / rb1, box.contact.modifications,
                                box.contact.local_contact, positions=np.array([s0]))
        return float(cyc.transmission_error[0])

    for i, e in enumerate(entries):
        for t, T in enumerate(reference["torques_Nm"]):
            lo, hi = e["torques"][t]["bracket_torque_Nm"]
            te[t, i] = loaded_te(T, e["s0_m"])
            k[t, i] = (hi - lo) / rb1 / (loaded_te(hi, e["s0_m"]) - loaded_te(lo, e["s0_m"]))
    return {"transmission_error_m": te, "mesh_stiffness_N_per_m": k}


def gearpipe_torques_at_rotations(reference: dict, indices, cache=None) -> np.ndarray:
    """gearpipe's driving torque (N m) at the reference's own load steps, the rotations of
    its full run (``step_displacement_m``, the loaded TE each step imposes) at the positions
    ``indices``: shape (len(indices), 4), the torque whose loaded TE equals the step's
    (brentq to 1e-6 N m). A comparison free of the load-step secant."""
    from scipy.optimize import brentq

    from pipeline.contact.ltca import loaded_mesh_cycle

    box, src = _demo_source(demo_pair_text(True), cache)
    rb1 = box.pair.pinion.base_radius
    out = []
    for i in indices:
        e = reference["runs"]["full"][i]

        def te(torque: float, s0: float = e["s0_m"]) -> float:
            return float(loaded_mesh_cycle(src, torque / rb1, box.contact.modifications,
                                           box.contact.local_contact,
                                           positions=np.array([s0])).transmission_error[0])

        out.append([brentq(lambda T, d=d: te(T) - d, 0.5 * T0, 1.5 * T0, xtol=1e-6)
                    for d, T0 in zip(e["step_displacement_m"], e["step_torque_Nm"],
                                     strict=True)])
    return np.array(out)


@dataclass(frozen=True)
class Comparison:
    """Reference against gearpipe at every position and torque.

    Attributes
    ----------
    s0 : (m,) roll coordinates, m.
    torque : (t,) driving torques, N m.
    zone : (m,) number of tooth pairs on the nominal path of contact (1 or 2).
    te_reference, te_gearpipe : (t, m) loaded transmission error, m.
    k_reference, k_gearpipe : (t, m) mesh stiffness, N/m.
    te_difference, k_difference : (t, m) gearpipe / reference - 1 (-).
    beyond_path : (t, m) True where the reference has a pair loaded outside the nominal
        path of contact.
    """

    s0: np.ndarray
    torque: np.ndarray
    zone: np.ndarray
    te_reference: np.ndarray
    te_gearpipe: np.ndarray
    k_reference: np.ndarray
    k_gearpipe: np.ndarray
    te_difference: np.ndarray
    k_difference: np.ndarray
    beyond_path: np.ndarray

    def rows(self) -> list[str]:
        """A text table: one line per torque and position (um, N/um, %)."""
        out = ["torque [N m]  s0 [mm]  pairs  TE ref [um]  TE gp [um]  dTE [%]  "
               "k ref [N/um]  k gp [N/um]  dk [%]  beyond path"]
        for t, T in enumerate(self.torque):
            for i, s in enumerate(self.s0):
                out.append(
                    f"{T:11.1f}  {s * 1e3:7.3f}  {self.zone[i]:5d}  "
                    f"{self.te_reference[t, i] * 1e6:11.3f}  "
                    f"{self.te_gearpipe[t, i] * 1e6:10.3f}  "
                    f"{self.te_difference[t, i] * 100:7.2f}  "
                    f"{self.k_reference[t, i] * 1e-6:12.2f}  "
                    f"{self.k_gearpipe[t, i] * 1e-6:11.2f}  "
                    f"{self.k_difference[t, i] * 100:6.2f}"
                    f"  {'yes' if self.beyond_path[t, i] else 'no'}")
        return out


def load_reference(path: Path = DATA) -> dict:
    """The committed reference data (JSON, SI units; keys name their units)."""
    return json.loads(Path(path).read_text())


def compare(reference: dict, gearpipe: dict, pair: GearPair, run: str = "full") -> Comparison:
    """Comparison table of a reference run (``"full"`` or ``"nominal"`` contact) of
    :func:`load_reference` and :func:`gearpipe_at_reference` of that run."""
    s0 = np.array(reference["positions_m"])
    torques = np.array(reference["torques_Nm"])
    runs = reference["runs"][run]
    te = np.array([[p["torques"][t]["transmission_error_m"] for p in runs]
                   for t in range(torques.size)])
    k = np.array([[p["torques"][t]["mesh_stiffness_N_per_m"] for p in runs]
                  for t in range(torques.size)])
    beyond = np.array([[any(p["torques"][t]["pair_beyond_path"]) for p in runs]
                       for t in range(torques.size)])
    _, on_path = pair.pair_positions(s0)
    te_g = np.asarray(gearpipe["transmission_error_m"])
    k_g = np.asarray(gearpipe["mesh_stiffness_N_per_m"])
    if te_g.shape != te.shape:
        raise ValueError(f"gearpipe results have shape {te_g.shape}, the reference {te.shape}")
    return Comparison(s0, torques, on_path.sum(axis=1), te, te_g, k, k_g, te_g / te - 1.0,
                      k_g / k - 1.0, beyond)


@dataclass(frozen=True)
class SweepComparison:
    """A load sweep of the reference (many load steps at one position, ``sweep``) against
    gearpipe at the same rotations.

    Attributes
    ----------
    s0 : roll coordinate of the position, m.
    size_contact : the reference's element size on the contact flanks, m.
    pairs : (K,) tooth pair indices of the reference's pair loads.
    rotation : (n,) imposed rotation of each step (arc on the pinion base circle), m.
    torque_reference, torque_gearpipe : (n,) driving torque at each rotation, N m.
    load_reference, load_gearpipe : (n, K) tooth pair loads along the line of action, N.
    k_reference, k_gearpipe : (n - 1,) secant mesh stiffness between consecutive steps, N/m.
    closing : (n - 1,) True where a contact closes inside the interval in either model
        (``closure_*``).
    closure_reference, closure_gearpipe : dict pair -> rotation (m) where a pair unloaded
        at the first step closes: its load extrapolated linearly to zero from its first
        two steps carrying more than :data:`LOADED_SHARE` of P.
    """

    s0: float
    size_contact: float
    pairs: np.ndarray
    rotation: np.ndarray
    torque_reference: np.ndarray
    torque_gearpipe: np.ndarray
    load_reference: np.ndarray
    load_gearpipe: np.ndarray
    k_reference: np.ndarray
    k_gearpipe: np.ndarray
    closing: np.ndarray
    closure_reference: dict
    closure_gearpipe: dict


def _closures(rotation: np.ndarray, loads: np.ndarray, pairs, threshold: np.ndarray) -> dict:
    out = {}
    for c, k in enumerate(pairs):
        on = np.flatnonzero(loads[:, c] > threshold)
        if on.size >= 2 and on[0] > 0:
            i, j = on[0], on[0] + 1
            slope = (loads[j, c] - loads[i, c]) / (rotation[j] - rotation[i])
            out[int(k)] = float(rotation[i] - loads[i, c] / slope)
    return out


def sweep_comparison(sweep: dict, cache=None, text: str | None = None) -> SweepComparison:
    """gearpipe (the demo pair with tip contact, the FE 2D source; ``text`` another gearbox
    of it, e.g. other ``[fe]`` settings) at the rotations of a reference load sweep: the
    torque whose loaded TE equals each step's rotation (brentq to 1e-7 N m), its pair loads
    there, the secant stiffness between steps of both, and where each model's contacts
    close."""
    from scipy.optimize import brentq

    from pipeline.contact.ltca import loaded_mesh_cycle

    box, src = _demo_source(demo_pair_text(True) if text is None else text, cache)
    rb1 = box.pair.pinion.base_radius
    s0 = np.array([sweep["s0_m"]])

    def cycle(torque: float):
        return loaded_mesh_cycle(src, torque / rb1, box.contact.modifications,
                                 box.contact.local_contact, positions=s0)

    d = np.asarray(sweep["step_displacement_m"])
    t_ref = np.asarray(sweep["step_torque_Nm"])
    t_gp = np.array([brentq(lambda T, x=x: cycle(T).transmission_error[0] - x, 0.5 * T0,
                            1.5 * T0, xtol=1e-7) for x, T0 in zip(d, t_ref, strict=True)])
    pairs = np.asarray(sweep["pairs"])
    load_ref = np.asarray(sweep["step_pair_load_N"])
    load_gp = np.zeros_like(load_ref)
    for i, T in enumerate(t_gp):
        cyc = cycle(T)
        for c, k in enumerate(cyc.pair_index):
            load_gp[i, np.flatnonzero(pairs == k)] = cyc.pair_loads[0, c]
    k_ref = np.diff(t_ref) / rb1 / np.diff(d)
    k_gp = np.diff(t_gp) / rb1 / np.diff(d)
    c_ref = _closures(d, load_ref, pairs, LOADED_SHARE * t_ref / rb1)
    c_gp = _closures(d, load_gp, pairs, LOADED_SHARE * t_gp / rb1)
    at = np.array([*c_ref.values(), *c_gp.values()])
    closing = ((at[None, :] >= d[:-1, None]) & (at[None, :] < d[1:, None])).any(axis=1)
    return SweepComparison(float(sweep["s0_m"]), float(sweep["size_contact_m"]), pairs, d,
                           t_ref, t_gp, load_ref, load_gp, k_ref, k_gp, closing, c_ref, c_gp)


# ---------------------------------------------------------------------------------------
# command line
# ---------------------------------------------------------------------------------------
TORQUES = (100.0, 340.0)
POSITIONS = 24
REGENERATE = (
    "run --contact full --log full.jsonl",
    "run --contact nominal --indices 0 2 4 6 8 10 12 14 16 18 20 22 --log nominal_0.jsonl",
    "run --contact nominal --indices 1 3 5 7 9 11 13 15 17 19 21 23 --log nominal_1.jsonl",
    "run --size-contact 0.2 --indices 9 18 21 --log conv_0.2.jsonl",
    "run --size-contact 0.05 --indices 9 18 21 --log conv_0.05.jsonl",
    "run --size-contact 0.1 --size-fine 0.25 --growth 0.3 --indices 9 21 --log conv_tooth.jsonl",
    "run --size-contact 0.1 --penalty 4e17 --indices 21 --log conv_pen.jsonl",
    "run --size-contact 0.1 --size-tooth 0.75 --size-body 2.5 --growth 0.3 --indices 9 21 "
    "--log conv_far.jsonl",
    "same-steps --log full.jsonl --index 21 --size-contact 0.05 --out samestep.json",
    "sweep --index 21 --torque 340 --span 0.1 --steps 11 --out p21_340_01.json",
    "sweep --index 21 --torque 340 --span 0.1 --steps 11 --size-contact 0.05 "
    "--out p21_340_005.json",
    "assemble --full full.jsonl --nominal nominal_0.jsonl nominal_1.jsonl --convergence "
    "0.2,0.5,1.5,5,0.6,1e17:conv_0.2.jsonl 0.05,0.5,1.5,5,0.6,1e17:conv_0.05.jsonl "
    "0.1,0.25,1.5,5,0.3,1e17:conv_tooth.jsonl 0.1,0.5,1.5,5,0.6,4e17:conv_pen.jsonl "
    "0.1,0.5,0.75,2.5,0.3,1e17:conv_far.jsonl --same-steps samestep.json",
)
"""The commands that wrote the committed reference (each ``run`` appends to its log)."""


def _demo_pair(tip_rounding_mm: float = 0.0) -> GearPair:
    from pipeline.config.gearbox import gearbox_from_text

    return gearbox_from_text(demo_pair_text(True, tip_rounding_mm), name="reference").pair


def rounded_run(reference: dict) -> tuple[list[dict], str]:
    """The rounded-tip run of the reference (entries at a subset of the rounded pair's
    mesh-cycle positions) and the gearbox text gearpipe compares it with."""
    r = reference["rounded"]
    return r["entries"], demo_pair_text(True, r["tip_rounding_m"] * 1e3)


def _settings(args) -> ReferenceSettings:
    base = ReferenceSettings()
    def mm(value, default):
        return value * 1e-3 if value else default

    return ReferenceSettings(size_contact=args.size_contact * 1e-3,
                             size_fine=mm(args.size_fine, base.size_fine),
                             size_tooth=mm(args.size_tooth, base.size_tooth),
                             size_body=mm(args.size_body, base.size_body),
                             growth=args.growth or base.growth, penalty=args.penalty,
                             slave=getattr(args, "slave", base.slave))


def _finite(x):
    """NaN -> None, recursively (strict JSON)."""
    if isinstance(x, float):
        return None if math.isnan(x) else x
    if isinstance(x, list):
        return [_finite(v) for v in x]
    if isinstance(x, dict):
        return {k: _finite(v) for k, v in x.items()}
    return x


def _mesh_info(pair: GearPair, settings: ReferenceSettings) -> dict:
    fp, fg = fine_teeth(pair)
    pm, gm = gear_mesh(pair.pinion, fp, settings), gear_mesh(pair.gear, fg, settings)
    return {"pinion_nodes": len(pm.nodes), "gear_nodes": len(gm.nodes),
            "pinion_elements": len(pm.tri), "gear_elements": len(gm.tri),
            "fine_teeth_pinion": list(fp), "fine_teeth_gear": list(fg)}


def _reflag(pair: GearPair, entry: dict) -> None:
    """Loaded / beyond-path flags of a log entry from its pair loads (:func:`pair_flags`)."""
    for T, res in zip(TORQUES, entry["torques"], strict=True):
        loaded, beyond = pair_flags(pair, entry["s0_m"], entry["pairs"], res["pair_load_N"], T)
        res["pair_loaded"], res["pair_beyond_path"] = loaded.tolist(), beyond.tolist()


def _run_entries(pair: GearPair, logs, s0: np.ndarray) -> list[dict]:
    """The entries of one run from its JSON-lines ``logs`` (a later log replaces an earlier
    one's entry at the same position), checked to cover the positions ``s0`` (m)."""
    by_s0 = {round(e["s0_m"], 12): e for log in logs for e in _read_log(log)}
    entries = [by_s0[k] for k in sorted(by_s0)]
    got = np.array([e["s0_m"] for e in entries])
    if got.shape != s0.shape or not np.allclose(got, s0, rtol=0, atol=1e-12):
        raise SystemExit(f"{logs}: positions do not cover the {s0.size}-position mesh cycle")
    for e in entries:
        _reflag(pair, e)
    return entries


def _convergence_entries(pair: GearPair, specs, slave: str = "gear") -> list[dict]:
    """Convergence entries from ``size,fine,tooth,body,growth,penalty:LOG`` specs (sizes in
    mm), labelled with their mesh settings and slave rule."""
    out = []
    for spec in specs or []:
        values, log = spec.split(":", 1)
        size, fine, tooth, body, growth, penalty = (float(v) for v in values.split(","))
        for e in _read_log(Path(log)):
            e.update(size_contact_m=size * 1e-3, size_fine_m=fine * 1e-3,
                     size_tooth_m=tooth * 1e-3, size_body_m=body * 1e-3, growth=growth,
                     penalty_Pa_per_m=penalty, slave=slave)
            _reflag(pair, e)
            out.append(e)
    return out


def _provenance(args) -> dict:
    """What a written reference file records of how it was made: versions, date, command."""
    import gmsh

    import pipeline

    return {"calculix_version": ccx_version(), "gmsh_version": gmsh.__version__,
            "gearpipe_version": pipeline.__version__,
            "date_utc": datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
            "command": " ".join(["python workflows/reference/calculix_spur_contact.py",
                                 *args.argv])}


def _cmd_assemble(args) -> int:
    """Merge the JSON-lines logs of the runs into the committed reference file."""


    pair = _demo_pair()
    settings = ReferenceSettings()
    s0 = pair.mesh_cycle(args.positions)
    runs = {name: _run_entries(pair, logs, s0)
            for name, logs in (("full", args.full), ("nominal", args.nominal))}
    convergence = _convergence_entries(pair, args.convergence, ReferenceSettings().slave)
    wall = sum(e["wall_s"] for r in runs.values() for e in r)
    doc = {
        "description": "CalculiX plane-strain contact reference of the demo pair "
                       "(workflows/reference/calculix_spur_contact.py); SI units",
        "provenance": {
            **_provenance(args),
            "run_commands": [f"python workflows/reference/calculix_spur_contact.py {c}"
                             for c in REGENERATE],
            "settings": asdict(settings), "mesh": _mesh_info(pair, settings),
            "elements": "CPE6 (plane strain, quadratic), thickness = face width",
            "contact": "surface to surface, frictionless, linear penalty",
            "ccx_wall_time_s": wall,
            "note": args.note,
            "ccx_wall_time_convergence_s": sum(e["wall_s"] for e in convergence),
        },
        "pair": {"teeth": [pair.pinion.teeth, pair.gear.teeth], "module_m": pair.pinion.module,
                 "face_width_m": pair.face_width, **pair.summary()},
        "torques_Nm": list(TORQUES),
        "positions_m": s0.tolist(),
        "runs": runs,
        "convergence": convergence,
        "convergence_same_steps": [json.loads(Path(f).read_text()) for f in args.same_steps],
    }
    args.out.write_text(json.dumps(_finite(doc), indent=1) + "\n")
    print(f"wrote {args.out} ({wall:.0f} s of CalculiX)")
    return 0


def _cmd_assemble_pair(args) -> int:
    """Write the reference file of another pair (a gearbox file, ``run --gearbox``) from the
    JSON-lines logs of its runs: the gearbox text, its provenance, the positions run."""


    text, pair = gearbox_pair(args.gearbox)
    settings = _settings(args)
    entries = sorted((e for log in args.log for e in _read_log(log)), key=lambda e: e["s0_m"])
    cycle = pair.mesh_cycle(args.positions)
    for e in entries:
        if not np.isclose(cycle, e["s0_m"], rtol=0, atol=1e-12).any():
            raise SystemExit(f"{e['s0_m']} m is not a position of the {args.positions}-position "
                             "mesh cycle")
        for T, res in zip(args.torques, e["torques"], strict=True):
            loaded, beyond = pair_flags(pair, e["s0_m"], e["pairs"], res["pair_load_N"], T)
            res["pair_loaded"], res["pair_beyond_path"] = loaded.tolist(), beyond.tolist()
    doc = {
        "description": f"CalculiX plane-strain contact reference of {args.gearbox.name} "
                       "(workflows/reference/calculix_spur_contact.py); SI units",
        "provenance": {
            **_provenance(args),
            "settings": asdict(settings), "mesh": _mesh_info(pair, settings),
            "ccx_wall_time_s": sum(e["wall_s"] for e in entries), "note": args.note,
        },
        "gearbox": text,
        "pair": {"teeth": [pair.pinion.teeth, pair.gear.teeth], "module_m": pair.pinion.module,
                 "face_width_m": pair.face_width, **pair.summary()},
        "torques_Nm": list(args.torques),
        "positions_m": cycle.tolist(),
        "runs": {"full": entries},
    }
    args.out.write_text(json.dumps(_finite(doc), indent=1) + "\n")
    print(f"wrote {args.out}")
    return 0


def _cmd_update(args) -> int:
    """Replace one run of the committed reference file by new logs (a later log replaces
    an earlier one's entry at the same position), or add convergence entries; the rest is
    kept, and the change is recorded in ``provenance["updates"]``."""
    pair = _demo_pair()
    doc = load_reference(args.data)
    s0 = np.array(doc["positions_m"])
    entry = {"date_utc": datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
             "command": " ".join(["python workflows/reference/calculix_spur_contact.py",
                                  *args.argv]),
             "calculix_version": ccx_version(), "settings": asdict(ReferenceSettings()),
             "note": args.note}
    if args.run:
        entries = _run_entries(pair, args.log, s0)
        doc["runs"][args.run] = entries
        entry["run"] = args.run
        entry["ccx_wall_time_s"] = sum(e["wall_s"] for e in entries)
    doc["convergence"] += _convergence_entries(pair, args.convergence, args.slave)
    if args.sweep:
        sweeps = [json.loads(Path(f).read_text()) for f in args.sweep]
        key = lambda e: (round(e["s0_m"], 12), e["torque_Nm"], e["size_contact_m"])  # noqa: E731
        kept = {key(e): e for e in doc.get("load_sweeps", []) + sweeps}
        doc["load_sweeps"] = [kept[k] for k in sorted(kept)]
        entry["sweeps"] = [str(f) for f in args.sweep]
    if args.rounded:
        rpair = _demo_pair(args.tip_rounding)
        entries = [e for log in args.rounded for e in _read_log(log)]
        for e in entries:
            _reflag(rpair, e)
        doc["rounded"] = {"tip_rounding_m": args.tip_rounding * 1e-3,
                          "positions_m": rpair.mesh_cycle(POSITIONS).tolist(),
                          "entries": sorted(entries, key=lambda e: e["s0_m"])}
        entry["rounded"] = args.tip_rounding
    doc["provenance"].setdefault("updates", []).append(entry)
    args.data.write_text(json.dumps(_finite(doc), indent=1) + "\n")
    print(f"updated {args.data}")
    return 0


def gearbox_pair(path: Path) -> tuple[str, GearPair]:
    """The text of a gearbox file for another reference pair (an external spur pair with
    ``[contact] compliance = "fe2d"``, gearpipe's side of the comparison) and its pair."""
    from pipeline.config.gearbox import gearbox_from_text

    text = Path(path).read_text()
    box = gearbox_from_text(text, name=Path(path).stem)
    if box.contact.compliance != "fe2d":
        raise SystemExit(f"{path}: [contact] compliance must be \"fe2d\" for the reference "
                         f"comparison, not {box.contact.compliance!r}")
    return text, box.pair


def _cmd_run(args) -> int:
    if args.gearbox:
        if args.tip_rounding:
            raise SystemExit("--tip-rounding applies to the demo pair; a gearbox file "
                             "states its own tip_rounding_mm")
        text, pair = gearbox_pair(args.gearbox)
    else:
        text, pair = demo_pair_text(True, args.tip_rounding), _demo_pair(args.tip_rounding)
    s0 = pair.mesh_cycle(args.positions)
    idx = np.array(args.indices if args.indices else range(args.positions), dtype=int)
    gp = gearpipe_cycle(text, s0[idx], tuple(args.torques))
    t0 = time.perf_counter()
    reference_cycle(pair, s0[idx], tuple(args.torques), _settings(args),
                    gp["transmission_error_m"].T, contact=args.contact, ccx=args.ccx,
                    threads=args.threads, log=args.log)
    print(f"wall {time.perf_counter() - t0:.1f} s")
    return 0


def _cmd_same_steps(args) -> int:
    """Rerun the load steps of a logged position on another mesh (torques at the same
    rotations: a convergence check free of the secant interval)."""
    pair = _demo_pair()
    s0 = float(pair.mesh_cycle(args.positions)[args.index])
    entry = next(e for e in _read_log(args.log) if abs(e["s0_m"] - s0) < 1e-12)
    settings = _settings(args)
    fp, fg = fine_teeth(pair)
    meshes = (gear_mesh(pair.pinion, fp, settings), gear_mesh(pair.gear, fg, settings))
    res = solve_position(pair, meshes, s0, np.array(entry["step_displacement_m"]), settings,
                         ccx=args.ccx, threads=args.threads)
    out = {"s0_m": s0, "size_contact_m": settings.size_contact,
           "step_displacement_m": entry["step_displacement_m"],
           "torque_committed_mesh_Nm": entry["step_torque_Nm"],
           "torque_this_mesh_Nm": res.torque.tolist(), "wall_s": res.wall}
    args.out.write_text(json.dumps(out) + "\n")
    return 0


def _cmd_sweep(args) -> int:
    """Many load steps at one committed position (the tangent stiffness on each side of a
    contact that closes inside the committed steps' interval): rotations spanning
    ``1 -+ span`` times the committed loaded TE at ``torque``, ``steps`` of them."""
    pair = _demo_pair()
    s0 = float(pair.mesh_cycle(args.positions)[args.index])
    ref = load_reference(args.data)
    entry = next(e for e in ref["runs"]["full"] if abs(e["s0_m"] - s0) < 1e-12)
    t = ref["torques_Nm"].index(args.torque)
    te = entry["torques"][t]["transmission_error_m"]
    steps = te * np.linspace(1.0 - args.span, 1.0 + args.span, args.steps)
    settings = _settings(args)
    fp, fg = fine_teeth(pair)
    meshes = (gear_mesh(pair.pinion, fp, settings), gear_mesh(pair.gear, fg, settings))
    res = solve_position(pair, meshes, s0, steps, settings, ccx=args.ccx, threads=args.threads)
    out = {"s0_m": s0, "index": args.index, "torque_Nm": args.torque,
           "size_contact_m": settings.size_contact, "pairs": res.pairs.tolist(),
           "step_displacement_m": res.displacement.tolist(),
           "step_torque_Nm": res.torque.tolist(), "step_pair_load_N": res.pair_load.tolist(),
           "wall_s": res.wall}
    args.out.write_text(json.dumps(out) + "\n")
    print(f"wrote {args.out} ({res.wall:.0f} s of CalculiX)")
    return 0


def _read_log(path: Path) -> list[dict]:
    return [json.loads(line) for line in Path(path).read_text().splitlines() if line.strip()]


def convergence_rows(reference: dict) -> list[str]:
    """Text rows of the convergence runs against the committed (production) mesh at the same
    position and with the same slave rule (``runs["full"]``: the corner tooth;
    ``runs["full_slave_gear"]``: the gear always): TE and stiffness at each torque and
    their change (%)."""
    prod = {rule: {round(e["s0_m"], 12): e for e in reference["runs"][run]}
            for rule, run in (("corner", "full"), ("gear", "full_slave_gear"))}
    out = ["s0 [mm]  slave   size_contact / fine / tooth / body [mm]  growth  penalty [Pa/m]  "
           + "  ".join(f"TE {T:g} [um] (d %)  k {T:g} [N/um] (d %)"
                       for T in reference["torques_Nm"])]
    for e in sorted(reference["convergence"],
                    key=lambda e: (e["s0_m"], e["slave"], -e["size_contact_m"])):
        base = prod[e["slave"]][round(e["s0_m"], 12)]
        cells = []
        for t in range(len(reference["torques_Nm"])):
            r, b = e["torques"][t], base["torques"][t]
            te, k = r["transmission_error_m"], r["mesh_stiffness_N_per_m"]
            d_te = (te / b["transmission_error_m"] - 1) * 100
            d_k = (k / b["mesh_stiffness_N_per_m"] - 1) * 100
            cells.append(f"{te * 1e6:8.3f} ({d_te:+6.2f})  {k * 1e-6:7.2f} ({d_k:+6.2f})")
        sizes = " / ".join(f"{e[k] * 1e3:g}" for k in ("size_contact_m", "size_fine_m",
                                                        "size_tooth_m", "size_body_m"))
        out.append(f"{e['s0_m'] * 1e3:7.3f}  {e['slave']:6s}  {sizes:>35}  {e['growth']:6.2f}  "
                   f"{e['penalty_Pa_per_m']:14.3g}  " + "  ".join(cells))
    return out


def plot_comparison(full: Comparison, nominal: Comparison | None = None, pair=None,
                    axes=None):
    """TE (um, top row) and mesh stiffness (N/um, bottom row) against the roll coordinate
    s0 (mm), one column per torque: CalculiX with all flanks, gearpipe, and the
    nominal-path control. ``axes``: (2, n_torques) array or None. Returns the axes."""
    import matplotlib.pyplot as plt

    n = full.torque.size
    if axes is None:
        _, axes = plt.subplots(2, n, figsize=(5.0 * n, 6.5), sharex=True, squeeze=False,
                               layout="constrained")
    x = full.s0 * 1e3
    for t, T in enumerate(full.torque):
        for row, scale, unit in ((0, 1e6, "loaded transmission error [um]"),
                                 (1, 1e-6, "mesh stiffness [N/um]")):
            ax = axes[row, t]
            pick = (lambda c: c.te_reference, lambda c: c.te_gearpipe) if row == 0 else (
                lambda c: c.k_reference, lambda c: c.k_gearpipe)
            ax.plot(x, pick[0](full)[t] * scale, "o-", color="tab:blue", ms=4,
                    label="CalculiX, all flanks")
            if nominal is not None:
                ax.plot(x, pick[0](nominal)[t] * scale, "^:", color="tab:green", ms=4,
                        label="CalculiX, nominal path only")
            ax.plot(x, pick[1](full)[t] * scale, "s--", color="tab:red", ms=4, mfc="none",
                    label="gearpipe fe2d")
            if pair is not None:
                ax.axvspan((pair.s_end - pair.base_pitch) * 1e3,
                           (pair.s_start + pair.base_pitch) * 1e3, color="0.9",
                           label="one pair on the nominal path")
            ax.set_ylabel(unit)
            ax.grid(alpha=0.3)
            if row == 0:
                ax.set_title(f"{T:g} N m")
            else:
                ax.set_xlabel("roll coordinate of the leading pair s0 [mm]")
    axes[0, 0].legend(fontsize=8, loc="upper left")
    return axes


def _cmd_compare(args) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pair = _demo_pair()
    ref = load_reference(args.data)
    full = compare(ref, gearpipe_at_reference(ref, "full"), pair, "full")
    nominal = compare(ref, gearpipe_at_reference(ref, "nominal"), pair, "nominal")
    for name, c in (("all flanks", full), ("nominal path only", nominal)):
        print(f"== CalculiX ({name}) against gearpipe fe2d (k: secant over the reference's "
              "load steps)")
        print("\n".join(c.rows()))
        for t, T in enumerate(c.torque):
            for label, te, k in (("CalculiX", c.te_reference[t], c.k_reference[t]),
                                 ("gearpipe", c.te_gearpipe[t], c.k_gearpipe[t])):
                print(f"{T:g} N m {label}: k mean {k.mean() * 1e-6:.2f} min "
                      f"{k.min() * 1e-6:.2f} max {k.max() * 1e-6:.2f} N/um, fluctuation "
                      f"(max - min) / mean {(k.max() - k.min()) / k.mean() * 100:.1f} %, TE "
                      f"mean {te.mean() * 1e6:.3f} um, peak to peak "
                      f"{(te.max() - te.min()) * 1e6:.3f} um")
    rb1 = pair.pinion.base_radius
    for t, T in enumerate(ref["torques_Nm"]):
        share = [sum(ld for ld, b in zip(e["torques"][t]["pair_load_N"],
                                          e["torques"][t]["pair_beyond_path"], strict=True)
                     if b) / (T / rb1) for e in ref["runs"]["full"]]
        print(f"{T:g} N m: load beyond the nominal path, share of P per position [%]: "
              + " ".join(f"{v * 100:.1f}" for v in share))
    print("== mesh convergence: change against the committed mesh at the same position [%]")
    print("\n".join(convergence_rows(ref)))
    if args.figure is not None:
        plot_comparison(full, nominal, pair)
        plt.savefig(args.figure, dpi=130)
        print(f"wrote {args.figure}")
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run CalculiX at mesh positions, append to a JSON-lines log")
    run.add_argument("--contact", choices=CONTACT_KINDS, default="full")
    run.add_argument("--positions", type=int, default=POSITIONS,
                     help="equally spaced positions over one mesh cycle")
    run.add_argument("--indices", type=int, nargs="*", help="only these position indices")
    run.add_argument("--torques", type=float, nargs="+", default=list(TORQUES),
                     help="driving torques, N m")
    run.add_argument("--size-contact", type=float, default=0.1,
                     help="element size on the contact flanks, mm")
    run.add_argument("--size-fine", type=float, default=None,
                     help="element size on the rest of the contacting teeth, mm")
    run.add_argument("--size-tooth", type=float, default=None,
                     help="element size on the other teeth, mm")
    run.add_argument("--size-body", type=float, default=None,
                     help="largest element size in the body, mm")
    run.add_argument("--growth", type=float, default=None, help="element size growth (-)")
    run.add_argument("--penalty", type=float, default=ReferenceSettings.penalty,
                     help="contact penalty, Pa/m")
    run.add_argument("--tip-rounding", type=float, default=0.0,
                     help="tip rounding of both gears, mm (0: sharp corners)")
    run.add_argument("--slave", choices=SLAVES, default=ReferenceSettings.slave,
                     help="which tooth of a pair carries the slave surface")
    run.add_argument("--gearbox", type=Path, default=None,
                     help="gearbox file of another external spur pair (default: the demo pair)")
    run.add_argument("--threads", type=int, default=1)
    run.add_argument("--ccx", default="ccx")
    run.add_argument("--log", type=Path, required=True)
    run.set_defaults(func=_cmd_run)
    same = sub.add_parser("same-steps", help="rerun a logged position's steps on another mesh")
    same.add_argument("--log", type=Path, required=True)
    same.add_argument("--index", type=int, required=True, help="position index in the cycle")
    same.add_argument("--positions", type=int, default=POSITIONS)
    same.add_argument("--size-contact", type=float, required=True, help="mm")
    same.add_argument("--out", type=Path, required=True)
    same.add_argument("--ccx", default="ccx")
    same.add_argument("--threads", type=int, default=1)
    same.set_defaults(func=_cmd_same_steps, size_fine=None, size_tooth=None, size_body=None,
                      growth=None, penalty=ReferenceSettings.penalty)
    swp = sub.add_parser("sweep", help="many load steps at one committed position")
    swp.add_argument("--index", type=int, required=True, help="position index in the cycle")
    swp.add_argument("--torque", type=float, required=True,
                     help="a committed torque, N m: the steps centre on its loaded TE")
    swp.add_argument("--span", type=float, default=0.1, help="relative half-span (-)")
    swp.add_argument("--steps", type=int, default=11)
    swp.add_argument("--positions", type=int, default=POSITIONS)
    swp.add_argument("--size-contact", type=float, default=0.1, help="mm")
    swp.add_argument("--data", type=Path, default=DATA)
    swp.add_argument("--out", type=Path, required=True)
    swp.add_argument("--ccx", default="ccx")
    swp.add_argument("--threads", type=int, default=1)
    swp.set_defaults(func=_cmd_sweep, size_fine=None, size_tooth=None, size_body=None,
                     growth=None, penalty=ReferenceSettings.penalty, slave=ReferenceSettings.slave)
    asm = sub.add_parser("assemble", help="merge run logs into the reference JSON")
    asm.add_argument("--note", default="", help="free text stored in the provenance")
    asm.add_argument("--full", type=Path, nargs="+", required=True)
    asm.add_argument("--nominal", type=Path, nargs="+", required=True)
    asm.add_argument("--convergence", nargs="*",
                     help="SIZE_CONTACT,SIZE_FINE,SIZE_TOOTH,SIZE_BODY (mm),GROWTH,"
                          "PENALTY (Pa/m):LOG of each study run")
    asm.add_argument("--same-steps", nargs="*", default=[],
                     help="JSON files of committed load steps rerun on another mesh")
    asm.add_argument("--positions", type=int, default=POSITIONS)
    asm.add_argument("--out", type=Path, default=DATA)
    asm.set_defaults(func=_cmd_assemble)
    asp = sub.add_parser("assemble-pair", help="write another pair's reference JSON")
    asp.add_argument("--gearbox", type=Path, required=True)
    asp.add_argument("--log", type=Path, nargs="+", required=True)
    asp.add_argument("--torques", type=float, nargs="+", required=True, help="N m")
    asp.add_argument("--positions", type=int, default=POSITIONS)
    asp.add_argument("--size-contact", type=float, default=0.1, help="mm, as run")
    asp.add_argument("--size-fine", type=float, default=None, help="mm, as run")
    asp.add_argument("--size-tooth", type=float, default=None, help="mm, as run")
    asp.add_argument("--size-body", type=float, default=None, help="mm, as run")
    asp.add_argument("--note", default="")
    asp.add_argument("--out", type=Path, required=True)
    asp.set_defaults(func=_cmd_assemble_pair, growth=None, penalty=ReferenceSettings.penalty,
                     slave=ReferenceSettings.slave)
    upd = sub.add_parser("update", help="replace a run or add convergence entries in the "
                         "reference JSON, recording the change")
    upd.add_argument("--run", choices=CONTACT_KINDS, default=None)
    upd.add_argument("--log", type=Path, nargs="*", default=[])
    upd.add_argument("--convergence", nargs="*", default=[],
                     help="size,fine,tooth,body,growth,penalty:LOG (sizes in mm)")
    upd.add_argument("--slave", choices=SLAVES, default=ReferenceSettings.slave,
                     help="the slave rule of the convergence logs")
    upd.add_argument("--sweep", type=Path, nargs="*", default=[],
                     help="JSON files of load sweeps (sweep) to add")
    upd.add_argument("--rounded", type=Path, nargs="*", default=[],
                     help="logs of a run with rounded tips (--tip-rounding)")
    upd.add_argument("--tip-rounding", type=float, default=0.0, help="mm")
    upd.add_argument("--note", default="")
    upd.add_argument("--data", type=Path, default=DATA)
    upd.set_defaults(func=_cmd_update)
    cmp_ = sub.add_parser("compare", help="gearpipe against the reference: table and figure")
    cmp_.add_argument("--data", type=Path, default=DATA)
    cmp_.add_argument("--figure", type=Path, default=None, help="PNG to write")
    cmp_.set_defaults(func=_cmd_compare)
    args = ap.parse_args(argv)
    args.argv = list(argv) if argv is not None else sys.argv[1:]
    return args.func(args)


if __name__ == "__main__":
    raise SystemExit(main())
