"""roadload in Python: decode a recording's J1939 signals and analyse drives in-process with the
C++ analysis of `roadload analyze`, as pandas frames (docs/python.md).

    import roadload
    res = roadload.analyze("drive1", route="th10-sartell")
    res.cells[["cell", "crr", "crr_lo", "crr_hi"]]

`roadload.batch` runs the analysis of many recordings on Dask (`roadload batch`, docs/python.md).
"""

from . import _paths
from ._analysis import Results, analyze, read_results
from ._collect import collect
from ._decode import decode
from ._errors import Error, InputError, OutputError, UsageError, Warning

__version__ = _paths.core().version
__all__ = [
    "Error",
    "InputError",
    "OutputError",
    "Results",
    "UsageError",
    "Warning",
    "analyze",
    "collect",
    "decode",
    "read_results",
]
