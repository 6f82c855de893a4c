# SPDX-License-Identifier: MIT
"""sbr.can: the CAN messages of dbc/sbr.dbc, packed and unpacked by the core
(include/sbr/can.h), with its end-to-end protection (CRC-8/SAE-J1850 over the Data ID and
payload, alive counter 0..14).

    from sbr import can
    frame_id, data = can.pack("SBR_Detection", class_id=1, confidence=90.0, center_x=612.0,
                              center_y=410.0, width=32.0, height=32.0, track_id=3)
    tx = can.Sender(); data = tx.protect(frame_id, data)      # counter + CRC
    rx = can.Receiver(frame_id); rx.check(data)                # "first", then "ok"
    name, values = can.unpack(frame_id, data)

Values outside a signal's range raise ValueError (never clamped); a frame that fails its
E2E check raises E2EError with the check's result ("wrong_crc", "repeated", ...).
"""
from typing import Dict, Tuple

from . import _sbr

__all__ = ["MESSAGES", "pack", "unpack", "crc8", "Sender", "Receiver", "E2EError", "E2E_RESULTS"]

#: message name -> (frame id, signal names in the core's order)
MESSAGES: Dict[str, Tuple[int, Tuple[str, ...]]] = {
    name: (int(fid), tuple(fields)) for name, (fid, fields) in _sbr.can_messages().items()}
#: sbr_can_e2e_result_t by value
E2E_RESULTS = ("ok", "first", "wrong_id", "wrong_length", "wrong_crc", "bad_counter", "repeated", "skipped")


class E2EError(ValueError):
    """A received frame failed its end-to-end check; `result` says how (E2E_RESULTS)."""

    def __init__(self, result: str, frame_id: int):
        super().__init__(f"frame 0x{frame_id:03X}: E2E check failed: {result}")
        self.result = result
        self.frame_id = frame_id


def pack(name: str, **values) -> Tuple[int, bytes]:
    """(frame id, 8 data bytes) of message `name` with every signal of MESSAGES[name] given
    as a keyword (physical values: %, px, px/s, ms); the E2E bytes (CRC, counter) are 0
    until Sender.protect()."""
    fid, data = _sbr.can_pack(str(name), values)
    return int(fid), bytes(data)


def unpack(frame_id: int, data: bytes) -> Tuple[str, Dict[str, float]]:
    """(message name, signal values) of a frame. The E2E check is the Receiver's job:
    unpack only refuses frames whose signals are outside their ranges."""
    name, values = _sbr.can_unpack(int(frame_id), bytes(data))
    return str(name), dict(values)


def crc8(data: bytes) -> int:
    """CRC-8/SAE-J1850 (0x1D, init 0xFF, xorout 0xFF) of `data`."""
    return int(_sbr.crc8_j1850(bytes(data)))


class Sender:
    """E2E sender state: each protect() writes the message's next alive counter and the CRC."""

    def __init__(self):
        self._core = _sbr.E2ESender()

    def protect(self, frame_id: int, data: bytes) -> bytes:
        return bytes(self._core.protect(int(frame_id), bytes(data)))


class Receiver:
    """E2E receiver state of one message: check() returns "first" or "ok" for a valid frame
    and raises E2EError otherwise (a repeated frame leaves the state as it was; after a
    skipped counter the state follows the new one)."""

    def __init__(self, frame_id: int):
        self._core = _sbr.E2EReceiver(int(frame_id))

    @property
    def frame_id(self) -> int:
        return int(self._core.frame_id)

    def check(self, data: bytes, frame_id=None) -> str:
        fid = self.frame_id if frame_id is None else int(frame_id)
        r = E2E_RESULTS[self._core.check(fid, bytes(data))]
        if r not in ("ok", "first"):
            raise E2EError(r, fid)
        return r
