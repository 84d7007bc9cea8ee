"""The tooth load distribution report: one self-contained HTML file per gear mesh, with
its numbers as JSON and CSV (``gearpipe report``, and the last step of ``gearpipe run``).

* :mod:`.model` - what a report holds: sections of quantities with units, figures, notes;
  :func:`~.model.format_value` prints a number the way the HTML shows it.
* :mod:`.content` - the sections from the stages' results (report units).
* :mod:`.root_section` - the root stress section (FE 2D beside ISO 6336-3).
* :mod:`.provenance` - configuration hash, code revision, versions, run time.
* :mod:`.html` - the self-contained HTML (figures as data URIs, print style sheet).
* :mod:`.writer` - :func:`write_reports`: every mesh of a run -> HTML, JSON, CSV files.
* the command ``gearpipe report CONFIG`` is :mod:`pipeline.cli.report`.

The load distribution quantities themselves (line load, K_Hbeta, tooth-pair unit load ratio,
Hertz pressure, TE orders) are :func:`pipeline.contact.distribution.load_distribution`, the
root stress :func:`pipeline.contact.root_stress.analyse_root_stress`: a design study
computes the same numbers without writing a report.

The HTML embeds its figures as data URIs and has no script or remote resource, with a print
style sheet (Chromium prints the small test case to 10 A4 pages); every number in it
carries the JSON path of its value (``data-key``), and a test checks each shown number
against the JSON. ``tests/test_report_render.py`` (slow) renders the report in headless
Chromium, which ``./dev.sh chromium`` installs from Debian when missing.

Measured through ``gearpipe report`` (one run each, 2 cores shared, load average 6):

* The demo's pair (z 50/50, FE 2D contact, 60 positions): root stress 184.1 / 184.5 MPa
  (pinion / gear) against ISO's 190.2 MPa (-3.3 / -3.0 %), the maximum with the tooth's own
  contact at 150.65 mm, ISO's outer point of single contact at 150.76 mm; Hertz 824 MPa, TE
  5.25 um = 74.5 urad p-p, tooth-pair unit load ratio 1.22. With a 10 um slope deviation (30
  slices, linear local contact): K_Hbeta 1.3947, the N-slice closed form with the stiffness
  stage's k(t) to 1e-6, against ISO 6336-1's continuous 1.4083 (the 1/N of the outer slice
  centre); with Weber's local contact 1.3556, line load 337 N/mm against 241 N/mm mean, p_H
  912 MPa against 824 MPa aligned.
* The helical traction pair of Yang et al. (2026) (analytical slices, 40 positions, 30
  slices): perfect flanks K_Hbeta 1.0085 (1.0040 at 80 positions: the sampling of the
  cycle), tooth-pair unit load ratio 1.18, p_H 570 MPa, root stress 25 / 32 % below ISO
  (eps_alpha 2.05: two or three pairs always share the load that ISO puts on one tooth, with
  Y_DT = 1); with a 15 um slope deviation K_Hbeta 1.32, line load 744 N/mm against 432 N/mm
  mean, p_H 653 MPa, pinion root stress 3 % below ISO.
* The wind-turbine planetary set of Xu et al. (2020) (one helical half, analytical slices):
  two reports; sun-planet K_Hbeta 1.03, p_H 833 MPa, root stress sun 137 MPa (+13 % to
  ISO), planet 122 MPa (+5 %); planet-ring p_H 373 MPa, planet 99.7 MPa (-2.4 %), ring 95.4
  MPa.

Cost: ``gearpipe run`` has the report figures drawn with its other figures, side by side
in the drawing pool (:func:`~pipeline.report.writer.prepare_reports`,
:mod:`pipeline.viz.figure_queue`), and its report step then writes the files only:
0.03-0.11 s for the demo's pair on 2 cores at load average up to 4 (its FE stress tables
are the run's load distribution step).
"""

from pipeline.report.model import MeshReport, Quantity, Section, format_value
from pipeline.report.writer import write_reports

__all__ = ["MeshReport", "Quantity", "Section", "format_value", "write_reports"]
