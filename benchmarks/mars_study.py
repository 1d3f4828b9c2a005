"""Lavin's Mars rover study (D*-PO paper, Table I), rerun with gapath.

100 random 100x100 workspaces (obstacles of three sizes covering ~23 %,
Mars DTM elevation windows tiled with reflection, a random risk cell, the
solar vector turning 1 rad per step); A* and D* (weighted sums), D*-PO and
the GA front (paper_nsga2, pop 100 x 150 generations). Writes
docs/results/mars.md and mars.csv and prints one JSON line per workspace,
per table row and for the statistics (see gapath.studies.mars).

Usage::

    python benchmarks/mars_study.py [--quick] [--n N] [--ga-pop P] [--ga-gen G]
                                    [--out DIR] [--jsonl FILE]

``--quick``: 5 workspaces and a small GA (a smoke test, ~1 min), written to
gapath-mars-quick/ unless --out is given. The same study runs as
``gapath experiment mars``.
"""

from __future__ import annotations

import argparse
import sys

from gapath.cli.studies.mars import add_arguments, run


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_arguments(parser)
    args = parser.parse_args(argv)
    if args.out is None and not args.quick:  # this script refreshes the committed results
        args.out = "docs/results"
    return run(args)


if __name__ == "__main__":
    sys.exit(main())
