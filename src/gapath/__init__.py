"""gapath: multi-objective path planning on grids for pymoo."""

from gapath.errors import ConfigError, GapathError, MapError, NoPathError
from gapath.generators import default_workspace, dense_workspace, random_workspace
from gapath.workspace import Workspace

__version__ = "0.2.0.dev0"

__all__ = [
    "ConfigError",
    "GapathError",
    "MapError",
    "NoPathError",
    "Workspace",
    "default_workspace",
    "dense_workspace",
    "random_workspace",
    "__version__",
]
