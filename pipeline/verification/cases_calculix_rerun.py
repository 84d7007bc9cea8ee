"""Rerun the independent CalculiX contact model where it is checked: the committed reference
data are reproducible with the CalculiX installed here.

Two positions of the reference's coarse convergence mesh (0.2 mm on the contact flanks)
where a tip corner carries about a third of the load (the pinion's, position 19; the
gear's, position 23), rerun at the committed load steps with the same mesh and deck: the
driving torques must equal the committed ones. The reference model is the workflow script
``workflows/reference/calculix_spur_contact.py`` (not part of the package: it is the
independent model), loaded from the context's reference folder; CalculiX is the ``ccx``
on the path (Debian: ``apt-get install calculix-ccx``).
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path
from types import ModuleType

import numpy as np

from pipeline.verification.cases_calculix import load_reference
from pipeline.verification.context import Context, checkout_script
from pipeline.verification.model import Outcome, Quantity

SCRIPT = "calculix_spur_contact.py"
COARSE_SIZE_M = 0.2e-3
TORQUE_TOLERANCE = 1e-6
"""Relative: same mesh, same deck, same load steps; what remains is the solver's round-off
and the digits CalculiX prints."""


def _reference_model(context: Context) -> ModuleType:
    """The reference script as a module (registered under a private name, as an import
    would, so that its dataclasses resolve their module)."""
    return checkout_script(Path(context.reference_dir) / SCRIPT, "_gearpipe_calculix_reference",
                           "workflows/reference/")


def case_calculix_rerun(context: Context, ccx: str = "ccx") -> Outcome:
    """The two coarse-mesh corner positions rerun: torques at the committed steps."""
    from pipeline.config.gearbox import gearbox_from_text
    from pipeline.verification.cases_calculix import DEMO_PAIR_TEXT

    if shutil.which(ccx) is None:
        raise FileNotFoundError(f"CalculiX ({ccx}) is not installed: apt-get install "
                                "calculix-ccx")
    ref = _reference_model(context)
    reference = load_reference(context)
    coarse = [e for e in reference["convergence"]
              if math.isclose(e["size_contact_m"], COARSE_SIZE_M) and e["slave"] == "corner"
              and e["penalty_Pa_per_m"] == ref.ReferenceSettings.penalty]
    if len(coarse) != 2:
        raise ValueError(f"the reference holds {len(coarse)} coarse corner positions, not 2")
    pair = gearbox_from_text(DEMO_PAIR_TEXT, name="reference").pair
    settings = ref.ReferenceSettings(size_contact=COARSE_SIZE_M, slave="corner")
    fine_p, fine_g = ref.fine_teeth(pair)
    meshes = (ref.gear_mesh(pair.pinion, fine_p, settings),
              ref.gear_mesh(pair.gear, fine_g, settings))
    cycle = np.array(reference["positions_m"])
    q = []
    for e in coarse:
        res = ref.solve_position(pair, meshes, e["s0_m"], np.array(e["step_displacement_m"]),
                                 settings)
        index = int(np.abs(cycle - e["s0_m"]).argmin())
        for i, (d, t_ref, t) in enumerate(zip(e["step_displacement_m"], e["step_torque_Nm"],
                                              res.torque, strict=True)):
            q.append(Quantity(f"driving torque, position {index} of {cycle.size}, step {i + 1} "
                              f"(rotation {d * 1e6:.3f} um on the base circle)", "N m", t_ref,
                              t, "relative", TORQUE_TOLERANCE,
                              "same mesh, deck and load steps: the solver's round-off and "
                              "the digits CalculiX prints"))
    inputs = (("pair", "demo pair: z 50/50, m 3 mm, 20 deg, b 20 mm, frictionless"),
              ("mesh", f"{COARSE_SIZE_M * 1e3:g} mm on the contact flanks, "
                       f"{len(meshes[0].nodes)} / {len(meshes[1].nodes)} nodes"),
              ("positions", ", ".join(str(int(np.abs(cycle - e["s0_m"]).argmin()))
                                      for e in coarse) + " (a tip corner carries about a third "
                                                         "of the load)"),
              ("CalculiX", f"{ref.ccx_version(ccx)} (committed: "
                           f"{reference['provenance']['calculix_version']})"))
    return Outcome(f"independent CalculiX model, workflows/reference/{SCRIPT}, rerun against "
                   "its committed convergence data", inputs, tuple(q))
