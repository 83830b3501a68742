"""roadload.decode: a recording's J1939 signals as a pandas frame, as `roadload decode` prints
them one message a line."""

import os

import numpy as np
import pandas as pd

from . import _errors, _paths


def _categorical(codes, names):
    return pd.Categorical.from_codes(codes, categories=pd.Index(names, dtype=object))


def decode(recording, *, pgn=None, dbc=None):
    """The J1939 signals of `recording` (a recording folder, a candump -L log, or a list of one
    drive's segments) as a long frame: one row per signal of every message the definitions know
    (the built-in ones, then each file of `dbc` over them), in capture order; only the PGNs in
    `pgn` (an int or a list) when given. Transport-protocol messages are reassembled first.

    Columns: t_s (the capture clock in seconds, as decode prints it), t_ns (the same, exact),
    iface, sa (source address), pgn, message (its name in the definitions), signal, value
    (NaN unless state is "valid"), unit, state ("valid", "not_available", "error", ...).
    Signals beyond a message's payload are left out, as decode leaves them out.

    A malformed line raises InputError naming file, line and field, with the frame of everything
    else in its `result`."""
    inputs = [recording] if isinstance(recording, (str, os.PathLike)) else list(recording)
    pgns = [] if pgn is None else [pgn] if isinstance(pgn, int) else list(pgn)
    dbcs = [] if dbc is None else [dbc] if isinstance(dbc, (str, os.PathLike)) else list(dbc)
    status, messages, c, names = _paths.core().decode(
        [os.fspath(i) for i in inputs], [os.fspath(d) for d in dbcs], [int(p) for p in pgns]
    )
    units = pd.Index(sorted(set(names["unit"])), dtype=object)
    unit_of_signal = units.get_indexer(names["unit"]).astype(np.int32)
    frame = pd.DataFrame(
        {
            "t_s": c["t_ns"] / 1e9,
            "t_ns": c["t_ns"],
            "iface": _categorical(c["iface"], names["iface"]),
            "sa": c["sa"],
            "pgn": c["pgn"],
            "message": _categorical(c["message"], names["message"]),
            "signal": _categorical(c["signal"], names["signal"]),
            "value": c["value"],
            "unit": _categorical(unit_of_signal[c["signal"]], list(units)),
            "state": _categorical(c["state"], names["state"]),
        }
    )
    _errors.check("decode", status, messages, frame)
    return frame
