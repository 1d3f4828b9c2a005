"""``gapath experiment`` sub-commands of the paper studies (Ahmed & Deb's
encodings and dense obstacles, Lavin's Mars rover study, NO-MOPP's dynamic
environments): the arguments and handlers over the library entry points
``run()`` of :mod:`gapath.studies`, which stays argparse-free."""
