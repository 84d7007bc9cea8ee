"""Input files -> frozen stage inputs (SI): one gearbox description, one units table.

* :mod:`.units` - the unit suffixes of keys (mm, um, deg, rpm, N m, GPa, ...), defined once.
* :mod:`.toml_file` - reading a file: encoding, BOM, binary data, syntax, nesting.
* :mod:`.schema` - strict tables: known keys, checked types, errors in the file's terms.
* :mod:`.tables` - every table and key of a gearbox file.
* :mod:`.gearbox` - the file -> :class:`Gearbox` (pair, planetary set, one gear).
* :mod:`.lumped` - ``[lumped_model]``: a published lumped model given by parameters.
"""

from pipeline.config.gearbox import (
    Carrier,
    Gearbox,
    gearbox_from_dict,
    gearbox_from_text,
    load_gearbox,
)
from pipeline.config.units import UNITS, Unit, unit_of_key
from pipeline.validation import InputError

__all__ = ["Carrier", "Gearbox", "InputError", "UNITS", "Unit", "gearbox_from_dict",
           "gearbox_from_text", "load_gearbox", "unit_of_key"]
