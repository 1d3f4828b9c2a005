"""Sub-commands of the ``gapath`` CLI beyond ``solve`` and ``demo``.

Each module listed in :data:`MODULES` defines ``register(subparsers)``, which
adds its parser(s) and sets ``func=run`` (a callable ``run(args) -> int``)
with ``parser.set_defaults``. Errors derived from
:class:`gapath.errors.GapathError` are printed by the CLI and exit with 2.
"""

import importlib

#: Modules that add sub-commands, in help order.
MODULES: list[str] = [
    "gapath.commands.exact",
    "gapath.commands.experiment",
    "gapath.commands.dynamic",
    "gapath.commands.plan",
    "gapath.commands.scen",
]


def register_all(subparsers) -> None:
    for name in MODULES:
        importlib.import_module(name).register(subparsers)
