"""The C++'s exit status and messages as exceptions. Each carries the messages the command would
have printed ("recording/can.log:12: id: not hexadecimal"), its exit status and, where the
input was read in part (status 65), what was made of the rest."""

import warnings


class Error(Exception):
    """A roadload call that failed. `status`: the command's exit status (sysexits); `messages`:
    its lines without the "roadload COMMAND: " prefix; `result`: what was made all the same."""

    def __init__(self, message, status, messages=(), result=None):
        super().__init__(message)
        self.status = status
        self.messages = list(messages)
        self.result = result

    def __reduce__(self):
        # Across processes (a Dask task's failure): the message, status and messages, not the
        # frames made all the same.
        return (type(self), (str(self), self.status, self.messages))


class UsageError(Error, ValueError):
    """An option the command refuses (64): an unknown keyword, a value out of its range."""


class InputError(Error):
    """Input that could not be read (66: no such recording, route or vehicle) or was malformed
    (65: a bad line or field; the rest was read, and `result` holds what was made of it)."""


class OutputError(Error, OSError):
    """An output that could not be written (73)."""


class Warning(UserWarning):  # noqa: A001 (roadload.Warning, as warnings name their category)
    """What the analysis said of a drive it analysed: an assumed vehicle, a sensor upside down."""


_KINDS = {64: UsageError, 65: InputError, 66: InputError, 73: OutputError}


def check(command, status, messages, result=None):
    """Raises the error for a non-zero status; otherwise warns each message and returns."""
    if status != 0:
        text = "\n".join(messages) if messages else "roadload %s: exit status %d" % (command, status)
        raise _KINDS.get(status, Error)(text, status, messages, result)
    for m in messages:
        warnings.warn("roadload %s: %s" % (command, m), Warning, stacklevel=3)
