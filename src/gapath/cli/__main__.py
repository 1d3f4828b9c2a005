"""``python -m gapath.cli``: the ``gapath`` command."""

import sys

from gapath.cli.main import main

sys.exit(main())
