# SPDX-License-Identifier: MIT
"""A candump log as real buses write it (`candump -l`: `(sec.usec) ifname FRAME` lines),
read line by line without giving up on the first line it does not expect.

FRAME is one of
  - `ID#DATA`: classic CAN, ID of 3 hex digits (11-bit) or 8 (29-bit, extended), DATA up
    to 8 bytes as hex pairs (optionally separated by dots);
  - `ID#R` or `ID#Rn`: a remote frame (no data; n its DLC);
  - `ID##F DATA`: CAN FD, F the flags nibble, DATA up to 64 bytes;
  - an error frame: an 8-digit ID with the error flag 0x20000000 set.
Comment lines (`#` first), blank lines and lines that are none of these (a truncated last
line, bad hex, an odd digit count, a DLC beyond its kind's limit) are reported as skipped,
with their line number and why; the reading goes on.
"""
import re
from dataclasses import dataclass

CAN_ERR_FLAG = 0x20000000
CAN_EFF_MASK = 0x1FFFFFFF
_LINE = re.compile(r"^\((\d+(?:\.\d+)?)\)\s+(\S+)\s+(\S+)(?:\s+\S+)?\s*$")
_HEX = re.compile(r"^[0-9A-Fa-f]*$")
FD_LENGTHS = (0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64)


@dataclass
class Frame:
    """One frame of the log."""
    line: int
    timestamp: float
    channel: str
    arbitration_id: int
    data: bytes
    is_extended_id: bool = False
    is_remote_frame: bool = False
    is_error_frame: bool = False
    is_fd: bool = False


@dataclass
class Skipped:
    """A line that holds no frame: its number, why, and whether it is only a comment or a
    blank line (not a problem)."""
    line: int
    reason: str
    harmless: bool = False


def _data(text, limit):
    text = text.replace(".", "")
    if not _HEX.match(text):
        raise ValueError("data is not hexadecimal")
    if len(text) % 2:
        raise ValueError("data has an odd number of hex digits (truncated?)")
    data = bytes.fromhex(text)
    if len(data) > limit:
        raise ValueError(f"{len(data)} data bytes, more than {limit}")
    return data


def parse_frame(text):
    """(id, data, extended, remote, error, fd) of a FRAME field; ValueError with the
    reason when it is none."""
    if "#" not in text:
        raise ValueError("no '#' between identifier and data")
    ident, rest = text.split("#", 1)
    if not ident or not _HEX.match(ident) or len(ident) not in (3, 8):
        raise ValueError(f"identifier '{ident}' is not 3 or 8 hex digits")
    fid = int(ident, 16)
    extended = len(ident) == 8
    if extended and fid & CAN_ERR_FLAG:
        return fid & CAN_EFF_MASK, _data(rest, 8), True, False, True, False
    if extended and fid > CAN_EFF_MASK:
        raise ValueError(f"identifier 0x{fid:X} beyond 29 bits")
    if not extended and fid > 0x7FF:
        raise ValueError(f"identifier 0x{fid:X} beyond 11 bits")
    if rest.startswith("#"):  # CAN FD: flags nibble, then data
        if len(rest) < 2 or not _HEX.match(rest[1]):
            raise ValueError("CAN FD frame without its flags digit")
        data = _data(rest[2:], 64)
        if len(data) not in FD_LENGTHS:
            raise ValueError(f"{len(data)} bytes is no CAN FD length")
        return fid, data, extended, False, False, True
    if rest[:1] in ("R", "r"):
        dlc = rest[1:]
        if dlc and (not dlc.isdigit() or int(dlc) > 8):
            raise ValueError(f"remote frame DLC '{dlc}' is not 0..8")
        return fid, b"", extended, True, False, False
    return fid, _data(rest, 8), extended, False, False, False


def read_log(lines):
    """Frames and Skipped entries of an iterable of text lines (a file), in order."""
    for n, raw in enumerate(lines, 1):
        line = raw.rstrip("\r\n")
        stripped = line.strip()
        if not stripped:
            yield Skipped(n, "blank line", True)
            continue
        if stripped.startswith("#"):
            yield Skipped(n, "comment", True)
            continue
        m = _LINE.match(stripped)
        if not m:
            yield Skipped(n, "not '(time) interface frame' (truncated or malformed)")
            continue
        try:
            fid, data, ext, remote, error, fd = parse_frame(m.group(3))
        except ValueError as e:
            yield Skipped(n, str(e))
            continue
        yield Frame(n, float(m.group(1)), m.group(2), fid, data, ext, remote, error, fd)


def open_log(path):
    """The log's lines as text (bytes that are not UTF-8 become replacement characters,
    so such a line is skipped, not the file refused)."""
    return open(path, "r", encoding="utf-8", errors="replace", newline="")
