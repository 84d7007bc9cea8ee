"""Write the committed table of the rounded-tip tangency correction.

``python workflows/tangency_table.py`` computes ``Phi(q, xi)`` on the grids of
:mod:`pipeline.contact.tangency` (about 30 s) and writes
``pipeline/contact/tangency_table.npz``; the tests recompute entries of it and compare.
"""

from __future__ import annotations

import sys

import numpy as np

from pipeline.contact.tangency import T_ROUNDING, TABLE, XI_INVOLUTE, Q, compute_table


def main() -> int:
    np.savez(TABLE, q=Q, xi_involute=XI_INVOLUTE, t_rounding=T_ROUNDING, phi=compute_table())
    print(f"wrote {TABLE}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
