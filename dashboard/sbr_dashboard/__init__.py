# SPDX-License-Identifier: MIT
"""sbr's reference dashboard: a consumer of sbr's CAN traffic that knows only the DBC.

Everything it knows of the messages (identifiers, layouts, ranges, value names, cycle
times, the E2E Data IDs, the CRC and the alive counter) is read from the DBC file at start;
see dbc.py. Inputs: SocketCAN, a candump log (recorded speed or as fast as possible), or
python-can's virtual bus (sources.py). Checks and state: monitor.py. Views: web.py (a page
updated by server-sent events) and terminal.py.
"""
__version__ = "1.0.0"
