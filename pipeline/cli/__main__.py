"""``python -m pipeline.cli``: the ``gearpipe`` command line (:func:`pipeline.cli.main`)."""

import sys

from pipeline.cli import main

sys.exit(main())
