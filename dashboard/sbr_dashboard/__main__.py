# SPDX-License-Identifier: MIT
"""sbr dashboard: a live view of sbr's CAN traffic, decoded with the DBC alone.

  sbr-dashboard --log FILE [--fast | --rate R]    replay a candump log
  sbr-dashboard --socketcan IFACE                 a live SocketCAN interface
  sbr-dashboard --virtual CHANNEL [--feed-log F]  python-can's virtual bus
(the console script of the package in dashboard/, pyproject.toml; python -m sbr_dashboard
does the same)
options: --dbc FILE (default: dbc/sbr.dbc, installed with the package), --terminal (no web page), --host, --port,
         --timeout-factor F (default 3), --wait-client (start the input only once a page
         is connected, so that it sees the whole replay), --exit-after-end S (stop S seconds after a log
         ended; default: keep serving), --once (terminal: print one screen when the log
         ended, then exit)
"""
import argparse
import os
import math
import signal
import sys
import threading
import time

from .dbc import DbcError, DbcModel
from .monitor import Monitor
from .sources import BusSource, LogSource, SourceError, feed_log_to_bus
from .terminal import HOME_CLEAR, render, terminal_width

# The project's DBC, shipped inside the package (sbr_dashboard/sbr.dbc, a link to
# dbc/sbr.dbc in the checkout that the wheel holds as a file).
DEFAULT_DBC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "sbr.dbc")


def main(argv=None):
    ap = argparse.ArgumentParser(prog="sbr-dashboard", description=__doc__.split("\n")[0])
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("--log", metavar="FILE", help="candump log to replay")
    src.add_argument("--socketcan", metavar="IFACE", help="live SocketCAN interface, e.g. can0")
    src.add_argument("--virtual", metavar="CHANNEL", help="python-can virtual bus channel")
    ap.add_argument("--feed-log", metavar="FILE", help="with --virtual: play this candump log onto the bus")
    ap.add_argument("--fast", action="store_true", help="replay the log as fast as possible")
    ap.add_argument("--rate", type=float, default=1.0, help="replay speed factor (default 1: the log's own timing)")
    ap.add_argument("--dbc", default=DEFAULT_DBC, help="the DBC that describes the messages (default: the project DBC, installed with the package)")
    ap.add_argument("--terminal", action="store_true",
                    help="terminal view instead of the page, laid out to the terminal's width")
    ap.add_argument("--once", action="store_true",
                    help="with --terminal: print one screen when the log has ended, then exit")
    ap.add_argument("--host", default="127.0.0.1", help="address the page is served on (default 127.0.0.1)")
    ap.add_argument("--port", type=int, default=8080, help="port of the page (default 8080; 0: any free port)")
    ap.add_argument("--timeout-factor", type=float, default=3.0, metavar="F",
                    help="a message times out after F times its GenMsgCycleTime without a frame (default 3)")
    ap.add_argument("--exit-after-end", type=float, default=None, metavar="S",
                    help="stop S seconds after a log has ended (default: keep serving the page)")
    ap.add_argument("--wait-client", action="store_true",
                    help="start the input when the first page connects")
    a = ap.parse_args(argv)
    if not (math.isfinite(a.rate) and a.rate > 0) and not a.fast:
        ap.error(f"--rate {a.rate}: a finite replay speed factor > 0 is needed (or use --fast)")
    try:
        model = DbcModel(a.dbc)
    except DbcError as e:
        print(f"sbr_dashboard: {e}", file=sys.stderr)
        return 2
    monitor = Monitor(model, timeout_factor=a.timeout_factor)
    try:
        if a.log:
            source = LogSource(monitor, a.log, rate=0.0 if a.fast else a.rate)
        elif a.socketcan:
            source = BusSource(monitor, "socketcan", a.socketcan)
        else:
            source = BusSource(monitor, "virtual", a.virtual)
    except SourceError as e:
        print(f"sbr_dashboard: {e}", file=sys.stderr)
        return 2
    monitor.source = source.name
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())

    server = None
    if not a.terminal:
        from .web import WebServer
        try:
            server = WebServer(monitor, a.host, a.port)
        except OSError as e:
            print(f"sbr_dashboard: cannot listen on {a.host}:{a.port}: {e}", file=sys.stderr)
            source.close()
            return 2
        server.start()
        print(f"sbr_dashboard: open {server.url} in a browser ({source.name}); Ctrl-C stops",
              flush=True)
    if server and a.wait_client:
        print("sbr_dashboard: the input starts when a page connects", flush=True)
        try:
            while not server.httpd.client_connected.wait(0.2) and not stop.is_set():
                pass
        except KeyboardInterrupt:
            stop.set()
        if stop.is_set():
            server.stop()
            source.close()
            return 0
    source.start()
    if a.virtual and a.feed_log:
        threading.Thread(target=feed_log_to_bus, daemon=True,
                         args=(a.feed_log, "virtual", a.virtual, 0.0 if a.fast else a.rate,
                               stop)).start()
    ended_at = None
    try:
        while not stop.is_set():
            if a.terminal and not a.once:
                sys.stdout.write(HOME_CLEAR + render(monitor.snapshot(), terminal_width()))
                sys.stdout.flush()
            if monitor.source_ended and a.log and monitor.frames == 0:
                # nothing to show: an empty log, or a file that is no candump log
                print(f"sbr_dashboard: {a.log}: no CAN frame could be read from it ({monitor.skipped_lines} "
                      "lines skipped); a candump log (candump -l) is expected", file=sys.stderr)
                source.stop()
                if server:
                    server.stop()
                return 1
            if monitor.source_ended:
                ended_at = ended_at or time.monotonic()
                if a.once:
                    sys.stdout.write(render(monitor.snapshot(), terminal_width()))
                    break
                if a.exit_after_end is not None and time.monotonic() - ended_at >= a.exit_after_end:
                    break
            stop.wait(0.5 if a.terminal else 0.1)
    except KeyboardInterrupt:
        pass
    source.stop()
    if server:
        server.stop()
    return 1 if source.error else 0


if __name__ == "__main__":
    sys.exit(main())
