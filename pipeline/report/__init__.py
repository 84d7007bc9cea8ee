"""The tooth load distribution report: one self-contained HTML file per gear mesh, with
its numbers as JSON and CSV (``gearpipe report``, and the last step of ``gearpipe run``).

* :mod:`.model` - what a report holds: sections of quantities with units, figures, notes;
  :func:`~.model.format_value` prints a number the way the HTML shows it.
* :mod:`.content` - the sections from the stages' results (report units).
* :mod:`.root_section` - the root stress section (FE 2D beside ISO 6336-3).
* :mod:`.provenance` - configuration hash, code revision, versions, run time.
* :mod:`.html` - the self-contained HTML (figures as data URIs, print style sheet).
* :mod:`.writer` - :func:`write_reports`: every mesh of a run -> HTML, JSON, CSV files.
* :mod:`.commands` - ``gearpipe report CONFIG``.

The load distribution quantities themselves (line load, K_Hbeta, K_Halpha, Hertz
pressure, TE orders) are :func:`pipeline.contact.distribution.load_distribution`, the root
stress :func:`pipeline.contact.root_stress.analyse_root_stress`: a design study computes
the same numbers without writing a report.
"""

from pipeline.report.model import MeshReport, Quantity, Section, format_value
from pipeline.report.writer import write_reports

__all__ = ["MeshReport", "Quantity", "Section", "format_value", "write_reports"]
