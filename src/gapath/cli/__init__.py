"""The ``gapath`` command line: every argparse line of gapath lives here.

* :mod:`gapath.cli.main` -- the parser, ``solve`` and ``demo``, dispatch and
  the exit statuses (:func:`main`, the ``gapath`` entry point);
* :mod:`gapath.cli._args` -- the arguments several commands share (map,
  start/goal, ``--scen``, world coordinates, the corner rule);
* one module per command: :mod:`~gapath.cli.exact`, :mod:`~gapath.cli.plan`,
  :mod:`~gapath.cli.scen`, :mod:`~gapath.cli.simulate`,
  :mod:`~gapath.cli.experiment`. Each defines ``register(subparsers)``, which
  adds its parser and sets ``func`` (``run(args) -> int``).
"""

from gapath.cli.main import main

__all__ = ["main"]
