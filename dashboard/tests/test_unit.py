# SPDX-License-Identifier: MIT
"""Unit tests of the dashboard: the DBC model, E2E checking, range checks, timeouts, the
application state, the views and the inputs, with crafted frames."""
import json
import random
import threading
import time
import urllib.request

import can
import pytest

from frames import DBC, Sender, frame, model
from sbr_dashboard.dbc import Crc8, DbcError, DbcModel
from sbr_dashboard.monitor import E2EChecker, Monitor, TimeoutMonitor
from sbr_dashboard.sources import BusSource, LogSource, MonitorListener
from sbr_dashboard.terminal import render
from sbr_dashboard.web import WebServer

M = model()


def feed_all(mon, frames, t):
    for fid, data in frames:
        mon.feed(t, fid, data)


# -- the DBC model -----------------------------------------------------------------------
def test_dbc_gives_e2e_and_cycle_times():
    assert sorted(M.messages) == [0x300, 0x301, 0x302, 0x310, 0x320]
    for fid, spec in M.messages.items():
        assert spec.cycle_ms == 100
        assert spec.data_id == 0x5B00 | (fid & 0xFF)
        assert spec.crc_signal.endswith("_CRC") and spec.counter_signal.endswith("_Counter")
        assert (spec.counter_start, spec.counter_length, spec.counter_max) == (8, 4, 14)
    assert (M.crc.poly, M.crc.init, M.crc.xorout) == (0x1D, 0xFF, 0xFF)


def test_crc_check_value_and_autosar_vectors():
    crc = M.crc
    assert crc(b"123456789") == 0x4B
    # AUTOSAR CRC library, CRC-8 SAE J1850 check values
    for data, want in [("00000000", 0x59), ("F20183", 0x37), ("0FAA0055", 0x79),
                       ("00FF5511", 0xB8), ("332255AABBCCDDEEFF", 0xCB), ("926B55", 0x8C),
                       ("FFFFFFFF", 0x74)]:
        assert crc(bytes.fromhex(data)) == want, data


def test_dbc_with_another_crc_is_refused(tmp_path):
    text = open(DBC).read()
    bad = tmp_path / "bad.dbc"
    bad.write_text(text.replace("check 0x4B", "check 0x4C"))
    with pytest.raises(DbcError):
        DbcModel(str(bad))
    missing = tmp_path / "nocrc.dbc"
    missing.write_text(text.replace("polynomial 0x1D", "poly 0x1D"))
    with pytest.raises(DbcError):
        DbcModel(str(missing))
    with pytest.raises(DbcError):
        DbcModel(str(tmp_path / "absent.dbc"))


# -- E2E -----------------------------------------------------------------------------------
def test_frames_written_by_the_c_library_pass():
    # candump lines written by sbr's C scheduler (sbr_detect --canlog), cycle 0 and 1
    chk = {fid: E2EChecker(M.messages[fid], M.crc) for fid in M.messages}
    first = [(0x300, "D800FFFFFF000000"), (0x301, "6C0000005E07C501"),
             (0x310, "06F00300000000FC"), (0x320, "AD00FF0000000000")]
    second = [(0x300, "8501FFFFFF000000"), (0x301, "E9010100DB0A7415"),
              (0x310, "4EE1403C5262B9FC"), (0x320, "F001FF0000000000")]
    assert [chk[f].check(bytes.fromhex(d)) for f, d in first] == ["first"] * 4
    assert [chk[f].check(bytes.fromhex(d)) for f, d in second] == ["ok"] * 4


def test_every_single_bit_flip_is_a_crc_error():
    good = frame(M, 0x310, 3, SBR_Det_Class=14, SBR_Det_Confidence=88, SBR_Det_CenterX=600,
                 SBR_Det_CenterY=300, SBR_Det_Width=40, SBR_Det_Height=44)
    for bit in range(64):
        bad = bytearray(good)
        bad[bit // 8] ^= 1 << (bit % 8)
        assert E2EChecker(M.messages[0x310], M.crc).check(bytes(bad)) == "crc", bit


def test_counter_sequence_results():
    chk = E2EChecker(M.messages[0x301], M.crc)
    f = lambda c: frame(M, 0x301, c)
    assert chk.check(f(13)) == "first"
    assert chk.check(f(14)) == "ok"
    assert chk.check(f(0)) == "ok"          # wraps after 14
    assert chk.check(f(0)) == "repeated"
    assert chk.check(f(3)) == "skipped"     # 1 and 2 lost; state follows
    assert chk.check(f(4)) == "ok"
    assert chk.check(frame(M, 0x301, 15, strict=False)) == "bad_counter"
    assert chk.check(f(5)[:7]) == "length"
    # a status payload under another id: its Data ID differs, so the CRC fails
    assert E2EChecker(M.messages[0x300], M.crc).check(f(6)) == "crc"


# -- range, timeouts, state ----------------------------------------------------------------
def test_out_of_range_values_are_counted_and_not_shown():
    mon = Monitor(M)
    s = Sender(M)
    feed_all(mon, s.cycle(0, dets=[(1, 50, 100, 100)]), 0.0)
    assert len(mon.snapshot()["detections"]) == 1
    feed_all(mon, s.cycle(1), 0.1)
    # confidence raw 63 -> 126 % (range 0..100), valid CRC and counter
    feed_all(mon, [(0x301, s(0x301, SBR_Status_FrameCounter=2, SBR_Status_DetectionCount=1)),
                   (0x310, frame(M, 0x310, s.counter[0x310], strict=False, SBR_Det_Class=2,
                                 SBR_Det_Confidence=126, SBR_Det_TrackId=63))], 0.2)
    snap = mon.snapshot()
    det = next(m for m in snap["messages"] if m["name"] == "SBR_Detection")
    assert det["out_of_range"] == 1 and det["state"] == "range error"
    assert snap["detections"] == []
    assert any(e["kind"] == "range" and "SBR_Det_Confidence=126" in e["detail"]
               for e in snap["events"])
    assert snap["totals"]["out_of_range"] == 1 and snap["totals"]["e2e_errors"] == 0


def test_timeout_after_three_cycles_once_per_silence_and_recovery():
    tm = TimeoutMonitor(M.messages, factor=3.0)
    tm.received(0x300, 0.0)
    assert tm.tick(0.29) == []
    # 0x300 silent since its frame at 0.0, the others never seen since the start at 0.0
    assert sorted(tm.tick(0.31)) == [0x300, 0x301, 0x302, 0x310, 0x320]
    assert tm.count[0x300] == 1
    assert tm.tick(1.0) == []     # still the same silence
    assert tm.received(0x300, 1.05) is True
    assert tm.tick(1.3) == [] and tm.tick(1.36) == [0x300]
    assert tm.count[0x300] == 2


def test_monitor_timeout_of_a_silent_message_in_source_time():
    mon = Monitor(M)
    s = Sender(M)
    r0 = (0, 0, 0, 0, 0)
    for k in range(5):
        feed_all(mon, s.cycle(k, restr=r0), 0.1 * k)
    for k in range(5, 15):  # tracked objects go silent
        feed_all(mon, [f for f in s.cycle(k, restr=r0) if f[0] != 0x320], 0.1 * k)
    snap = mon.snapshot()
    obj = next(m for m in snap["messages"] if m["name"] == "SBR_TrackedObject")
    assert obj["timeouts"] == 1 and obj["state"] == "timeout"
    assert snap["totals"]["timeouts"] == 1
    # the ECU kept counting while its frames were lost: the next one is "skipped" (valid)
    feed_all(mon, s.cycle(15, restr=r0), 1.5)
    snap = mon.snapshot()
    obj = next(m for m in snap["messages"] if m["name"] == "SBR_TrackedObject")
    assert obj["timeouts"] == 1 and obj["skipped"] == 1 and obj["valid"] == 6
    assert [(e["message"], e["kind"]) for e in snap["events"][:2]] == \
        [("SBR_TrackedObject", "recovered"), ("SBR_TrackedObject", "e2e")]
    feed_all(mon, s.cycle(16), 1.6)
    obj = next(m for m in mon.snapshot()["messages"] if m["name"] == "SBR_TrackedObject")
    assert obj["state"] == "ok" and obj["timeouts"] == 1


def test_no_timeouts_after_the_log_ended():
    mon = Monitor(M)
    s = Sender(M)
    feed_all(mon, s.cycle(0), 0.0)
    mon.end_of_source()
    mon.tick(10.0)
    assert mon.snapshot()["totals"]["timeouts"] == 0


def test_speed_limit_from_confirmed_signs():
    mon = Monitor(M)
    s = Sender(M)
    feed_all(mon, s.cycle(0), 0.0)
    assert mon.snapshot()["speed_limit"] is None
    # newest first: a give-way sign (13) then a 70 limit (class 4)
    feed_all(mon, s.cycle(1, signs=[(13, 255, 80, 0), (4, 70, 90, 3)]), 0.1)
    snap = mon.snapshot()
    assert snap["speed_limit"] == 70
    assert [x["class_name"] for x in snap["signs"]] == ["GiveWay", "SpeedLimit70"]
    assert snap["signs"][0]["speed"] is None and snap["signs"][0]["track"] == 0
    # a list without speed signs keeps the limit; the end of restrictions clears it
    feed_all(mon, s.cycle(2, signs=[(14, 255, 60, 0)]), 0.2)
    assert mon.snapshot()["speed_limit"] == 70
    feed_all(mon, s.cycle(3, signs=[(6, 255, 60, 0), (4, 70, 90, 5)]), 0.3)
    assert mon.snapshot()["speed_limit"] is None
    feed_all(mon, s.cycle(4, signs=[(8, 120, 77, 0)]), 0.4)
    assert mon.snapshot()["speed_limit"] == 120
    # a lost slot: the incomplete list is not shown
    frames = s.cycle(5, signs=[(2, 50, 70, 0), (3, 60, 70, 0)])
    feed_all(mon, frames[1:], 0.5)
    snap = mon.snapshot()
    assert snap["speed_limit"] == 120 and [x["class_id"] for x in snap["signs"]] == [8]


def test_detections_per_image_and_health():
    mon = Monitor(M)
    s = Sender(M)
    feed_all(mon, s.cycle(0, dets=[(14, 90, 500, 300), (2, 40, 100, 200)], proc_ms=40.0), 0.0)
    snap = mon.snapshot()
    assert [(d["class_name"], d["confidence"], d["cx"]) for d in snap["detections"]] == \
        [("Stop", 90, 500), ("SpeedLimit50", 40, 100)]
    feed_all(mon, s.cycle(1, proc_ms=60.0), 0.1)
    snap = mon.snapshot()
    assert snap["detections"] == []
    h = snap["health"]
    assert h["status_frames"] == 2 and h["processing_ms"] == pytest.approx(60.0)
    assert h["processing_ms_mean"] == pytest.approx(50.0) and h["fps"] == pytest.approx(10.0)
    assert snap["totals"]["valid"] == 9 and snap["totals"]["e2e_errors"] == 0


def test_garbage_never_raises_and_every_frame_is_counted():
    rng = random.Random(7)
    mon = Monitor(M)
    n = 3000
    for k in range(n):
        fid = rng.choice([0x300, 0x301, 0x310, 0x320, 0x123, 0x7FF])
        data = bytes(rng.randrange(256) for _ in range(rng.randrange(9)))
        mon.feed(k * 0.01, fid, data, is_error=rng.random() < 0.01)
    snap = mon.snapshot()
    t = snap["totals"]
    assert snap["frames"] == n
    assert t["received"] + snap["unknown"] == n
    assert t["received"] == t["valid"] + t["crc"] + t["repeated"] + t["bad_counter"] + \
        t["length"] + t["out_of_range"]  # skipped frames are valid too
    assert t["crc"] > 0 and t["length"] > 0 and snap["unknown"] > 0


# -- views and inputs ----------------------------------------------------------------------
def test_terminal_screen_shows_state():
    mon = Monitor(M, source="test")
    s = Sender(M)
    feed_all(mon, s.cycle(0, signs=[(5, 80, 95, 0)], dets=[(5, 94, 640, 400)]), 0.0)
    bad = bytearray(s(0x301))
    bad[3] ^= 0x10
    mon.feed(0.05, 0x301, bytes(bad))
    screen = render(mon.snapshot())
    assert "SPEED LIMIT: 80 km/h" in screen
    assert "SpeedLimit80 95 % (age 0 frames)" in screen and "SpeedLimit80 94 % at (640 px, 400 px)" in screen
    assert "SBR_EcuStatus" in screen and "CRC mismatch" in screen
    row = next(line for line in screen.splitlines() if line.startswith("SBR_EcuStatus"))
    assert row.split()[1:3] == ["e2e", "error"] and row.split()[4] == "1"


def test_web_server_state_and_events():
    mon = Monitor(M, source="test")
    s = Sender(M)
    feed_all(mon, s.cycle(0, signs=[(1, 30, 90, 0)]), 0.0)
    srv = WebServer(mon, "127.0.0.1", 0)
    srv.start()
    try:
        snap = json.load(urllib.request.urlopen(srv.url + "state.json", timeout=5))
        assert snap["speed_limit"] == 30
        page = urllib.request.urlopen(srv.url, timeout=5).read().decode()
        assert 'id="speed-limit"' in page and "/static/app.js" in page
        with urllib.request.urlopen(srv.url + "events", timeout=5) as ev:
            assert ev.headers["Content-Type"] == "text/event-stream"
            lines = [ev.readline().decode() for _ in range(2)]
        assert lines[0].startswith("id: ") and lines[1].startswith("data: ")
        assert json.loads(lines[1][6:])["signs"][0]["class_name"] == "SpeedLimit30"
        with pytest.raises(urllib.error.HTTPError):
            urllib.request.urlopen(srv.url + "static/../../dbc.py", timeout=5)
    finally:
        srv.stop()


def test_log_source_replays_as_fast_as_possible(tmp_path):
    s = Sender(M)
    log = tmp_path / "x.log"
    with open(log, "w") as f:
        for k in range(20):
            for fid, data in s.cycle(k, dets=[(4, 80, 300, 200)] if k % 2 else ()):
                f.write(f"({1700000000 + k // 10}.{(k % 10) * 100000:06d}) can0 "
                        f"{fid:03X}#{data.hex().upper()}\n")
    mon = Monitor(M)
    src = LogSource(mon, str(log), rate=0.0)
    src.start()
    src.thread.join(10)
    snap = mon.snapshot()
    assert snap["source_ended"] and snap["frames"] == 80
    assert snap["totals"]["valid"] == 80 and snap["totals"]["e2e_errors"] == 0
    assert snap["health"]["status"]["FrameCounter"] == 19
    assert snap["source_time"] == pytest.approx(1.9)


def test_a_real_bus_log_is_replayed_to_its_end(tmp_path):
    # what candump logs of real buses hold besides sbr's frames: comments, blank lines, CAN
    # FD, remote, error and extended frames, bad hex, an odd digit count, a line without a
    # frame, and a truncated last line. Every valid sbr frame is used; the others are
    # counted and named; the bad lines are listed with their numbers; the replay goes on.
    s = Sender(M)
    lines = ["# candump -l can0, recorded on a test drive", ""]
    good = 0
    for k in range(10):
        for fid, data in s.cycle(k):
            lines.append(f"(1700000000.{k * 100000:06d}) can0 {fid:03X}#{data.hex().upper()}")
            good += 1
        if k == 3:
            lines += ["(1700000000.350000) can0 7DF##1020C0000000000",  # CAN FD
                      "(1700000000.350100) can0 7DF#R",                # remote
                      "(1700000000.350200) can0 20000004#0000000000000000",  # error frame
                      "(1700000000.350300) can0 18DAF110#0210030000000000",  # extended
                      "(1700000000.350400) can0 123#GG",                # bad hex
                      "(1700000000.350500) can0 123#ABC",               # odd digits
                      "garbage without a frame"]
    lines.append("(1700000001.000000) can0 12")  # truncated last line
    log = tmp_path / "real.log"
    log.write_text("\n".join(lines))
    mon = Monitor(M)
    src = LogSource(mon, str(log), rate=0.0)
    src.start()
    src.thread.join(10)
    snap = mon.snapshot()
    assert snap["source_ended"] and src.error is None
    assert snap["totals"]["valid"] == good and snap["frames"] == good + 4
    assert snap["unknown"] == 4 and snap["skipped_lines"] == 4
    text = "\n".join(e["detail"] for e in snap["events"])
    for what in ("CAN FD frame id 0x7DF", "remote frame id 0x7DF", "error frame id 0x4",
                 "extended frame id 0x18DAF110"):
        assert what in text, what
    bad = [i + 1 for i, l in enumerate(lines) if l.startswith("(1700000000.3504") or l.startswith("(1700000000.3505")
           or l.startswith("garbage") or l.endswith("can0 12")]
    for n in bad:
        assert f"line {n} skipped" in text, n
    assert "end of log (4 lines skipped)" in text


def test_virtual_bus_source():
    mon = Monitor(M)
    src = BusSource(mon, "virtual", "sbr-test")
    src.start()
    tx = can.Bus(interface="virtual", channel="sbr-test")
    try:
        s = Sender(M)
        for fid, data in s.cycle(0, signs=[(7, 100, 99, 0)]):
            tx.send(can.Message(arbitration_id=fid, data=data, is_extended_id=False))
        deadline = time.monotonic() + 5
        while mon.snapshot()["frames"] < 4 and time.monotonic() < deadline:
            time.sleep(0.02)
        snap = mon.snapshot()
        assert snap["frames"] == 4 and snap["speed_limit"] == 100
    finally:
        tx.shutdown()
        src.stop()
        src.thread.join(2)


def test_bus_source_is_a_python_can_listener():
    """Frames reach the monitor through python-can's Listener interface; an error in the
    Notifier's receive thread ends the source with its reason instead of vanishing."""
    mon = Monitor(M)
    src = BusSource(mon, "virtual", "sbr-listener")
    try:
        lis = MonitorListener(src)
        assert isinstance(lis, can.Listener)
        s = Sender(M)
        for fid, data in s.cycle(0, signs=[(7, 100, 99, 0)]):
            lis(can.Message(arbitration_id=fid, data=data, is_extended_id=False, timestamp=12.5))
        snap = mon.snapshot()
        assert snap["frames"] == 4 and snap["speed_limit"] == 100
        lis.on_error(OSError("bus off"))
        assert src.error == "bus off"
        assert mon.source_ended
    finally:
        src.bus.shutdown()


def test_tracked_objects_list_per_cycle():
    mon = Monitor(M)
    s = Sender(M)
    frames = [f for f in s.cycle(0) if f[0] != 0x320]
    frames += [(0x320, s(0x320, SBR_Obj_Index=0, SBR_Obj_TrackId=7, SBR_Obj_PosX=640,
                         SBR_Obj_PosY=300, SBR_Obj_VelX=-40, SBR_Obj_VelY=8,
                         SBR_Obj_Certainty=88)),
               (0x320, s(0x320, SBR_Obj_Index=1, SBR_Obj_TrackId=9, SBR_Obj_PosX=100,
                         SBR_Obj_PosY=700, SBR_Obj_VelX=0, SBR_Obj_VelY=0,
                         SBR_Obj_Certainty=40))]
    feed_all(mon, frames, 0.0)
    snap = mon.snapshot()
    assert [(o["track"], o["x"], o["y"], o["vx"], o["vy"], o["certainty"]) for o in snap["objects"]] \
        == [(7, 640, 300, -40, 8, 88), (9, 100, 700, 0, 0, 40)]
    assert "tracked objects: #7 at (640 px, 300 px) moving (-40 px/s, 8 px/s) 88 %," in render(snap, 120)
    feed_all(mon, s.cycle(1), 0.1)  # "no object" frame
    assert mon.snapshot()["objects"] == []


# -- what a CAN engineer reads: timing, bytes, signals, trace, problems ---------------------
def test_period_jitter_bytes_and_signals_per_message():
    mon = Monitor(M)
    snd = Sender(M)
    # two detections per image (two frames of 0x310 a cycle), images 100 ms apart with
    # +-5 ms of alternating jitter
    for k in range(21):
        t = 0.1 * k + (0.005 if k % 2 else -0.005)
        feed_all(mon, snd.cycle(k, dets=[(1, 90, 300, 200), (14, 80, 800, 300)]), t)
    msgs = {m["name"]: m for m in mon.snapshot()["messages"]}
    det = msgs["SBR_Detection"]
    assert det["frames_per_cycle"] == 2.0
    assert det["period_ms"] == pytest.approx(100.0, abs=0.6)
    assert det["jitter_ms"] == pytest.approx(10.0, abs=0.6)  # the cycle steps 90, 110, 90, ...
    assert det["dlc"] == 8 and det["cycle_ms"] == 100
    last = snd.cycle(21, dets=[(1, 90, 300, 200)])
    feed_all(mon, last, 2.1)
    status = {m["name"]: m for m in mon.snapshot()["messages"]}["SBR_EcuStatus"]
    assert status["data"] == bytes(last[1][1]).hex(" ").upper()
    sig = {g["name"]: g for g in status["signals"]}
    assert sig["SBR_Status_FrameCounter"]["value"] == 21 and sig["SBR_Status_ProcessingTime"]["unit"] == "ms"
    det_sig = {g["name"]: g for g in {m["name"]: m for m in mon.snapshot()["messages"]}["SBR_Detection"]["signals"]}
    assert det_sig["SBR_Det_Class"]["choice"] == M.choice_name(0x310, "SBR_Det_Class", 1)


def test_trace_keeps_frames_with_their_check():
    mon = Monitor(M)
    snd = Sender(M)
    feed_all(mon, snd.cycle(0), 0.0)
    bad = bytearray(snd(0x301, SBR_Status_FrameCounter=1))
    bad[3] ^= 1
    mon.feed(0.1, 0x301, bad)
    mon.feed(0.1, 0x7FF, bytes(3))
    tr = mon.snapshot()["trace"]
    assert [f["check"] for f in tr[-2:]] == ["crc", "unknown"]
    assert tr[-2]["id"] == "0x301" and tr[-2]["data"] == bad.hex(" ").upper() and tr[-1]["dlc"] == 3
    assert all(f["check"] == "ok" for f in tr[:-2])
    for k in range(1, 400):
        feed_all(mon, snd.cycle(k), 0.1 * k)
    assert len(mon.snapshot()["trace"]) == 200


def test_terminal_fits_its_width_and_lists_the_page_problems():
    mon = Monitor(M, source="log " + "/very/long/path/of/a/recorded/drive" * 3 + ".log")
    snd = Sender(M)
    signs = [(1, 30, 95, 3), (40, 255, 90, 1), (42, 255, 80, 2), (12, 255, 99, 9)]
    for k in range(10):
        feed_all(mon, snd.cycle(k, dets=[(1, 90, 1300, 700)] * 4, signs=signs), 0.1 * k)
    for k in range(8):
        mon.feed(1.0 + 0.01 * k, 0x7FF, bytes(8))
        mon.feed(1.0, 0x301, bytes(8))
    s = mon.snapshot()
    assert s["problems"] and len(s["problems"]) <= 20
    for width in (80, 100, 120):
        screen = render(s, width)
        lines = screen.rstrip("\n").split("\n")
        assert max(len(ln) for ln in lines) <= width
        start = lines.index("recent problems:") + 1
        got = []
        for ln in lines[start:]:
            if ln.startswith("      ") and got:
                got[-1] += " " + ln.strip()
            else:
                got.append(ln.strip())
        assert got == s["problems"], width  # broken at spaces only
        # the detections' list breaks between items: every "at (x px, y px)" whole on its line
        assert screen.count("at (1300 px, 700 px)") == 4


def test_tracked_objects_are_shown_when_their_frames_arrive():
    mon = Monitor(M)
    snd = Sender(M)
    feed_all(mon, [f for f in snd.cycle(0) if f[0] != 0x320], 0.0)
    s = mon.snapshot()
    assert s["tracker_seen"] is False
    assert "no SBR_TrackedObject frame received so far" in render(s, 80)
    mon.feed(0.05, 0x320, snd(0x320, SBR_Obj_TrackId=255))  # the ECU reports none
    s = mon.snapshot()
    assert s["tracker_seen"] is True and "tracked objects: none" in render(s, 80)
    mon.feed(0.1, 0x320, snd(0x320, SBR_Obj_TrackId=3, SBR_Obj_PosX=100, SBR_Obj_PosY=50))
    s = mon.snapshot()
    assert [o["track"] for o in s["objects"]] == [3] and "tracked objects: #3 at (100 px, 50 px)" in render(s, 80)


def test_overload_when_processing_exceeds_the_cycle():
    # SBR_EcuStatus's GenMsgCycleTime is 100 ms: 130 ms of processing is an overload,
    # as is the Overload bit (results dropped); 60 ms with the bit clear is none
    mon = Monitor(M)
    s = Sender(M)
    feed_all(mon, s.cycle(0, proc_ms=60.0), 0.0)
    assert mon.snapshot()["health"]["overload_now"] is False
    feed_all(mon, s.cycle(1, proc_ms=130.0), 0.1)
    feed_all(mon, s.cycle(2, proc_ms=125.0), 0.2)
    snap = mon.snapshot()
    h = snap["health"]
    assert h["cycle_ms"] == 100 and h["overload_now"] is True
    assert (h["flag_counts"]["overload"], h["flag_counts"]["late"], h["flag_counts"]["dropped"]) == (2, 2, 0)
    assert [p for p in snap["problems"] if "overload" in p] == \
        ["0.10 s SBR_EcuStatus overload: processing 130.0 ms > the 100 ms cycle"]  # once, when it began
    screen = render(snap, 100)
    assert "ECU: OVERLOAD," in screen and "processing 125.0 ms (mean 105.0 ms, cycle 100 ms)" in screen
    assert "overload 2 (late 2, dropped 0)" in screen
    feed_all(mon, s.cycle(3, proc_ms=50.0), 0.3)
    assert mon.snapshot()["health"]["overload_now"] is False


def test_a_refused_start_shuts_the_bus_down(caplog):
    # a bus opened, then the start refused (the page's port taken): close() lets go of it,
    # so python-can does not warn that it was "not properly shut down"
    import gc
    src = BusSource(Monitor(M), "virtual", "refused-start")
    src.close()
    del src
    gc.collect()
    assert "not properly shut down" not in caplog.text


# -- issue 70: every fault seen, nothing silent ------------------------------------------
def test_a_flood_of_one_problem_does_not_push_out_a_fault():
    # item 6: 300 late images (an overloaded host) and 500 bad log lines around one CRC
    # fault: the fault keeps its line; each flood is one line with its count and times
    mon = Monitor(M)
    snd = Sender(M)
    for k in range(300):
        proc = 130.0 if k % 2 == 0 else 60.0  # overload begins 150 times
        feed_all(mon, snd.cycle(k, proc_ms=proc), 0.1 * k)
        if k == 20:
            fid, data = snd.cycle(21)[0]
            bad = bytes([data[0] ^ 0xFF]) + data[1:]
            mon.feed(0.1 * k + 0.05, fid, bad)
    for n in range(500):
        mon.skipped(1000 + n, "not a candump line")
    p = mon.snapshot()["problems"]
    crc = [x for x in p if "CRC mismatch" in x]
    over = [x for x in p if " overload:" in x]
    log = [x for x in p if " log:" in x]
    assert len(crc) == 1 and len(over) == 1 and len(log) == 1, p
    assert "(150 times, first at 0.00 s)" in over[0], over
    assert "(500 times, first at" in log[0] and "line 1499 skipped" in log[0], log
    assert len(p) <= 20


def test_a_bad_crc_turns_the_message_state_to_a_fault():
    # item 6: one bad frame among good ones: the row shows the fault for FAULT_HOLD_S of
    # source time (not "ok" again at the next good frame), then ok
    from sbr_dashboard.monitor import FAULT_HOLD_S
    mon = Monitor(M)
    snd = Sender(M)
    feed_all(mon, snd.cycle(0), 0.0)
    fid, data = snd.cycle(1)[0]
    mon.feed(0.1, fid, bytes([data[0] ^ 0x5A]) + data[1:])
    name = M.messages[fid].name
    row = lambda: next(m for m in mon.snapshot()["messages"] if m["name"] == name)
    assert row()["state"] == "e2e error" and row()["crc"] == 1
    k = 2
    while 0.1 * k < 0.1 + FAULT_HOLD_S - 0.05:
        feed_all(mon, snd.cycle(k), 0.1 * k)
        assert row()["state"] == "e2e error", (0.1 * k, row()["state"])
        k += 1
    feed_all(mon, snd.cycle(k + 1), 0.1 * (k + 1))
    assert row()["state"] == "ok" and row()["crc"] == 1


@pytest.mark.parametrize("content", [b"", bytes(random.Random(7).randrange(256) for _ in range(4096))])
def test_a_log_without_frames_is_an_error(tmp_path, content):
    # item 7: an empty log or random bytes: "no CAN frame", exit 1 (not 0 with "frames 0")
    import subprocess
    import sys
    log = tmp_path / "x.log"
    log.write_bytes(content)
    r = subprocess.run([sys.executable, "-m", "sbr_dashboard", "--log", str(log), "--terminal", "--once", "--fast"],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "no CAN frame could be read" in r.stderr


@pytest.mark.parametrize("rate", ["nan", "inf", "0", "-1"])
def test_a_rate_that_is_not_a_speed_is_refused(tmp_path, rate):
    # item 8
    import subprocess
    import sys
    log = tmp_path / "x.log"
    log.write_text("(1700000000.000000) can0 300#0011223344556677\n")
    r = subprocess.run([sys.executable, "-m", "sbr_dashboard", "--log", str(log), "--terminal", "--once",
                        "--rate", rate], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and f"--rate {float(rate)}" in r.stderr, r.stderr


# -- the restrictions in force (SBR_Restrictions) ----------------------------------------
def test_restrictions_are_the_ecus_not_read_from_the_signs():
    mon = Monitor(M)
    s = Sender(M)
    # the ECU lists a 30 km/h sign, but says the limit in force is 50 (seen 12 s ago),
    # no overtaking and priority road
    feed_all(mon, s.cycle(0, signs=[(1, 30, 90, 0)], restr=(50, 1, 0, 1, 12)), 0.0)
    snap = mon.snapshot()
    assert snap["speed_limit"] == 50
    assert snap["restrictions"] == dict(speed_limit=50, no_overtaking=True, no_overtaking_trucks=False,
                                        priority_road=True, speed_age_s=12)
    # the limit ends: none shown, however many speed signs are listed
    feed_all(mon, s.cycle(1, signs=[(1, 30, 90, 1)], restr=(0, 0, 1, 0, 0)), 0.1)
    snap = mon.snapshot()
    assert snap["speed_limit"] is None and snap["restrictions"]["no_overtaking_trucks"] is True
    assert snap["totals"]["e2e_errors"] == 0


def test_without_restrictions_the_limit_is_read_from_the_signs():
    mon = Monitor(M)
    feed_all(mon, Sender(M).cycle(0, signs=[(1, 30, 90, 0)]), 0.0)
    snap = mon.snapshot()
    assert snap["restrictions"] is None and snap["speed_limit"] == 30
