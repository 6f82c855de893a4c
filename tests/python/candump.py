# SPDX-License-Identifier: MIT
"""Test-side reading of sbr's CAN logs, independent of the product's code: candump log
lines (`(sec.usec) ifname ID#DATA`) and the E2E CRC the DBC describes (CRC-8/SAE-J1850 over
the Data ID 0x5B00 | (id & 0xFF), low byte first, and payload bytes 1..7)."""
import re

LINE = re.compile(r"^\((\d+)\.(\d{6})\) (\S+) ([0-9A-F]{3})#([0-9A-F]{0,16})$")


def crc8_j1850(data):
    crc = 0xFF
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1D) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
    return crc ^ 0xFF


def e2e_crc(frame_id, data):
    """The CRC byte a frame of this id and payload must carry."""
    did = 0x5B00 | (frame_id & 0xFF)
    return crc8_j1850(bytes([did & 0xFF, did >> 8]) + bytes(data[1:8]))


def read_candump(path):
    """[time_us, ifname, id, bytearray] per line; every line must be a candump line."""
    out = []
    with open(path) as f:
        for raw in f:
            m = LINE.match(raw.strip())
            assert m, f"not a candump line: {raw!r}"
            out.append([int(m.group(1)) * 1000000 + int(m.group(2)), m.group(3),
                        int(m.group(4), 16), bytearray.fromhex(m.group(5))])
    return out


def write_candump(path, frames):
    with open(path, "w") as f:
        for t, ifname, fid, data in frames:
            f.write(f"({t // 1000000}.{t % 1000000:06d}) {ifname} {fid:03X}#"
                    f"{bytes(data).hex().upper()}\n")
