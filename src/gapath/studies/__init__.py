"""The paper studies: gapath's reproductions of the papers' experiments.

* :mod:`gapath.studies.encodings` -- Ahmed & Deb's encoding comparison
  (Fig. 3 set-up);
* :mod:`gapath.studies.dense` -- Ahmed & Deb's dense obstacles (Table 1),
  grids of runs on :mod:`gapath.experiments`' runner and store;
* :mod:`gapath.studies.mars` -- Lavin's Mars rover study (Table I);
* :mod:`gapath.studies.dynamic` -- NO-MOPP's dynamic environments (its
  Tables I-IV).

Each study has a library entry point ``run(...)`` that computes the study
and returns its result, and writers of its tables and figures; the
``gapath experiment <study>`` sub-commands (:mod:`gapath.cli.studies`) are
thin wrappers over them. The studies are imported on first use
(``from gapath.studies import dense``), so ``import gapath.studies`` stays
light.
"""
