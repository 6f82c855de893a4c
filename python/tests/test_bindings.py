# SPDX-License-Identifier: MIT
"""The sbr package against the C tools and hostile input (ctest python_package).

Environment: SBR_DETECT (the sbr_detect binary), SBR_DATA (the GTSDB folder); the tests
that need them are skipped without.
  - the bindings on real GTSDB frames write byte-identical detection lines to sbr_detect's
    (every detection down to 0.05, and at the operating point), with the same pixels
    (Pillow's JPEG decoding equals OpenCV's on these files; checked);
  - RGB and BGR orders, grey frames, a crop (a row stride larger than the row) and a ROI
    give what the core gives on the same pixels;
  - wrong dtype, 0-size, huge, non-contiguous, wrong channel counts and non-arrays raise
    ValueError/TypeError with what is wrong; configuration fields out of range raise
    ValueError naming the field;
  - the GIL is released while the core runs: another thread makes progress during one
    detect() call, and results from two threads equal the serial ones.
"""
import os
import subprocess
import threading

import numpy as np
import pytest

import sbr

DATA = os.environ.get("SBR_DATA", "")
DETECT = os.environ.get("SBR_DETECT", "")
IMAGES = os.path.join(DATA, "FullIJCNN2013") if os.path.isdir(os.path.join(DATA, "FullIJCNN2013")) else DATA
need_data = pytest.mark.skipif(not (DATA and os.path.isdir(IMAGES) and DETECT), reason="SBR_DATA/SBR_DETECT not set")


def load(n):
    from PIL import Image
    return np.asarray(Image.open(os.path.join(IMAGES, f"{n:05d}.jpg")).convert("RGB"))


@pytest.fixture(scope="module")
def rec():
    return sbr.Recognizer()


@need_data
def test_detections_byte_identical_to_sbr_detect(tmp_path):
    first, last = 400, 409
    subprocess.run([DETECT, "--input", DATA, "--range", f"{first}-{last}", "--quiet",
                    "--detections", str(tmp_path / "det.txt"), "--all-detections", str(tmp_path / "all.txt")],
                   check=True, stdout=subprocess.DEVNULL)
    r0 = sbr.Recognizer()
    r = sbr.Recognizer(min_score=min(r0.config["min_score"], 0.05))  # sbr_detect --all-detections
    all_lines, op_lines = [], []
    for n in range(first, last + 1):
        for d in r.detect(load(n), order="rgb"):
            line = d.gtsdb_line(f"{n:05d}.jpg")
            all_lines.append(line)
            if d.score >= r.threshold:
                op_lines.append(line)
    want_all = (tmp_path / "all.txt").read_text()
    want_op = (tmp_path / "det.txt").read_text()
    assert want_all.count("\n") >= 10, "too few detections to compare"
    assert "".join(l + "\n" for l in all_lines) == want_all
    assert "".join(l + "\n" for l in op_lines) == want_op
    assert set(r.last_stats["stage_ms"]) == {"parts", "votes", "group", "verify", "nms", "class"}
    assert r.last_stats["parts"] > 0
    assert 0 < r.last_stats["outlines"] <= r.config["max_outline_candidates"] == 64


@need_data
def test_strips_byte_identical_to_sbr_detect(tmp_path):
    """The strip configuration (strips=True) writes sbr_detect --strips's lines."""
    first, last = 400, 404
    subprocess.run([DETECT, "--input", DATA, "--range", f"{first}-{last}", "--quiet", "--strips",
                    "--detections", str(tmp_path / "det.txt"), "--all-detections", str(tmp_path / "all.txt")],
                   check=True, stdout=subprocess.DEVNULL)
    r = sbr.Recognizer(strips=True, min_score=0.05)
    lines = [d.gtsdb_line(f"{n:05d}.jpg") for n in range(first, last + 1) for d in r.detect(load(n), order="rgb")]
    want = (tmp_path / "all.txt").read_text()
    assert want.count("\n") >= 5, "too few detections to compare"
    assert "".join(l + "\n" for l in lines) == want
    assert r.config["max_candidates"] == 96 and r.config["max_heap"] == 70000
    assert r.workspace_size(1360, 800) == 1942760
    with pytest.raises(ValueError, match="roi"):
        r.detect(load(first), roi=(0, 0, 100, 100))


@need_data
def test_orders_grey_crops_and_roi_agree(rec):
    rgb = np.ascontiguousarray(load(444))
    bgr = np.ascontiguousarray(rgb[:, :, ::-1])
    a = rec.detect(rgb, order="rgb")
    assert a and a == rec.detect(bgr)  # bgr is the default order
    # a crop is a view with the frame's row stride: the same as a contiguous copy of it
    crop = bgr[300:700, 200:1200]
    assert crop.strides[0] == bgr.strides[0] and not crop.flags["C_CONTIGUOUS"]
    assert rec.detect(crop) == rec.detect(np.ascontiguousarray(crop))
    # a ROI's boxes are in frame pixels and equal those of the crop, shifted
    roi = rec.detect(bgr, roi=(200, 300, 1000, 400))
    shifted = [sbr.Detection(d.class_id, (d.box[0] + 200, d.box[1] + 300, d.box[2], d.box[3]), d.score, d.share,
                             d.parts) for d in rec.detect(crop)]
    assert roi == shifted
    grey = np.ascontiguousarray(rgb.mean(axis=2).round().astype(np.uint8))
    g2 = rec.detect(grey)
    assert g2 == rec.detect(grey[:, :, None])
    assert all(0 <= d.class_id < 43 for d in g2)
    assert [d.class_name for d in a][:2] == [sbr.class_name(d.class_id) for d in a][:2]


@pytest.mark.parametrize("image, kind, text", [
    (np.zeros((64, 64, 3), np.float32), ValueError, "dtype uint8"),
    (np.zeros((64, 64, 3), np.uint16), ValueError, "dtype uint8"),
    (np.zeros((0, 64, 3), np.uint8), ValueError, "empty"),
    (np.zeros((64, 0), np.uint8), ValueError, "empty"),
    (np.zeros((64, 64, 4), np.uint8), ValueError, "H x W x 3"),
    (np.zeros((64, 64, 2), np.uint8), ValueError, "H x W x 3"),
    (np.zeros((4, 64, 64, 3), np.uint8), ValueError, "H x W x 3"),
    (np.zeros((64,), np.uint8), ValueError, "H x W x 3"),
    (np.zeros((64, 128, 3), np.uint8)[:, ::2], ValueError, "contiguous"),
    (np.zeros((64, 64, 3), np.uint8).transpose(1, 0, 2), ValueError, "contiguous"),
    (np.zeros((64, 64, 3), np.uint8)[::-1], ValueError, "contiguous"),
    (np.zeros((64, 64, 6), np.uint8)[:, :, ::2], ValueError, "contiguous"),
    (np.zeros((16400, 8, 3), np.uint8), ValueError, "largest side"),
    (np.zeros((2, 2, 3), np.uint8), ValueError, "too small"),
    ([[1, 2], [3, 4]], TypeError, "numpy array"),
    (None, TypeError, "numpy array"),
])
def test_hostile_arrays_raise_clear_errors(rec, image, kind, text):
    with pytest.raises(kind, match=text):
        rec.detect(image)


def test_bad_roi_order_and_config(rec):
    img = np.zeros((96, 160, 3), np.uint8)
    with pytest.raises(ValueError, match="RANGE"):
        rec.detect(img, roi=(100, 20, 84, 64))  # leaves the frame
    with pytest.raises(ValueError, match="roi"):
        rec.detect(img, roi=(1, 2, 3))
    with pytest.raises(ValueError, match="roi"):
        rec.detect(img, roi=(-1, 0, 10, 10))
    with pytest.raises(ValueError, match="order"):
        rec.detect(img, order="bgra")
    for field, value in [("views", 0), ("nms_iou", 2.0), ("verify_error", float("nan")), ("max_parts", 0),
                         ("vote_error", -1.0), ("min_score", float("inf"))]:
        with pytest.raises(ValueError, match=field):
            sbr.Recognizer(**{field: value})
    with pytest.raises(ValueError, match="unknown configuration field: bogus"):
        sbr.Recognizer(bogus=1)
    with pytest.raises(ValueError, match="integer"):
        sbr.Recognizer(views=1.5)
    with pytest.raises(ValueError, match="out of range"):
        sbr.Recognizer(max_parts=-3)
    with pytest.raises(ValueError, match="model"):
        sbr.Recognizer(model="/no/such/file.sbrm")
    r = sbr.Recognizer({"views": 3}, max_candidates=128)
    assert r.config["views"] == 3 and r.config["max_candidates"] == 128
    assert set(sbr.CONFIG_FIELDS) == set(r.config)
    assert r.config["outline_maps"] == 6  # the red and blue maps' outline candidates
    assert sbr.Recognizer(outline_maps=0).config["outline_maps"] == 0
    with pytest.raises(ValueError, match="outline_maps"):
        sbr.Recognizer(outline_maps=16)
    assert r.workspace_size(1360, 800) == sbr.Recognizer().workspace_size(1360, 800) == 7193960


def test_config_table_is_the_core_table():
    """Every keyword is a field of the core's tables (sbr.CONFIG_TABLE): a Recognizer
    starts at each one's default, and one step beyond either end of its range is refused
    with the field's name (the strip-free defaults; min_score is the operating point)."""
    assert list(sbr.CONFIG_TABLE) == list(sbr.CONFIG_FIELDS)
    r = sbr.Recognizer()
    for name, (kind, count, lo, hi, default, meaning) in sbr.CONFIG_TABLE.items():
        assert meaning and kind in ("int", "float")
        if name != "min_score":
            assert r.config[name] == pytest.approx(default), name
        if kind == "int":
            beyond = [hi + 1] + ([lo - 1] if lo > 0 else [])
            if count > 1:
                beyond = [[v] * count for v in beyond]
        else:
            beyond = [hi * 1.001 + 1e-3, lo - 1e-3 * (1 + abs(lo))]
        for v in beyond:
            with pytest.raises(ValueError, match=name):
                sbr.Recognizer(**{name: v})
    # the per-map-kind lists: the first 1..4 values (intensity, red, blue, yellow)
    assert sbr.Recognizer(map_polarity=[3, 3]).config["map_polarity"] == [3, 3, 0, 0]
    with pytest.raises(ValueError, match="map_polarity"):
        sbr.Recognizer(map_polarity=[1, 2, 3, 0, 1])
    # a rule between fields names the field it blames
    with pytest.raises(ValueError, match="max_size"):
        sbr.Recognizer(min_size=50.0, max_size=20.0)
    # the class stage's looks are the model's; a keyword sets the copy in use
    assert r.config["refine_score"] == pytest.approx(0.001)
    assert sbr.Recognizer(refine_score=0.5).config["refine_score"] == pytest.approx(0.5)
    with pytest.raises(ValueError, match="a look of the class stage"):
        sbr.Recognizer(no_picto=True, view_score=0.2)


def test_gil_released_and_threads_agree():
    rng = np.random.default_rng(7)
    frames = [rng.integers(0, 256, (400, 680, 3), dtype=np.uint8) for _ in range(4)]
    for f in frames:  # some structure to find regions in
        f[100:200, 100:200] = 240
        f[120:180, 300:420] = 20
    rec = sbr.Recognizer()
    serial = [rec.detect(f) for f in frames]
    ticks = []
    stop = threading.Event()

    def counter():
        while not stop.is_set():
            ticks.append(1)

    t = threading.Thread(target=counter)
    t.start()
    before = len(ticks)
    for f in frames:  # the counter runs only if detect() lets go of the GIL
        rec.detect(f)
    during = len(ticks) - before
    stop.set()
    t.join()
    assert during > 100, during
    out = [None] * len(frames)

    def work(i):
        out[i] = rec.detect(frames[i])

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(frames))]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert out == serial
