# SPDX-License-Identifier: MIT
"""The checks a real consumer does, and the state the views show.

Per received frame (in this order):
1. Identifier: a frame whose id is not in the DBC (or an error/remote/extended frame) is
   counted as "unknown" and ignored.
2. Length: a DLC other than the DBC's message length is an E2E "length" error.
3. E2E: the CRC (algorithm and Data ID from the DBC) must match ("crc" error otherwise);
   the alive counter must be within the counter signal's range ("bad_counter") and advance
   by one modulo its range: the same value again is "repeated" (a stale frame), a larger
   step is "skipped" (frames were lost; the frame itself is valid and used). The first
   valid frame of a message synchronises the counter.
4. Range: every signal's physical value must lie in the DBC's [minimum, maximum]
   ("out_of_range" otherwise, one count per frame, naming the signals).
Only frames that pass 2-4 ("skipped" included) change what is shown; every problem is
counted per message and listed among the recent events, never raised.

Timeouts: a message times out when no frame of it has arrived for more than
`timeout_factor` (default 3) times its GenMsgCycleTime, judged in source time (a log's
timestamps; the wall clock for live buses). One timeout is counted per silence; the
message shows "timeout" until a frame arrives again. When a log has been replayed to its
end no more source time passes, so no timeouts are declared after its last frame.

Timing, per message, from every frame of its identifier (checked or not): the frames that
arrive less than a quarter of the cycle time after the one before belong to the same
cycle (a message with several frames per image, e.g. one per detection); the measured
period is the mean time between the first frames of consecutive cycles over the last 200
cycles, the jitter their standard deviation, beside the DBC's GenMsgCycleTime.

The trace keeps the last 1000 frames (time, identifier, DLC, bytes, check result); the
snapshot carries the newest TRACE_SHOWN. The problems list is the same on the page and in
the terminal: one line per kind of problem (message, kind and what it is: a CRC mismatch
of SBR_Detection, an overload, skipped log lines), with how often it happened and when
first and last, the most recent first (at most PROBLEMS_SHOWN lines). So a flood of one
kind (an overloaded host's late images, a log's bad lines) is one line with its count and
never pushes a rare fault out of the list.

A message's state shows an E2E fault (CRC, alive counter, length) or a range error for
FAULT_HOLD_S seconds of source time after the last one (at least 10 of its cycles), even
when valid frames arrive in between, so that one bad frame is seen and not overwritten by
the next good one; its count stays in the message's row.

Absent values: a raw value at the top of a signal's range that the DBC's value table names
(e.g. 255 "NoSign", 63 "NoDetection", 255 "NotAvailable") means "absent".

Speed limit: when a list of confirmed signs is complete (SBR_Sign_Count frames), the newest
sign (lowest slot) that has a speed value sets the current limit, unless a newer sign's
DBC class name starts with "RestrictionEnds", which clears it; a list with neither keeps
the limit that was shown.
"""
import collections
import threading
import time

E2E_KINDS = ("crc", "repeated", "skipped", "bad_counter", "length")
TRACE_KEPT = 1000
TRACE_SHOWN = 200
PROBLEMS_SHOWN = 20
PERIOD_WINDOW = 200
FAULT_HOLD_S = 2.0


class PeriodMeter:
    """Cycle period and jitter of one message (see the module's note on timing)."""

    def __init__(self, cycle_ms):
        self.gap = 0.25 * cycle_ms / 1000.0
        self.last = None
        self.cycle_start = None
        self.frames_in_cycle = 0
        self.intervals = collections.deque(maxlen=PERIOD_WINDOW)
        self.cycles = 0
        self.frames = 0

    def received(self, t):
        self.frames += 1
        if self.last is None or t - self.last >= self.gap:
            if self.cycle_start is not None:
                self.intervals.append(t - self.cycle_start)
            self.cycle_start = t
            self.cycles += 1
        self.last = t

    def figures(self):
        """period_ms, jitter_ms (None until two cycles), frames per cycle."""
        n = len(self.intervals)
        if n == 0:
            return None, None, None
        mean = sum(self.intervals) / n
        var = sum((x - mean) ** 2 for x in self.intervals) / n
        return (round(mean * 1000.0, 2), round(var ** 0.5 * 1000.0, 2),
                round(self.frames / self.cycles, 2))


def event_text(e):
    """The one line a problem is shown as, on the page and in the terminal: its newest
    occurrence, and with more than one how many and when the first was."""
    text = f"{e['t']:.2f} s {e['message'] or '-'} {e['kind']}: {e['detail']}"
    n = e.get("count", 1)
    return text + (f" ({n} times, first at {e['first']:.2f} s)" if n > 1 else "")


class E2EChecker:
    """Receiver-side E2E state of one message."""

    def __init__(self, spec, crc):
        self.spec = spec
        self.crc = crc
        self.last = None

    def check(self, data):
        """'first', 'ok', or one of E2E_KINDS."""
        spec = self.spec
        if len(data) != spec.length:
            return "length"
        if self.crc(spec.crc_input(data)) != data[0]:
            return "crc"
        raw = int.from_bytes(bytes(data), "little")
        counter = (raw >> spec.counter_start) & ((1 << spec.counter_length) - 1)
        if counter > spec.counter_max:
            return "bad_counter"
        if self.last is None:
            self.last = counter
            return "first"
        step = (counter - self.last) % (spec.counter_max + 1)
        if step == 0:
            return "repeated"
        self.last = counter
        return "ok" if step == 1 else "skipped"


class TimeoutMonitor:
    """Per message: silence longer than factor x cycle time is a timeout."""

    def __init__(self, specs, factor=3.0):
        self.limit = {fid: factor * s.cycle_ms / 1000.0 for fid, s in specs.items()}
        self.last_rx = {fid: None for fid in specs}
        self.timed_out = {fid: False for fid in specs}
        self.count = {fid: 0 for fid in specs}
        self.start = None

    def received(self, fid, t):
        """A valid frame at source time t; True when this ends a timeout."""
        if self.start is None:
            self.start = t
        self.last_rx[fid] = t
        was = self.timed_out[fid]
        self.timed_out[fid] = False
        return was

    def tick(self, now):
        """Source time now; the messages that timed out at this tick."""
        if self.start is None:
            return []
        new = []
        for fid, limit in self.limit.items():
            ref = self.last_rx[fid] if self.last_rx[fid] is not None else self.start
            if not self.timed_out[fid] and now - ref > limit:
                self.timed_out[fid] = True
                self.count[fid] += 1
                new.append(fid)
        return new


def _is_absent(sig, raw):
    return sig.choices is not None and raw == (1 << sig.length) - 1 and raw in sig.choices


class Monitor:
    """Consumes frames, keeps the dashboard state; thread-safe (one lock)."""

    def __init__(self, model, timeout_factor=3.0, source="", clock=None):
        self.model = model
        self.lock = threading.Condition()
        self.version = 0
        self.source = source
        self.source_ended = False
        self.started_wall = time.time()
        self.e2e = {fid: E2EChecker(s, model.crc) for fid, s in model.messages.items()}
        self.timeouts = TimeoutMonitor(model.messages, timeout_factor)
        self.timeout_factor = timeout_factor
        self.stats = {fid: dict(name=s.name, cycle_ms=s.cycle_ms, received=0, valid=0,
                                out_of_range=0, timeouts=0, state="waiting",
                                **{k: 0 for k in E2E_KINDS})
                      for fid, s in model.messages.items()}
        self.periods = {fid: PeriodMeter(s.cycle_ms) for fid, s in model.messages.items()}
        self.last_frame = {}  # fid -> (dlc, hex bytes) of the newest frame
        self.signals = {}     # fid -> (raw, physical) values of the newest valid frame
        self.trace = collections.deque(maxlen=TRACE_KEPT)
        self.frames = 0
        self.unknown = 0
        self.skipped_lines = 0  # log lines that held no frame (comments and blanks not counted)
        self.events = collections.deque(maxlen=40)
        self.problems = {}  # (message, kind, what) -> its newest event, with count and first time
        self.t0 = None
        self.now = None
        # application state
        self.signs = []
        self._pending_signs = []
        self.speed_limit = None
        self.speed_limit_sign = None
        # the ECU's restrictions in force (SBR_Restrictions); None until its first frame,
        # and then the speed limit is the ECU's, not the dashboard's reading of the signs
        self.restrictions = None
        self.detections = []
        self._pending_dets = []
        self.objects = []
        self._pending_objs = []
        self.status = None
        self.status_count = 0
        # overload: images whose processing took longer than the status message's cycle
        # (late) or whose results the ECU dropped (the Overload bit); either is an overload
        self.flag_counts = dict(overload=0, late=0, dropped=0, error=0, capacity=0)
        self.overload_now = False
        # the cycle an image's processing must fit: SBR_EcuStatus's GenMsgCycleTime
        self.status_cycle_ms = next((m.cycle_ms for m in model.messages.values() if m.name == "SBR_EcuStatus"),
                                    None)
        self.object_frames = 0  # SBR_TrackedObject frames received, NoObject ones too
        self._proc_sum = 0.0
        self._status_times = collections.deque()

    # -- input ---------------------------------------------------------------------------
    def feed(self, t, frame_id, data, is_extended=False, is_error=False, is_remote=False, is_fd=False):
        """One received frame at source time t (seconds). Extended, error, remote and CAN FD
        frames are valid on a bus but none of the DBC's messages: counted as unknown,
        named in the problems list by kind."""
        kind = ("error frame" if is_error else "remote frame" if is_remote else "CAN FD frame" if is_fd
                else "extended frame" if is_extended else "")
        with self.lock:
            self._feed(t, frame_id, bytes(data), kind)
            self.version += 1
            self.lock.notify_all()

    def skipped(self, line, reason):
        """A line of a log that held no frame (truncated, malformed): counted and listed with
        its line number; the replay goes on."""
        with self.lock:
            self.skipped_lines += 1
            self._event(self.now or 0.0, None, "log", f"line {line} skipped: {reason}", what="skipped lines")
            self.version += 1
            self.lock.notify_all()

    def tick(self, now):
        """Advance source time (timeouts) without a frame."""
        with self.lock:
            if self.source_ended:
                return
            if self._tick(now):
                self.version += 1
                self.lock.notify_all()

    def end_of_source(self, reason="end of log"):
        with self.lock:
            self.source_ended = True
            self._event(self.now or 0.0, None, "source", reason)
            self.version += 1
            self.lock.notify_all()

    def _event(self, t, fid, kind, detail="", what=None):
        """A problem: into the recent events, and counted under (message, kind, what) for
        the problems list (`what`: what stays the same from one occurrence to the next,
        the detail itself by default)."""
        rel = 0.0 if self.t0 is None else t - self.t0
        name = self.stats[fid]["name"] if fid in self.stats else ""
        e = dict(t=round(rel, 3), message=name, kind=kind, detail=detail)
        self.events.appendleft(e)
        key = (name, kind, detail if what is None else what)
        had = self.problems.get(key)
        self.problems[key] = dict(e, count=(had["count"] + 1) if had else 1,
                                  first=had["first"] if had else e["t"])

    def _fault(self, t, fid, state):
        """A message's state turned to a fault, held FAULT_HOLD_S (at least 10 cycles)."""
        st = self.stats[fid]
        st["state"] = state
        st["fault_until"] = t + max(FAULT_HOLD_S, 10 * st["cycle_ms"] / 1000.0)

    def _tick(self, now):
        if self.t0 is None:
            return False
        self.now = max(self.now or now, now)
        changed = False
        for fid in self.timeouts.tick(self.now):
            st = self.stats[fid]
            st["timeouts"] += 1
            st["state"] = "timeout"
            limit_ms = self.timeout_factor * st["cycle_ms"]
            # the event at the moment the silence passed the limit, not when a tick noticed
            # it: the same time whatever the replay speed or the ticks' timing
            last = self.timeouts.last_rx[fid]
            at = (last if last is not None else self.timeouts.start) + self.timeouts.limit[fid]
            self._event(at, fid, "timeout", f"no frame for more than {limit_ms:.0f} ms")
            changed = True
        return changed

    def _feed(self, t, fid, data, odd_kind):
        if self.t0 is None:
            self.t0 = t
            self.timeouts.start = t
        self._tick(t)
        self.frames += 1
        spec = self.model.messages.get(fid)
        known = spec is not None and not odd_kind
        text = data.hex(" ").upper()
        if known:
            self.periods[fid].received(t)
            self.last_frame[fid] = (len(data), text)
        check = self._check(t, fid, data, spec) if known else "unknown"
        if not known:
            self.unknown += 1
            what = f"{odd_kind} " if odd_kind else ""
            self._event(t, None, "unknown", f"{what}id 0x{fid:X}", what="frames not in the DBC")
        self.trace.append(dict(t=round(t - self.t0, 4), id=f"0x{fid:03X}",
                               name=spec.name if spec is not None else "", dlc=len(data),
                               data=text, check=check))

    def _check(self, t, fid, data, spec):
        """The checks of one frame of a known message; the result for the trace."""
        st = self.stats[fid]
        st["received"] += 1
        result = self.e2e[fid].check(data)
        if result in E2E_KINDS:
            st[result] += 1
            detail = {"crc": "CRC mismatch", "repeated": "alive counter repeated",
                      "skipped": "alive counter skipped (frames lost)",
                      "bad_counter": "alive counter out of range",
                      "length": f"DLC {len(data)}, expected {spec.length}"}[result]
            self._event(t, fid, "e2e", detail)
            if result == "skipped" and st["state"] == "timeout":
                st["state"] = "e2e error"  # the frames lost are the timeout's, shown already
            else:
                self._fault(t, fid, "e2e error")
            if result != "skipped":
                return result
        msg = spec.message
        try:
            raw = msg.decode(data, decode_choices=False, scaling=False)
            # scaled from the raw values by each signal's own conversion (what cantools'
            # scaling=True does, without decoding the bits a second time)
            phys = {sig.name: sig.conversion.raw_to_scaled(raw[sig.name], False) for sig in msg.signals}
        except Exception as e:  # never expected for a frame of the right length
            st["out_of_range"] += 1
            self._event(t, fid, "range", f"cannot decode: {e}")
            return "range"
        bad = []
        for sig in msg.signals:
            v = phys[sig.name]
            eps = 1e-6 * max(1.0, abs(sig.scale))
            if (sig.minimum is not None and v < sig.minimum - eps) or \
               (sig.maximum is not None and v > sig.maximum + eps):
                bad.append(f"{sig.name}={v:g} outside [{sig.minimum:g}, {sig.maximum:g}]")
        if bad:
            st["out_of_range"] += 1
            self._fault(t, fid, "range error")
            self._event(t, fid, "range", "; ".join(bad), what="out of range: " + ", ".join(b.split("=")[0] for b in bad))
            return "range"
        st["valid"] += 1
        if self.timeouts.received(fid, t):
            self._event(t, fid, "recovered", "frames arrive again")
        if result != "skipped" and t >= st.get("fault_until", float("-inf")):
            st["state"] = "ok"
        self.signals[fid] = (raw, phys)  # shown as a table in snapshots (_message_view)
        self._apply(t, spec, msg, raw, phys)
        return "ok" if result in ("ok", "first") else result

    # -- application ---------------------------------------------------------------------
    def _name(self, spec, sig_name, raw):
        return self.model.choice_name(spec.frame_id, sig_name, raw)

    def _absent(self, msg, sig_name, raw):
        return _is_absent(msg.get_signal_by_name(sig_name), int(raw))

    def _apply(self, t, spec, msg, raw, phys):
        n = spec.name
        if n == "SBR_ConfirmedSign":
            count, slot = int(raw["SBR_Sign_Count"]), int(raw["SBR_Sign_Slot"])
            if count == 0 or self._absent(msg, "SBR_Sign_Class", raw["SBR_Sign_Class"]):
                self._pending_signs = []
                self._publish_signs()
                return
            if slot == 0:
                self._pending_signs = []
            if slot != len(self._pending_signs):
                return  # a slot was lost: wait for the next complete list
            cls = int(raw["SBR_Sign_Class"])
            speed = int(raw["SBR_Sign_SpeedLimit"])
            track = int(raw["SBR_Sign_TrackId"])
            self._pending_signs.append(dict(
                slot=slot, class_id=cls, class_name=self._name(spec, "SBR_Sign_Class", cls),
                speed=None if self._absent(msg, "SBR_Sign_SpeedLimit", speed) else speed,
                track=None if self._absent(msg, "SBR_Sign_TrackId", track) else track,
                confidence=phys["SBR_Sign_Confidence"], age=int(raw["SBR_Sign_AgeFrames"])))
            if len(self._pending_signs) == count:
                self._publish_signs()
        elif n == "SBR_EcuStatus":
            self.status = {k.replace("SBR_Status_", ""): phys[k] for k in phys
                           if not k.endswith(("_CRC", "_Counter"))}
            self.status_count += 1
            proc = phys["SBR_Status_ProcessingTime"]
            self._proc_sum += proc
            for key, sig in (("dropped", "SBR_Status_Overload"), ("error", "SBR_Status_Error"),
                             ("capacity", "SBR_Status_CapacityHit")):
                if raw[sig]:
                    self.flag_counts[key] += 1
            late = proc > spec.cycle_ms
            self.flag_counts["late"] += late
            was = self.overload_now
            self.overload_now = late or bool(raw["SBR_Status_Overload"])
            self.flag_counts["overload"] += self.overload_now
            if self.overload_now and not was:
                self._event(t, spec.frame_id, "overload", f"processing {proc:.1f} ms > the {spec.cycle_ms} ms cycle" if late
                            else "the ECU dropped results of this image", what="overload")
            self._status_times.append(t)
            while len(self._status_times) > 2 and t - self._status_times[0] > 2.0:
                self._status_times.popleft()
            # the detections of this image follow its status frame
            self._pending_dets = []
            self.detections = []
        elif n == "SBR_Detection":
            cls = int(raw["SBR_Det_Class"])
            if self._absent(msg, "SBR_Det_Class", cls):
                self.detections = []
                return
            track = int(raw["SBR_Det_TrackId"])
            self._pending_dets.append(dict(
                class_id=cls, class_name=self._name(spec, "SBR_Det_Class", cls),
                confidence=phys["SBR_Det_Confidence"], cx=phys["SBR_Det_CenterX"],
                cy=phys["SBR_Det_CenterY"], w=phys["SBR_Det_Width"], h=phys["SBR_Det_Height"],
                track=None if self._absent(msg, "SBR_Det_TrackId", track) else track))
            self.detections = list(self._pending_dets)
        elif n == "SBR_Restrictions":
            limit = int(raw["SBR_Restr_SpeedLimit"])
            self.restrictions = dict(
                speed_limit=None if limit == 0 else limit,  # the DBC's "NoLimit"
                no_overtaking=bool(raw["SBR_Restr_NoOvertaking"]),
                no_overtaking_trucks=bool(raw["SBR_Restr_NoOvertakingTrucks"]),
                priority_road=bool(raw["SBR_Restr_PriorityRoad"]),
                speed_age_s=int(raw["SBR_Restr_SpeedAge"]))
            self.speed_limit = self.restrictions["speed_limit"]
        elif n == "SBR_TrackedObject":
            self.object_frames += 1
            track = int(raw["SBR_Obj_TrackId"])
            if int(raw["SBR_Obj_Index"]) == 0:
                self._pending_objs = []
            if self._absent(msg, "SBR_Obj_TrackId", track):
                self.objects = []
                return
            self._pending_objs.append(dict(
                track=track, x=phys["SBR_Obj_PosX"], y=phys["SBR_Obj_PosY"],
                vx=phys["SBR_Obj_VelX"], vy=phys["SBR_Obj_VelY"],
                certainty=phys["SBR_Obj_Certainty"]))
            self.objects = list(self._pending_objs)

    def _publish_signs(self):
        self.signs = list(self._pending_signs)
        self._pending_signs = []
        for s in self.signs:  # newest first: the sign that set or ended the limit
            if self.restrictions is not None:  # the ECU says which limit is in force
                if s["speed"] is not None and s["speed"] == self.speed_limit:
                    self.speed_limit_sign = s
                    return
                continue
            if (s["class_name"] or "").startswith("RestrictionEnds"):
                self.speed_limit, self.speed_limit_sign = None, s
                return
            if s["speed"] is not None:
                self.speed_limit, self.speed_limit_sign = s["speed"], s
                return

    # -- output --------------------------------------------------------------------------
    def snapshot(self):
        with self.lock:
            return self._snapshot()

    def _snapshot(self):
        times = self._status_times
        fps = (len(times) - 1) / (times[-1] - times[0]) if len(times) > 1 and times[-1] > times[0] else 0.0
        totals = {k: sum(s[k] for s in self.stats.values())
                  for k in E2E_KINDS + ("out_of_range", "timeouts", "received", "valid")}
        totals["e2e_errors"] = sum(totals[k] for k in E2E_KINDS)
        return dict(
            version=self.version, source=self.source, source_ended=self.source_ended,
            source_time=0.0 if self.t0 is None else round((self.now or self.t0) - self.t0, 3),
            frames=self.frames, unknown=self.unknown, skipped_lines=self.skipped_lines, totals=totals,
            timeout_factor=self.timeout_factor,
            messages=[self._message_view(fid, st) for fid, st in sorted(self.stats.items())],
            events=list(self.events),
            problems=[event_text(e) for e in sorted(self.problems.values(), key=lambda e: -e["t"])][:PROBLEMS_SHOWN],
            trace=list(self.trace)[-TRACE_SHOWN:],
            tracker_seen=self.object_frames > 0,
            speed_limit=self.speed_limit,
            speed_limit_sign=self.speed_limit_sign,
            restrictions=self.restrictions,
            signs=self.signs, detections=self.detections, objects=self.objects,
            health=dict(status_frames=self.status_count, fps=round(fps, 2),
                        processing_ms=None if self.status is None else self.status["ProcessingTime"],
                        processing_ms_mean=self._proc_sum / self.status_count
                        if self.status_count else None,
                        cycle_ms=self.status_cycle_ms, overload_now=self.overload_now,
                        status=self.status, flag_counts=dict(self.flag_counts)))

    def _message_view(self, fid, st):
        period, jitter, per_cycle = self.periods[fid].figures()
        dlc, data = self.last_frame.get(fid, (None, ""))
        spec = self.model.messages[fid]
        raw, phys = self.signals.get(fid, ({}, {}))
        signals = [dict(name=sig.name, value=phys[sig.name], raw=int(raw[sig.name]), unit=sig.unit or "",
                        choice=self._name(spec, sig.name, int(raw[sig.name])) or "")
                   for sig in spec.message.signals if sig.name in raw]
        return dict(id=f"0x{fid:03X}", period_ms=period, jitter_ms=jitter, frames_per_cycle=per_cycle,
                    dlc=dlc, data=data, signals=signals, **st)

    def wait_change(self, version, timeout):
        """Block until the state version differs from `version` (or timeout)."""
        with self.lock:
            self.lock.wait_for(lambda: self.version != version, timeout)
            return self.version
