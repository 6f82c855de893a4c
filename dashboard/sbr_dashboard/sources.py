# SPDX-License-Identifier: MIT
"""Inputs: a candump log (at recorded speed or as fast as possible), a live SocketCAN
interface, or python-can's virtual bus. Each runs in a thread of its own and feeds a
Monitor; `clock()` gives the current source time for timeout supervision."""
import threading
import time

import can

from .candump import Frame, open_log, read_log


class SourceError(Exception):
    pass


class Source:
    name = ""

    def __init__(self, monitor):
        self.monitor = monitor
        self.stop_event = threading.Event()
        self.thread = None
        self.error = None

    def start(self):
        self.thread = threading.Thread(target=self._guarded, name=self.name, daemon=True)
        self.thread.start()
        ticker = threading.Thread(target=self._tick_loop, name="ticker", daemon=True)
        ticker.start()

    def stop(self):
        self.stop_event.set()

    def close(self):
        """Lets go of the input when it was never started (a refusal after it was opened)."""

    def _guarded(self):
        try:
            self.run()
        except Exception as e:  # a broken source is reported, never a crash
            self.error = str(e)
            self.monitor.end_of_source(f"source failed: {e}")

    def _tick_loop(self):
        while not self.stop_event.wait(0.05):
            now = self.clock()
            if now is not None:
                self.monitor.tick(now)

    def clock(self):
        return None

    def _feed(self, msg, t=None):
        self.monitor.feed(msg.timestamp if t is None else t, msg.arbitration_id, msg.data,
                          is_extended=msg.is_extended_id, is_error=msg.is_error_frame,
                          is_remote=msg.is_remote_frame, is_fd=getattr(msg, "is_fd", False))


class LogPacer:
    """The frames of a candump log (candump.read_log: comments, blank, truncated and malformed
    lines go to `on_skip(line, reason)` and the reading goes on), each released at `rate`
    times the recorded speed (0: at once). `t0`/`wall0` tie log time to the monotonic
    clock; `next_t` is the timestamp of the frame being released."""

    def __init__(self, path, rate, stop_event, on_skip=None):
        self.path, self.rate, self.stop_event = path, rate, stop_event
        self.on_skip = on_skip
        self.t0 = self.wall0 = self.next_t = None

    def __iter__(self):
        with open_log(self.path) as f:
            yield from self._frames(f)

    def _frames(self, f):
        for msg in read_log(f):
            if self.stop_event.is_set():
                return
            if not isinstance(msg, Frame):
                if not msg.harmless and self.on_skip is not None:
                    self.on_skip(msg.line, msg.reason)
                continue
            self.next_t = msg.timestamp
            if self.t0 is None:
                self.t0, self.wall0 = msg.timestamp, time.monotonic()
            if self.rate > 0:
                delay = self.wall0 + (msg.timestamp - self.t0) / self.rate - time.monotonic()
                if delay > 0 and self.stop_event.wait(delay):
                    return
            yield msg

    def log_time(self):
        """Log time now (paced replay): never ahead of the frame being released."""
        if self.rate == 0 or self.t0 is None:
            return None
        return min(self.t0 + (time.monotonic() - self.wall0) * self.rate, self.next_t)


class LogSource(Source):
    """A candump log (`(sec.usec) ifname ID#DATA` lines), via python-can's reader. With
    rate 0 it is replayed as fast as possible (source time = the last frame's timestamp);
    otherwise at `rate` times the recorded speed (source time runs with the wall clock)."""

    def __init__(self, monitor, path, rate=1.0):
        super().__init__(monitor)
        self.path, self.rate = path, rate
        self.name = f"log {path}" + (" (as fast as possible)" if rate == 0 else
                                     f" ({rate:g}x recorded speed)")
        self.pacer = LogPacer(path, rate, self.stop_event, on_skip=monitor.skipped)
        try:
            with open(path, "rb"):
                pass
        except OSError as e:
            raise SourceError(f"cannot read {path}: {e}") from e

    def clock(self):
        # never ahead of the next frame of the log: a replay that runs late (a slow
        # machine) must not turn into timeouts the recording does not have
        return None if self.monitor.source_ended else self.pacer.log_time()

    def run(self):
        for msg in self.pacer:
            self._feed(msg, msg.timestamp)
        if not self.stop_event.is_set():
            n = self.monitor.skipped_lines
            self.monitor.end_of_source("end of log" + (f" ({n} lines skipped)" if n else ""))


class MonitorListener(can.Listener):
    """python-can's listener interface for a Source: every received frame goes to the
    source's monitor (stamped with the bus's receive time, or now when the bus gives none);
    an error in the receive thread ends the source with its reason."""

    def __init__(self, source):
        self.source = source

    def on_message_received(self, msg):
        self.source._feed(msg, msg.timestamp or time.time())

    def on_error(self, exc):
        self.source.error = str(exc)
        self.source.monitor.end_of_source(f"source failed: {exc}")


class BusSource(Source):
    """A live python-can bus: SocketCAN (`interface='socketcan'`) or the virtual bus, read
    by python-can's Notifier (its own receive thread) into a MonitorListener."""

    def __init__(self, monitor, interface, channel):
        super().__init__(monitor)
        self.name = f"{interface} {channel}"
        try:
            self.bus = can.Bus(interface=interface, channel=channel)
        except (OSError, can.CanError, ValueError, ImportError) as e:
            raise SourceError(f"cannot open {interface} channel {channel}: {e}") from e

    def clock(self):
        return time.time()

    def close(self):
        self.bus.shutdown()  # python-can warns of a bus that is never shut down

    def run(self):
        notifier = can.Notifier(self.bus, [MonitorListener(self)], timeout=0.1)
        try:
            self.stop_event.wait()
        finally:
            notifier.stop()
            self.bus.shutdown()


def feed_log_to_bus(path, interface, channel, rate=1.0, stop_event=None):
    """Play a candump log onto a bus (the ECU side, for demos and tests on the virtual bus),
    with fresh timestamps, at `rate` times the recorded speed (0: as fast as possible)."""
    bus = can.Bus(interface=interface, channel=channel)
    try:
        for msg in LogPacer(path, rate, stop_event or threading.Event()):
            bus.send(can.Message(arbitration_id=msg.arbitration_id, data=msg.data,
                                 is_extended_id=msg.is_extended_id, is_remote_frame=msg.is_remote_frame,
                                 is_error_frame=msg.is_error_frame, is_fd=msg.is_fd, timestamp=time.time()))
    finally:
        bus.shutdown()
