#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A recorded drive as a video file through sbr_detect (issue: recorded drives as video).

usage: test_video.py --tools DIR --image FRAME --dbc DBC --work DIR

The video is made here from one recorded frame (sbr_make_drive: the camera moving towards
the image centre, 30 frames at 10 per second); no video is kept in the repository. Then:
  - the whole video: exit 0; the frames' times in the CAN log are the file's (100 ms
    apart); each sign of the scene is confirmed once (SBR_ConfirmedSign with age 0 once
    per track id); the limit in force (SBR_Restrictions) is the scene's 100 km/h from the
    frame after its first detection to the end; the annotated video holds every frame
    (sbr_detect reads it back);
  - the video cut to 60 % of its bytes: exit 3, the file named with the frame it ends at,
    the frames before it in the detections file;
  - a file that is not a video: exit 2, named, nothing written.
"""
import argparse
import os
import re
import subprocess
import sys


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def test_whole_video(a, video, work):
    det, log, ann = (os.path.join(work, n) for n in ("det.txt", "can.log", "annotated.avi"))
    r = run([os.path.join(a.tools, "sbr_detect"), "--input", video, "--detections", det, "--canlog", log,
             "--annotated-video", ann, "--quiet"])
    assert r.returncode == 0, r.stderr
    import cantools
    db = cantools.database.load_file(a.dbc)
    times, confirmed, limits = [], {}, []
    for line in open(log):
        t, _, fr = line.split()
        fid, data = fr.split("#")
        fid, data = int(fid, 16), bytes.fromhex(data)
        d = db.decode_message(fid, data, decode_choices=False)
        t = float(t.strip("()"))
        if fid == 0x301:
            times.append(t)
        if fid == 0x300 and d["SBR_Sign_Class"] != 255 and d["SBR_Sign_AgeFrames"] == 0:
            confirmed.setdefault(d["SBR_Sign_TrackId"], []).append((t, d["SBR_Sign_Class"]))
        if fid == 0x302:
            limits.append(d["SBR_Restr_SpeedLimit"])
    steps = {round(b - a_, 3) for a_, b in zip(times, times[1:])}
    assert len(times) == 30 and steps == {0.1}, (len(times), steps)
    assert all(len(v) == 1 for v in confirmed.values()), confirmed  # once per pass
    classes = sorted(c for v in confirmed.values() for _, c in v)
    assert classes.count(7) >= 1, classes  # the 100 km/h sign
    assert limits[-1] == 100 and limits.count(100) >= 25, limits
    r = run([os.path.join(a.tools, "sbr_detect"), "--input", ann, "--detections", os.path.join(work, "det2.txt"),
             "--quiet"])
    m = re.search(r"\((\d+) frames of a video", r.stdout)
    assert r.returncode == 0 and m and int(m.group(1)) == 30, (r.returncode, r.stdout[:300], r.stderr[-300:])
    print(f"whole video: 30 frames 100 ms apart, signs confirmed once each (classes {classes}), "
          f"limit in force {limits[-1]} km/h in {limits.count(100)} of 30 frames, annotated video of 30 frames")


def test_truncated_video(a, video, work):
    cut = os.path.join(work, "cut.avi")
    with open(video, "rb") as f:
        data = f.read()
    with open(cut, "wb") as f:
        f.write(data[:int(len(data) * 0.6)])
    det = os.path.join(work, "det_cut.txt")
    r = run([os.path.join(a.tools, "sbr_detect"), "--input", cut, "--detections", det, "--quiet"])
    m = re.search(r"cut\.avi: the video ends at frame (\d+) of the 30", r.stderr)
    assert r.returncode == 3 and m, (r.returncode, r.stderr[-500:])
    n = int(m.group(1))
    frames = {int(line.split(".")[0]) for line in open(det)}
    assert 0 < n < 30 and frames and max(frames) < n and min(frames) == 0, (n, sorted(frames))
    print(f"truncated video: exit 3, named, ends at frame {n} of 30; detections of frames 0..{max(frames)} kept")


def test_not_a_video(a, work):
    bad = os.path.join(work, "bad.mp4")
    with open(bad, "wb") as f:
        f.write(b"not a video" * 64)
    det = os.path.join(work, "det_bad.txt")
    r = run([os.path.join(a.tools, "sbr_detect"), "--input", bad, "--detections", det, "--quiet"])
    assert r.returncode == 2 and "bad.mp4" in r.stderr and "nothing was run" in r.stderr, r.stderr[-300:]
    assert not os.path.exists(det)
    print("not a video: exit 2, named, nothing written")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tools", required=True)
    ap.add_argument("--image", required=True)
    ap.add_argument("--dbc", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    if not os.path.exists(a.image):
        print(f"SKIP: no frame {a.image}")
        return 77
    os.makedirs(a.work, exist_ok=True)
    video = os.path.join(a.work, "drive.avi")
    r = run([os.path.join(a.tools, "sbr_make_drive"), "--image", a.image, "--out", video, "--frames", "30",
             "--fps", "10"])
    assert r.returncode == 0, r.stderr
    test_whole_video(a, video, a.work)
    test_truncated_video(a, video, a.work)
    test_not_a_video(a, a.work)
    return 0


if __name__ == "__main__":
    sys.exit(main())
