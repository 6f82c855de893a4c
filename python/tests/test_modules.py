# SPDX-License-Identifier: MIT
"""sbr.Tracker, sbr.ellipse_fit, sbr.fd and sbr.can against known geometry, the DBC read by
cantools (an independent decoder) and hostile input.

Expected values are the truth of the constructed input (a target's real path, an
ellipse's real parameters, a shape's real rotation, scale and start shift, the DBC's own
layout), not figures the code produced.
"""
import math
import os
import re

import numpy as np
import pytest

import sbr
from sbr import can, fd

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DBC = os.path.join(ROOT, "dbc", "sbr.dbc")


# --- Tracker ---------------------------------------------------------------------------

def _det(x, y, w, cls, score):
    return sbr.Detection(cls, (int(x - w / 2), int(y - w / 2), int(w), int(w)), score, 1.0, 3)


def test_sign_tracker_names_a_sign_by_its_evidence_once_per_pass():
    st = sbr.SignTracker(1360, 800, 0.1)
    assert st.config["confirm_hits"] == 2 and st.config["confirm_share"] == pytest.approx(0.6)
    news, ids = [], set()
    for f in range(12):
        dets = []
        if f < 8:  # a 50 km/h sign passing, taken for 60 in frame 4
            dets.append(_det(800 + 10 * f, 300 - 4 * f, 30 + 2 * f, 3 if f == 4 else 2, 0.9))
        if f == 5:  # a one-frame false detection
            dets.append(_det(200, 600, 40, 25, 0.8))
        signs, det_sign = st.update(dets, time=0.1 * f)
        assert len(det_sign) == len(dets)
        news += [s for s in signs if s.new]
        ids |= {s.id for s in signs}
        if f == 5:
            assert det_sign[1] == 0  # never confirmed
        if 1 <= f < 8:
            assert len(signs) == 1 and signs[0].class_id == 2 and signs[0].class_name == "SpeedLimit50"
            assert det_sign[0] == signs[0].id and not signs[0].renamed
    assert [(s.class_id, s.frames) for s in news] == [(2, 0)] and len(ids) == 1
    with pytest.raises(ValueError, match="confirm_share"):
        sbr.SignTracker(confirm_share=1.5)
    with pytest.raises(ValueError, match="unknown sign-tracking field"):
        sbr.SignTracker(window=9)
    with pytest.raises(ValueError, match="time"):
        st.update([], time=0.5)  # not after the previous frame's


def test_tracker_follows_two_targets_with_stable_ids():
    trk = sbr.Tracker("cv", width=640, height=480, period=0.1, window=31, meas_sigma=4.0)
    rng = np.random.default_rng(3)
    for k in range(12):
        truth = np.array([[100 + 10 * k, 200], [500 - 6 * k, 100 + 3 * k]], np.float64)
        noisy = truth + rng.normal(0, 0.5, truth.shape)
        targets = trk.step(noisy[::-1] if k % 2 else noisy)  # order of the detections changes
    assert len(targets) == 2 and all(t.confirmed and t.updated for t in targets)
    assert sorted(t.id for t in targets) == [1, 2]  # no target was lost and reborn
    a = min(targets, key=lambda t: t.x)
    b = max(targets, key=lambda t: t.x)
    assert abs(a.x - 210) < 2 and abs(a.y - 200) < 2 and abs(a.vx - 10) < 1.5 and abs(a.vy) < 1.5
    assert abs(b.x - 434) < 2 and abs(b.y - 133) < 2 and abs(b.vx + 6) < 1.5 and abs(b.vy - 3) < 1.5
    assert trk.workspace_size > 0 and trk.config["window"] == 31 and not trk.capacity_hit


def test_tracker_coasts_confirms_and_resets():
    trk = sbr.Tracker("cv", width=640, height=480, confirm_hits=3, max_misses=2, window=31, meas_sigma=4.0)
    first = trk.step([[300.0, 240.0, 0.9]])
    assert len(first) == 1 and first[0].born and not first[0].confirmed and first[0].detection == 0
    trk.step([[308.0, 240.0]])
    third = trk.step([[316.0, 240.0]])
    assert third[0].confirmed and third[0].hits == 3
    coast = trk.step([])  # a miss: the target coasts on its prediction
    assert coast[0].misses == 1 and coast[0].detection is None and abs(coast[0].x - 324) < 3
    trk.step(np.zeros((0, 3)))
    assert trk.step([]) == []  # more than max_misses consecutive misses
    trk.reset()
    assert trk.step([[10.0, 10.0]])[0].id == 1  # ids start again


def test_tracker_takes_recogniser_detections_and_the_kitti_model():
    trk = sbr.Tracker()  # the learned KITTI model
    assert trk.extent == (1242.0, 375.0) and trk.config["window"] == 25 and trk.period == pytest.approx(0.1)
    dets = [sbr.Detection(1, (100, 150, 40, 20), 0.8, 1.0, 3)]
    t = trk.step(dets)
    assert len(t) == 1 and (t[0].x, t[0].y) == (pytest.approx(120, abs=2), pytest.approx(160, abs=2))


@pytest.mark.parametrize("kwargs,text", [
    (dict(window=30), "window"),
    (dict(gate=-1.0), "gate"),
    (dict(meas_sigma=float("nan")), "meas_sigma"),
    (dict(max_targets=0), "max_targets"),
    (dict(confirm_hits=99), "confirm_hits"),
    (dict(speed=3), "unknown tracker field: speed"),
    (dict(model="ukf"), "model"),
    (dict(model="cv"), "width and height"),
    (dict(model="cv", width=640, height=480, vel_count=40), "constant-velocity model"),
])
def test_tracker_refuses_bad_configuration(kwargs, text):
    with pytest.raises(ValueError, match=text):
        sbr.Tracker(**kwargs)


@pytest.mark.parametrize("dets,dt,text", [
    ([[float("nan"), 10.0]], None, "step"),
    ([[2000.0, 10.0]], None, "step"),  # outside the 1242 x 375 image
    ([[10.0, 10.0, 1.5]], None, "step"),  # certainty above 1
    ([[1.0, 2.0, 3.0, 4.0]], None, "N x 2 or N x 3"),
    (np.zeros((300, 3)), None, "at most 256"),
    ([[10.0, 10.0]], 0.0, "dt"),
    ([[10.0, 10.0]], 1e9, "dt"),
])
def test_tracker_refuses_bad_steps_and_stays_usable(dets, dt, text):
    trk = sbr.Tracker()
    with pytest.raises(ValueError, match=text):
        trk.step(dets, dt)
    assert trk.step([[10.0, 10.0]])[0].id == 1  # the refused step changed nothing


# --- ellipse_fit -------------------------------------------------------------------------

def ellipse_points(cx, cy, a, b, angle, n=60, noise=0.0, arc=2 * math.pi, seed=0):
    t = np.linspace(0, arc, n, endpoint=False)
    x, y = a * np.cos(t), b * np.sin(t)
    c, s = math.cos(angle), math.sin(angle)
    pts = np.stack([cx + c * x - s * y, cy + s * x + c * y], 1)
    return pts + np.random.default_rng(seed).normal(0, noise, pts.shape)


def test_ellipse_fit_recovers_the_ellipse():
    e = sbr.ellipse_fit(ellipse_points(320.5, 240.25, 80, 30, 0.6, noise=0.3))
    assert (e.cx, e.cy) == (pytest.approx(320.5, abs=0.3), pytest.approx(240.25, abs=0.3))
    assert (e.semi_major, e.semi_minor) == (pytest.approx(80, abs=0.5), pytest.approx(30, abs=0.5))
    assert e.angle == pytest.approx(0.6, abs=0.01)
    assert 0.1 < e.rms < 0.6 and e.max_residual >= e.rms  # about the noise's sigma
    a, b, c, d, ee, f = e.conic  # the centre satisfies the conic's gradient = 0
    assert abs(a * e.cx + b * e.cy + d) < 1e-4 * max(map(abs, e.conic)) * 10 and abs(b * e.cx + c * e.cy + ee) < 1e-3


def test_ellipse_fit_on_an_arc_and_opencv_layout():
    arc = ellipse_points(100, 60, 40, 25, -0.3, n=30, arc=math.pi)  # half an ellipse
    e = sbr.ellipse_fit(np.round(arc).astype(np.int32).reshape(-1, 1, 2))  # as cv2.findContours gives
    assert (e.cx, e.cy, e.semi_major, e.semi_minor) == (
        pytest.approx(100, abs=2), pytest.approx(60, abs=2), pytest.approx(40, abs=3), pytest.approx(25, abs=3))


@pytest.mark.parametrize("points,text", [
    (np.array([[0, 0], [1, 1], [2, 2], [3, 3], [4, 4], [5, 5]], float), "DEGENERATE"),
    (np.array([[0, 0], [1, 0], [0, 1], [1, 1]], float), "SIZE"),
    (np.array([[0, 0], [1, 0], [0, 1], [1, 1], [np.nan, 2]], float), "RANGE"),
    (np.zeros((5, 3)), "N x 2"),
    (np.array([[1 + 1j, 2], [3, 4]]), "real coordinates"),
])
def test_ellipse_fit_refuses(points, text):
    with pytest.raises(ValueError, match=text):
        sbr.ellipse_fit(points)


# --- fd ----------------------------------------------------------------------------------

L_SHAPE = np.array([[0, 0], [40, 0], [40, 10], [10, 10], [10, 60], [0, 60]], float)


def densify(poly, per_edge=20):
    out = []
    for i in range(len(poly)):
        p, q = poly[i], poly[(i + 1) % len(poly)]
        for t in np.arange(per_edge) / per_edge:
            out.append(p + t * (q - p))
    return np.array(out)


def rotate(pts, theta, scale=1.0, shift=(0.0, 0.0)):
    c, s = math.cos(theta), math.sin(theta)
    return scale * pts @ np.array([[c, s], [-s, c]]) + np.array(shift)


def test_fd_match_gives_rotation_scale_and_start_shift():
    base = densify(L_SHAPE)
    proto = fd.descriptor(base)
    assert proto.m == 12 and proto.coefficients.shape == (25,) and proto.coefficients[12] == 0
    moved = np.roll(rotate(base, 0.5, 2.0, (300, 100)), -len(base) // 4, axis=0)  # starts a quarter later
    q = fd.descriptor(moved)
    m = fd.match(q, proto, mode="invariant")  # any rotation matches
    assert m.error < 1e-3
    assert m.rotation == pytest.approx(0.5, abs=0.01)
    assert m.scale_ratio == pytest.approx(2.0, rel=0.01)
    assert m.shift == pytest.approx(0.225, abs=0.01)  # 30 points: edge 0 (40) + half edge 1 (5) of 200
    poly = rotate(L_SHAPE, 0.5, 2.0, (300, 100))  # the boundary's centroid (by arc length)
    edges = np.roll(poly, -1, axis=0) - poly
    lengths = np.hypot(edges[:, 0], edges[:, 1])
    centre = ((poly + edges / 2) * lengths[:, None]).sum(0) / lengths.sum()
    assert q.centroid == (pytest.approx(centre[0], abs=0.2), pytest.approx(centre[1], abs=0.2))
    # rotation covariant (the default): the turn costs, at most 2 - 2 cos(0.5) at the true lag;
    # upright, the same shape matches exactly; a rotation bound below the turn refuses it
    cov = fd.match(q, proto)
    assert 0.1 < cov.error <= 2 - 2 * math.cos(0.5) + 1e-3
    upright = fd.descriptor(np.roll(2.0 * base + np.array([300, 100]), -len(base) // 4, axis=0))
    assert fd.match(upright, proto).error < 1e-3
    assert fd.match(q, proto, max_rotation=0.2).error > cov.error


def test_fd_match_table_mirror_and_roundtrip():
    base = densify(L_SHAPE)
    mirrored = base * np.array([-1.0, 1.0])  # x -> -x, traced in the other direction
    q = fd.descriptor(mirrored[::-1])  # traced in the same direction again
    p = fd.descriptor(base)
    results, best = fd.match_table(q, [p, p.mirror()], mode="invariant")
    assert best == 1 and results[1].error < 1e-3 and results[0].error > 0.05  # an L is not its mirror image
    again = fd.from_coefficients(p.coefficients, p.scale, p.centroid)
    assert fd.match(again, p).error == pytest.approx(0.0, abs=1e-6)
    smooth = p.smooth(0.02)
    assert 0.0 < fd.match(smooth, p).error < 0.2


@pytest.mark.parametrize("call,text", [
    (lambda: fd.descriptor([[0, 0], [1, 1]]), "DEGENERATE"),
    (lambda: fd.descriptor(densify(L_SHAPE), m=33), "SIZE"),
    (lambda: fd.descriptor(densify(L_SHAPE), samples=100), "samples"),
    (lambda: fd.descriptor(np.array([[0, 0], [1, 0], [np.inf, 1]])), "RANGE"),
    (lambda: fd.from_coefficients(np.full(25, np.nan, np.complex64)), "RANGE"),
    (lambda: fd.from_coefficients(np.ones(24, np.complex64)), "2M \\+ 1"),
    (lambda: fd.from_coefficients(np.ones(25, np.complex64), scale=0.0), "RANGE"),
    (lambda: fd.match(fd.descriptor(densify(L_SHAPE)), fd.descriptor(densify(L_SHAPE), m=8)), "SIZE"),
    (lambda: fd.match_table(fd.descriptor(densify(L_SHAPE)), []), "at least one"),
    (lambda: fd.match(fd.descriptor(densify(L_SHAPE)), fd.descriptor(densify(L_SHAPE)), mode="x"), "mode"),
    (lambda: fd.match(fd.descriptor(densify(L_SHAPE)), fd.descriptor(densify(L_SHAPE)),
                      max_rotation=float("nan")), "RANGE"),
])
def test_fd_refuses(call, text):
    with pytest.raises(ValueError, match=text):
        call()


# --- can ---------------------------------------------------------------------------------

SAMPLES = {
    "SBR_Detection": dict(class_id=14, confidence=88.0, center_x=612.0, center_y=410.0, width=32.0, height=28.0,
                          track_id=5),
    "SBR_ConfirmedSign": dict(slot=1, count=2, class_id=2, track_id=17, speed_kmh=50, confidence=93.0,
                              age_frames=12),
    "SBR_TrackedObject": dict(index=3, track_id=200, x=1021.0, y=377.0, vx=-40.0, vy=12.0, certainty=64.0),
    "SBR_EcuStatus": dict(frame_counter=54321, processing_ms=87.3, region_count=1234, detection_count=7,
                          overload=1, error=0, capacity_hit=1),
    "SBR_Restrictions": dict(speed_limit_kmh=70, no_overtaking=1, no_overtaking_trucks=0, priority_road=1,
                             speed_age_s=345),
}
# the DBC's signal name (cantools) of each of the core's fields
DBC_NAMES = {
    "SBR_Detection": dict(class_id="SBR_Det_Class", confidence="SBR_Det_Confidence", center_x="SBR_Det_CenterX",
                          center_y="SBR_Det_CenterY", width="SBR_Det_Width", height="SBR_Det_Height",
                          track_id="SBR_Det_TrackId"),
    "SBR_ConfirmedSign": dict(slot="SBR_Sign_Slot", count="SBR_Sign_Count", class_id="SBR_Sign_Class",
                              track_id="SBR_Sign_TrackId", speed_kmh="SBR_Sign_SpeedLimit",
                              confidence="SBR_Sign_Confidence", age_frames="SBR_Sign_AgeFrames"),
    "SBR_TrackedObject": dict(index="SBR_Obj_Index", track_id="SBR_Obj_TrackId", x="SBR_Obj_PosX", y="SBR_Obj_PosY",
                              vx="SBR_Obj_VelX", vy="SBR_Obj_VelY", certainty="SBR_Obj_Certainty"),
    "SBR_EcuStatus": dict(frame_counter="SBR_Status_FrameCounter", processing_ms="SBR_Status_ProcessingTime",
                          region_count="SBR_Status_RegionCount", detection_count="SBR_Status_DetectionCount",
                          overload="SBR_Status_Overload", error="SBR_Status_Error",
                          capacity_hit="SBR_Status_CapacityHit"),
    "SBR_Restrictions": dict(speed_limit_kmh="SBR_Restr_SpeedLimit", no_overtaking="SBR_Restr_NoOvertaking",
                             no_overtaking_trucks="SBR_Restr_NoOvertakingTrucks",
                             priority_road="SBR_Restr_PriorityRoad", speed_age_s="SBR_Restr_SpeedAge"),
}


@pytest.mark.parametrize("name", sorted(SAMPLES))
def test_can_pack_matches_the_dbc_and_round_trips(name):
    cantools = pytest.importorskip("cantools")
    db = cantools.database.load_file(DBC, strict=True)
    fid, data = can.pack(name, **SAMPLES[name])
    assert fid == db.get_message_by_name(name).frame_id == can.MESSAGES[name][0] and len(data) == 8
    decoded = db.decode_message(fid, data, decode_choices=False)
    for field, value in SAMPLES[name].items():
        assert decoded[DBC_NAMES[name][field]] == pytest.approx(value, abs=0.05), field
    back_name, back = can.unpack(fid, data)
    assert back_name == name and back == pytest.approx(SAMPLES[name], abs=0.05)


def test_can_e2e_equals_the_dashboards_and_detects_faults():
    import sys
    sys.path.insert(0, os.path.join(ROOT, "dashboard"))
    try:
        from sbr_dashboard.dbc import DbcModel
    except ImportError:
        pytest.skip("the dashboard's dependencies are not installed")
    finally:
        sys.path.pop(0)
    model = DbcModel(DBC)
    assert can.crc8(b"123456789") == 0x4B  # CRC-8/SAE-J1850's check value
    tx, rx = can.Sender(), can.Receiver(0x310)
    fid, raw = can.pack("SBR_Detection", **SAMPLES["SBR_Detection"])
    frames = [tx.protect(fid, raw) for _ in range(3)]
    assert [f[1] & 0x0F for f in frames] == [0, 1, 2]  # the alive counter
    assert all(model.protect(fid, f) == f for f in frames)  # the dashboard's CRC, from the DBC
    assert rx.check(frames[0]) == "first" and rx.check(frames[1]) == "ok"
    with pytest.raises(can.E2EError) as err:
        rx.check(frames[1])
    assert err.value.result == "repeated"
    bad = bytearray(frames[2])
    bad[4] ^= 0x10
    for data, fid2, result in [(bytes(bad), None, "wrong_crc"), (frames[2][:7], None, "wrong_length"),
                               (frames[2], 0x320, "wrong_id")]:
        with pytest.raises(can.E2EError) as err:
            rx.check(data, fid2)
        assert err.value.result == result
    assert rx.check(frames[2]) == "ok"
    tx.protect(fid, raw)  # a frame lost on the bus
    with pytest.raises(can.E2EError) as err:
        rx.check(tx.protect(fid, raw))
    assert err.value.result == "skipped"
    assert rx.check(tx.protect(fid, raw)) == "ok"  # the state followed the new counter


@pytest.mark.parametrize("call,text", [
    (lambda: can.pack("SBR_Detection", **dict(SAMPLES["SBR_Detection"], confidence=101.0)), "range"),
    (lambda: can.pack("SBR_Detection", **dict(SAMPLES["SBR_Detection"], center_x=float("nan"))), "range"),
    (lambda: can.pack("SBR_Detection", **dict(SAMPLES["SBR_Detection"], class_id=-1)), "range"),
    (lambda: can.pack("SBR_Detection", **dict(SAMPLES["SBR_Detection"], colour=1)), "unknown signal colour"),
    (lambda: can.pack("SBR_Detection", class_id=1), "missing"),
    (lambda: can.pack("SBR_Speed", a=1), "unknown message"),
    (lambda: can.unpack(0x123, bytes(8)), "not an sbr message"),
    (lambda: can.unpack(0x310, bytes(7)), "8 data bytes"),
    (lambda: can.unpack(0x310, bytes([0, 0xF0 | 0, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF])), "outside its range"),
    (lambda: can.Receiver(0x123), "RANGE"),
    (lambda: can.Sender().protect(0x123, bytes(8)), "RANGE"),
])
def test_can_refuses(call, text):
    with pytest.raises(ValueError, match=text):
        call()


def test_evaluate_scores_constructed_files(tmp_path):
    # two images: a found 70 sign, a false give-way sign, a missed road-works sign; and the
    # same detections as their own baseline
    gt = tmp_path / "gt.txt"
    gt.write_text("00001.ppm;10;10;49;49;4\n00002.ppm;100;100;139;139;25\n")
    det = tmp_path / "det.txt"
    det.write_text("00001.jpg;11;11;49;49;4;0.9\n00002.jpg;300;300;339;339;13;0.8\n")
    plot = tmp_path / "pr.png"
    ev = sbr.evaluate(str(det), str(gt), threshold=0.5, baseline=str(det), max_drop=0.0, plot=str(plot))
    cl = ev.figures["eval"]["class_level"]
    assert (cl["tp"], cl["fp"], cl["fn"]) == (1, 1, 1)
    sc = ev.figures["eval"]["superclasses"]
    assert (sc["prohibitory"]["tp"], sc["danger"]["fn"], sc["other"]["fp"]) == (1, 1, 1)
    assert re.search(r"^4 +1 +0 +0 +1\.0000 +1\.0000 +1\.0000  SpeedLimit70$", ev.text, re.M), ev.text
    assert "25 Construction" in ev.text and "13 GiveWay" in ev.text
    assert ev.worst_drop == 0.0 and not ev.regression
    assert ev.text.splitlines()[-1].startswith("superclass_ap prohibitory=1.0000")
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    only_first = sbr.evaluate(str(det), str(gt), images=[1])
    assert only_first.figures["images"] == 1 and only_first.figures["gt"] == 1


def test_evaluate_names_what_it_cannot_read(tmp_path):
    gt = tmp_path / "gt.txt"
    gt.write_text("00001.ppm;10;10;49;49;4\n")
    with pytest.raises(ValueError, match="missing.txt: cannot open it"):
        sbr.evaluate(str(tmp_path / "missing.txt"), str(gt))
    bad = tmp_path / "bad.txt"
    bad.write_text("00001.jpg;1;2;3;4;5\n00001.jpg;1;2\n")
    with pytest.raises(ValueError, match="bad.txt:2: not a detection line"):
        sbr.evaluate(str(bad), str(gt))
    with pytest.raises(ValueError, match="threshold"):
        sbr.evaluate(str(gt), str(gt), threshold=2.0)
