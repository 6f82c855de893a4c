#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Seeds for the CAN harness (fuzz_can) from the DBC: every message of dbc/sbr.dbc
encoded by cantools at its signals' minimum, middle and maximum, as the frames the
harness's unpack branch reads.

    can_seeds.py --dbc dbc/sbr.dbc --out DIR

fuzz_can takes its parameters from the input's end (libFuzzer's FuzzedDataProvider):
the branch (0: unpack), the message id's index, the DLC choice, then the eight data
bytes. A seed is those bytes in that order, reversed.
"""
import argparse
import os
import sys

import cantools

IDS = [0x300, 0x301, 0x310, 0x320]  # the harness's id table, in its order


def seed(frame_id, data):
    consumed = [0,                    # branch 0 (value % 4)
                0,                    # < 230: an sbr id from the table
                IDS.index(frame_id),  # its index (value % 4)
                0]                    # < 230: DLC 8
    consumed += list(data)
    return bytes(reversed(consumed))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dbc", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    db = cantools.database.load_file(a.dbc)
    os.makedirs(a.out, exist_ok=True)
    n = 0
    for msg in db.messages:
        if msg.frame_id not in IDS:
            continue
        for which in ("minimum", "middle", "maximum"):
            values = {}
            for s in msg.signals:
                lo = s.minimum if s.minimum is not None else 0
                hi = s.maximum if s.maximum is not None else lo
                v = {"minimum": lo, "middle": (lo + hi) / 2, "maximum": hi}[which]
                # the raw value must be a whole number of the signal's resolution
                v = round((v - s.offset) / s.scale) * s.scale + s.offset
                values[s.name] = min(max(v, lo), hi)
            data = msg.encode(values, strict=False)
            with open(os.path.join(a.out, f"dbc-{msg.name}-{which}"), "wb") as f:
                f.write(seed(msg.frame_id, data))
            n += 1
    print(f"seeds: {n} DBC frames -> {a.out}")
    return 0 if n > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
