"""GA encodings of column-monotone paths.

Every encoding turns a genome matrix ``X`` (N, n_var) into column profiles
(see :mod:`gapath.monotone`) with ``decode``, turns paths back into
genomes with ``encode``, and offers Ahmed & Deb's edge-fixing as ``edge_fix``.
"""

from gapath.encodings.absolute import AbsoluteEncoding
from gapath.encodings.binary import BinaryEncoding
from gapath.encodings.integer import IntegerEncoding
from gapath.encodings.mixed import MixedEncoding
from gapath.errors import ConfigError
from gapath.monotone import Frame, expand_profiles, profiles_of_paths, split_paths

#: Encoding classes by name (Ahmed & Deb's four schemes, section 2).
ENCODINGS = {
    "integer": IntegerEncoding,
    "binary": BinaryEncoding,
    "mixed": MixedEncoding,
    "absolute": AbsoluteEncoding,
}


def make_encoding(name: str, frame: Frame):
    """The encoding called ``name`` over ``frame``.

    Raises
    ------
    ConfigError
        If ``name`` is not one of :data:`ENCODINGS`.
    """
    try:
        cls = ENCODINGS[name]
    except KeyError:
        raise ConfigError(f"unknown encoding {name!r}; expected one of {', '.join(ENCODINGS)}") from None
    return cls(frame)


__all__ = [
    "ENCODINGS",
    "AbsoluteEncoding",
    "BinaryEncoding",
    "Frame",
    "IntegerEncoding",
    "MixedEncoding",
    "expand_profiles",
    "make_encoding",
    "profiles_of_paths",
    "split_paths",
]
