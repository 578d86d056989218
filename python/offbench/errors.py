"""The package's exceptions: one base class, offbench.Error, and one
subclass per kind of failure (the C library's obx_code, plus what Python
itself checks).  Each also derives from the built-in exception a Python
caller would expect (ValueError for a bad argument, OSError for a file that
cannot be read, ...), so `except ValueError` works as well as
`except offbench.Error`.  The message is the library's own: it names the
file and line, or the option, that was wrong.
"""

from typing import Optional

# obx_code values of include/offbench.h
OBX_OK = 0
OBX_E_INVALID = 1
OBX_E_PARSE = 2
OBX_E_IO = 3
OBX_E_NOMEM = 4
OBX_E_UNSUPPORTED = 5
OBX_E_MEASURE = 6
OBX_E_STOPPED = 7


class Error(Exception):
    """Anything offbench refuses or cannot do.  .code is the C library's
    obx_code (0 where Python found the problem itself), .message the text."""

    code = 0

    def __init__(self, message: str, code: Optional[int] = None) -> None:
        super().__init__(message)
        self.message = message
        if code is not None:
            self.code = code

    def __str__(self) -> str:
        return self.message


class InvalidError(Error, ValueError):
    """A bad argument: unknown method, metric, split, curve or parameter;
    a tolerance or d that is NaN, 0 or out of range; arrays of the wrong
    shape."""

    code = OBX_E_INVALID


class UnknownCurveError(InvalidError, KeyError):
    """A curve id that is not in the set (also a KeyError, as a mapping's
    missing key is)."""

    def __str__(self) -> str:  # KeyError would print the message's repr
        return self.message


class InvalidTypeError(InvalidError, TypeError):
    """An argument or field of the wrong type (a Curve's index that is not
    a whole number)."""


class CurveIndexError(InvalidError, IndexError):
    """A curve index outside its set."""


class ParseError(Error, ValueError):
    """A curve file, results.csv or meta.json that is not valid: the
    message starts with FILE:LINE."""

    code = OBX_E_PARSE


class FileError(Error, OSError):
    """A file that cannot be read: the message starts with its path."""

    code = OBX_E_IO


class OutOfMemoryError(Error, MemoryError):
    code = OBX_E_NOMEM


class UnsupportedError(Error):
    """Valid, but not available here (the method sisl without its server
    program)."""

    code = OBX_E_UNSUPPORTED


class MeasureError(Error):
    """An approximation that cannot be measured: a piece whose ends cannot
    be matched on the exact offset ("piece K: reason")."""

    code = OBX_E_MEASURE


class StoppedError(Error):
    """A batch its progress callback stopped (run re-raises the callback's
    own exception instead)."""

    code = OBX_E_STOPPED


class LibraryNotFound(Error, ImportError):
    """liboffbench.so.0 could not be found or loaded, or is too old: the
    message lists where it was looked for and what to do."""


_BY_CODE = {
    OBX_E_INVALID: InvalidError,
    OBX_E_PARSE: ParseError,
    OBX_E_IO: FileError,
    OBX_E_NOMEM: OutOfMemoryError,
    OBX_E_UNSUPPORTED: UnsupportedError,
    OBX_E_MEASURE: MeasureError,
    OBX_E_STOPPED: StoppedError,
}


def from_code(code: int, message: str) -> Error:
    """The exception for an obx_error the library filled."""
    return _BY_CODE.get(code, Error)(message, code)
