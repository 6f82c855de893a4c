# SPDX-License-Identifier: MIT
"""What the dashboard learns from the DBC, and nothing else.

Per message: identifier, name, cycle time (attribute GenMsgCycleTime), E2E Data ID
(attribute SBR_E2E_DataID), the CRC signal (8 bits at bit 0, its comment names a CRC) and
the alive-counter signal (its comment names an alive counter; the counter wraps after the
signal's maximum). The CRC algorithm is read from the database comment ("polynomial 0x..,
init 0x.., final XOR 0x..; check 0x.." over "the 16-bit Data ID (low byte, high byte) and
bytes 1..7"); the check value is verified at load, so a DBC describing a different CRC is
refused instead of producing false E2E errors.
"""
import re
import warnings
from dataclasses import dataclass, field

import functools

import cantools


class DbcError(Exception):
    """The DBC cannot be used (does not load strictly, or its E2E description is unknown)."""


@functools.lru_cache(maxsize=None)
def _crc8_table(poly):
    """The byte-at-a-time table of the MSB-first CRC-8 with this polynomial (the same
    results as shifting bit by bit, eight times faster in Python)."""
    table = []
    for byte in range(256):
        crc = byte
        for _ in range(8):
            crc = ((crc << 1) ^ poly) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
        table.append(crc)
    return tuple(table)


@dataclass(frozen=True)
class Crc8:
    poly: int
    init: int
    xorout: int

    def __call__(self, data):
        table = _crc8_table(self.poly)
        crc = self.init
        for b in data:
            crc = table[crc ^ b]
        return crc ^ self.xorout


@dataclass
class MessageSpec:
    frame_id: int
    name: str
    length: int
    cycle_ms: int
    data_id: int
    crc_signal: str
    counter_signal: str
    counter_start: int
    counter_length: int
    counter_max: int
    message: object = field(repr=False)  # the cantools message

    def crc_input(self, data):
        """The bytes the E2E CRC covers: the Data ID (low byte, high byte), then bytes 1..7."""
        return bytes([self.data_id & 0xFF, self.data_id >> 8]) + bytes(data[1:])


_CRC_RE = re.compile(r"polynomial 0x([0-9A-Fa-f]{1,2}), init 0x([0-9A-Fa-f]{1,2}), "
                     r"final XOR 0x([0-9A-Fa-f]{1,2}); check 0x([0-9A-Fa-f]{1,2})")


class DbcModel:
    def __init__(self, path):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                self.db = cantools.database.load_file(path, strict=True)
        except Exception as e:  # cantools raises several types; all mean "unusable"
            raise DbcError(f"{path}: {e}") from e
        comment = " ".join(b.comment or "" for b in self.db.buses)
        m = _CRC_RE.search(comment)
        if not m or "(low byte, high byte)" not in comment or "bytes 1..7" not in comment:
            raise DbcError("the DBC does not describe its E2E CRC in a form this dashboard knows")
        poly, init, xorout, check = (int(g, 16) for g in m.groups())
        self.crc = Crc8(poly, init, xorout)
        if self.crc(b"123456789") != check:
            raise DbcError(f"the DBC's CRC parameters do not give its check value 0x{check:02X}")
        self.messages = {}
        for msg in self.db.messages:
            attrs = msg.dbc.attributes if msg.dbc else {}
            if "SBR_E2E_DataID" not in attrs:
                raise DbcError(f"{msg.name}: no SBR_E2E_DataID attribute")
            crc = [s for s in msg.signals
                   if s.start == 0 and s.length == 8 and "CRC" in (s.comment or "")]
            cnt = [s for s in msg.signals if "alive counter" in (s.comment or "")]
            if len(crc) != 1 or len(cnt) != 1:
                raise DbcError(f"{msg.name}: no unique CRC and alive-counter signals")
            cycle = msg.cycle_time
            if not cycle or cycle <= 0:
                raise DbcError(f"{msg.name}: no GenMsgCycleTime")
            self.messages[msg.frame_id] = MessageSpec(
                frame_id=msg.frame_id, name=msg.name, length=msg.length, cycle_ms=int(cycle),
                data_id=int(attrs["SBR_E2E_DataID"].value), crc_signal=crc[0].name,
                counter_signal=cnt[0].name, counter_start=cnt[0].start,
                counter_length=cnt[0].length, counter_max=int(cnt[0].maximum), message=msg)

    def by_name(self, name):
        for spec in self.messages.values():
            if spec.name == name:
                return spec
        raise KeyError(name)

    def choice_name(self, frame_id, signal, value):
        """The DBC's value name of a raw signal value, or None."""
        sig = self.messages[frame_id].message.get_signal_by_name(signal)
        if sig.choices and int(value) in sig.choices:
            return str(sig.choices[int(value)])
        return None

    def choices(self, frame_id, signal):
        sig = self.messages[frame_id].message.get_signal_by_name(signal)
        return {int(k): str(v) for k, v in (sig.choices or {}).items()}

    def protect(self, frame_id, data):
        """Sender-side E2E of a payload (used by tests and fault injection): the CRC byte
        recomputed over the Data ID and bytes 1..7."""
        body = bytes(data[:8])
        return bytes([self.crc(self.messages[frame_id].crc_input(body))]) + body[1:]
