#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The exit-status table (docs/usage/exit-status.md) as the programs follow it: each
program run into each case that applies, its status and its message checked.

    test_exit_status.py --tools DIR --sbr-sh PATH --dashboard PATH --data GTSDB_DIR

sbr_detect: 0 (a whole image); 2 (a bad value, a missing or empty folder, --roi outside
the image with its size, a missing model file, --annotated = the input folder); 3 (a
truncated or a 20000-pixel image beside a whole one, each named, the size limit stated);
1 (every image failed). sbr_eval: 0; 2 (a missing file, named); 4 (a regression beyond
--max-drop). ./sbr.sh: 0 (--help); 2 (no command, an unknown one, an option without its
value, a missing or empty --input folder, a missing --baseline file), all before any
set-up. sbr-dashboard: 0 (a log replayed, --help); 2 (a missing log, an unknown option).
sbr.regress's cases are in python/tests/test_regress.py. The exit-status table (docs/usage/exit-status.md) is
read and each of its examples tied to the cases that show it.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

FAILURES = []
RAN = {}  # case name -> whether it ended as expected


# Each example of docs/usage/exit-status.md's table -> the cases of this file that show it
# (run here), or "file::test" for a test elsewhere that shows it (that test must exist).
EXAMPLES = {
    0: {"a run of `sbr_detect`": ["sbr_detect, a whole image"],
        "`sbr_eval`": ["sbr_eval"],
        "a log replayed by `sbr-dashboard`": ["sbr-dashboard, a log replayed"],
        "`--help`": ["./sbr.sh --help", "./sbr.sh detect --help", "sbr-dashboard --help"]},
    1: {"every image failed to decode": ["sbr_detect, every image failed"],
        "an output file cannot be written (named: under a file, a full disk)": [
            "sbr_detect --all-detections under a file", "sbr_detect --summary under a file",
            "sbr_detect --canlog under a file", "sbr_detect --overview under a file",
            "sbr_detect, a write fails mid-run (disk full)"],
        "a log with no CAN frame (empty, or not a candump log)": [
            "dashboard/tests/test_unit.py::test_a_log_without_frames_is_an_error"]},
    2: {"an unknown command or option": ["./sbr.sh bogus", "sbr-dashboard --bogus"],
        "an option without its value or with a value out of range (the option named)": [
            "./sbr.sh detect --input (no value)", "sbr_detect --threshold abc",
            "dashboard/tests/test_unit.py::test_a_rate_that_is_not_a_speed_is_refused"],
        "a file or folder that is not there (named)": [
            "sbr_detect, a missing folder", "sbr_eval, a missing --gt file", "./sbr.sh detect, a missing folder",
            "./sbr.sh detect --baseline missing", "sbr-dashboard, a missing log"],
        "a folder without images": ["sbr_detect, an empty folder", "./sbr.sh detect, an empty folder"],
        "an input folder that cannot be listed or read (named, with the reason)": [
            "sbr_detect, an input folder it cannot list (mode 000)",
            "sbr_detect, an input folder it can list but not read (mode 444)"],
        "`--roi` outside the first image (with its size)": ["sbr_detect --roi outside"],
        "a model file the loader refuses": ["sbr_detect, a missing model file"],
        "a malformed `--baseline` file (its line named)": [
            "./sbr.sh detect --baseline malformed: refused before anything runs"],
        "`sbr.regress` without its extra": [
            "python/tests/test_regress.py::test_a_missing_extra_is_named_before_anything_is_written"],
        "a `--scheduler` that cannot be reached": [
            "python/tests/test_regress.py::test_a_bad_scheduler_touches_nothing"],
        "an image folder given as `--annotated`": ["sbr_detect --annotated = the input"],
        "a file given as `--annotated`": ["sbr_detect --annotated naming a file"],
        "a file given as `--input` that is no video OpenCV can read (named)": [
            "tests/python/test_video.py::test_not_a_video"]},
    3: {"a truncated JPEG among whole ones (named in `summary.txt` / `failures.txt`)": [
            "sbr_detect, a truncated image beside a whole one"],
        "a truncated video (named, with the frame it ends at; the frames before it processed)": [
            "tests/python/test_video.py::test_truncated_video"],
        "an image larger than the recogniser's limit (16384 pixels a side, named with its size)": [
            "sbr_detect, a 20000-pixel image beside a whole one"],
        "a chunk of `sbr.regress` whose worker died more often than allowed (what was computed in "
        "`OUT/partial/`, `--resume` goes on)": ["python/tests/test_regress.py::test_fault_injection"]},
    4: {"`sbr_eval --baseline FILE --max-drop D` when class-level F1 or a superclass's recall, precision or AP "
        "fell by more than D": ["sbr_eval, a regression beyond --max-drop"]},
    77: {"`recog_scene_same_as_host` without GTSDB": ["tests/CMakeLists.txt::recog_scene_same_as_host"],
         "`host_socketcan_vcan0` without `vcan0`": ["tests/host/CMakeLists.txt::host_socketcan_vcan0"]},
}


def split_examples(cell):
    """The examples of a table cell: separated by '; ' outside parentheses."""
    out, depth, cur = [], 0, ""
    for ch in cell:
        depth += ch == "("
        depth -= ch == ")"
        if ch == ";" and depth == 0:
            out.append(cur.strip())
            cur = ""
        else:
            cur += ch
    out.append(cur.strip())
    return [x for x in out if x]


def walk_table(doc, root):
    """Every example of the doc's table is tied to cases that ran and ended as expected, or
    to a test elsewhere that exists; the table and EXAMPLES name the same examples."""
    rows = {}
    for line in open(doc):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 4 and cells[0].isdigit():
            rows[int(cells[0])] = split_examples(cells[3])
    ok = sorted(rows) == sorted(EXAMPLES)
    for status, examples in rows.items():
        want = EXAMPLES.get(status, {})
        if sorted(examples) != sorted(want):
            print(f"FAIL table row {status}: the doc's examples {sorted(set(examples) ^ set(want))} "
                  "are not the test's (or the other way round)")
            ok = False
        for ex in examples:
            for case in want.get(ex, []):
                if "::" in case:
                    path, name = case.split("::")
                    text = open(os.path.join(root, path)).read()
                    found = f"def {name}(" in text or (name in text and "SKIP_RETURN_CODE 77" in text)
                else:
                    found = RAN.get(case) is True
                if not found:
                    print(f"FAIL status {status}, '{ex}': {case} did not show it")
                    ok = False
    print(f"{'ok  ' if ok else 'FAIL'} docs/usage/exit-status.md: every example of its table shown by a case "
          f"({sum(len(v) for v in rows.values())} examples)")
    if not ok:
        FAILURES.append("exit-status table")


def expect(what, cmd, status, *texts, env=None, preexec_fn=None):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600, env=env, stdin=subprocess.DEVNULL,
                       preexec_fn=preexec_fn)
    said = r.stdout + r.stderr
    missing = [t for t in texts if t not in said]
    ok = r.returncode == status and not missing
    RAN[what] = ok
    first = next((ln for ln in r.stderr.splitlines() if ln.strip()), "")
    print(f"{'ok  ' if ok else 'FAIL'} {what}: exit {r.returncode} (expected {status}){': ' + first if first else ''}")
    if not ok:
        FAILURES.append(what)
        if missing:
            print(f"     missing from the output: {missing}\n{said[-1500:]}")


def unprivileged():
    """The command prefix that runs a program without root's right to read anything (as
    nobody through setpriv when this test runs as root), so that a folder's mode counts."""
    if os.geteuid() != 0:
        return []
    return ["setpriv", "--reuid=nobody", "--regid=nogroup", "--clear-groups"]


def same_bytes(path, content):
    try:
        with open(path, "rb") as f:
            return f.read() == content
    except OSError:
        return False


def detect_outputs(w, run, whole, data):
    """sbr_detect's outputs (issue 70, items 3 and 4): each checked before the first image,
    written under a temporary name and renamed; a failed write is exit 1 naming the path;
    an earlier run's files survive every error; an unreadable input folder or an
    --annotated file is one line, exit 2."""
    out = os.path.join(w, "outs")
    os.makedirs(out)
    blocker = os.path.join(out, "f")
    open(blocker, "w").close()
    det, alld, summ, can = (os.path.join(out, n) for n in ("d.txt", "a.txt", "s.txt", "c.log"))
    base = [run[0], "--quiet", "--input", whole, "--detections", det]
    subprocess.run(base + ["--all-detections", alld, "--summary", summ, "--canlog", can], check=True,
                   capture_output=True)
    earlier = {p: open(p, "rb").read() for p in (det, alld, summ, can)}
    for opt in ("--all-detections", "--summary", "--canlog", "--overview"):
        bad = os.path.join(blocker, "x.png" if opt == "--overview" else "x.txt")
        gt = ["--gt", os.path.join(data, "FullIJCNN2013", "gt.txt")] if opt == "--overview" else []
        expect(f"sbr_detect {opt} under a file", base + [opt, bad] + gt, 1,
               f"{opt} {bad}: cannot write it: Not a directory")
    expect("sbr_detect --annotated naming a file", base + ["--annotated", blocker], 2,
           f"--annotated {blocker}: a file, not a folder")
    intact = all(same_bytes(p, b) for p, b in earlier.items())
    print(f"{'ok  ' if intact else 'FAIL'} sbr_detect: the earlier run's files are intact after each refusal")
    if not intact:
        FAILURES.append("earlier files after a refusal")
    # a full disk: the file size limit (its signal ignored) makes a write fail mid-run
    import resource
    import signal

    def small_disk():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (600, 600))
    many = [run[0], "--quiet", "--input", data, "--range", "400-419", "--detections", det, "--all-detections", alld]
    expect("sbr_detect, a write fails mid-run (disk full)", many, 1, f"--all-detections {alld}: the write failed",
           preexec_fn=small_disk)
    intact = all(same_bytes(p, earlier[p]) for p in (det, alld)) and not [
        f for f in os.listdir(out) if ".tmp-" in f]
    print(f"{'ok  ' if intact else 'FAIL'} sbr_detect: after the failed write the earlier files are intact, no "
          "temporary left")
    if not intact:
        FAILURES.append("earlier files after a failed write")
    # an input folder that cannot be listed, and one whose images cannot be looked at
    locked, peek = os.path.join(w, "locked"), os.path.join(w, "peek")
    for d, mode in ((locked, 0o000), (peek, 0o444)):
        os.makedirs(d)
        shutil.copy(os.path.join(whole, "00444.jpg"), d)
        os.chmod(d, mode)
    os.chmod(w, 0o755)
    ok_det = os.path.join(w, "nobody")
    os.makedirs(ok_det, mode=0o777)
    os.chmod(ok_det, 0o777)
    nobody = unprivileged()
    expect("sbr_detect, an input folder it cannot list (mode 000)",
           nobody + [run[0], "--quiet", "--input", locked, "--detections", ok_det + "/d.txt"], 2,
           f"--input {locked}: {locked}: cannot list it: Permission denied")
    expect("sbr_detect, an input folder it can list but not read (mode 444)",
           nobody + [run[0], "--quiet", "--input", peek, "--detections", ok_det + "/d.txt"], 2,
           f"--input {peek}: {peek}/00444.jpg: Permission denied")
    for d in (locked, peek):
        os.chmod(d, 0o755)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tools", required=True)
    ap.add_argument("--sbr-sh", required=True)
    ap.add_argument("--dashboard", required=True, help="the sbr-dashboard console script")
    ap.add_argument("--data", required=True, help="GTSDB folder")
    a = ap.parse_args()
    src = os.path.join(a.data, "FullIJCNN2013") if os.path.isdir(os.path.join(a.data, "FullIJCNN2013")) else a.data
    image = os.path.join(src, "00444.jpg")
    if not os.path.isfile(image):
        print(f"SKIP: no GTSDB image {image}")
        return 77
    detect, ev = os.path.join(a.tools, "sbr_detect"), os.path.join(a.tools, "sbr_eval")
    w = tempfile.mkdtemp(prefix="sbr_exit_")
    try:
        def folder(name, files):
            d = os.path.join(w, name)
            os.makedirs(d)
            for n, cut in files:
                shutil.copy(image, os.path.join(d, n))
                if cut:
                    os.truncate(os.path.join(d, n), os.path.getsize(image) // 2)
            return d

        whole = folder("whole", [("00444.jpg", False)])
        mixed = folder("mixed", [("00444.jpg", False), ("00445.jpg", True)])
        broken = folder("broken", [("00445.jpg", True)])
        empty = folder("empty", [])
        big = folder("big", [("00444.jpg", False)])
        with open(os.path.join(big, "00446.ppm"), "wb") as f:  # 20000 x 2 grey pixels
            f.write(b"P6\n20000 2\n255\n" + bytes(20000 * 2 * 3))
        det = os.path.join(w, "d.txt")
        run = [detect, "--quiet", "--detections", det]

        expect("sbr_detect, a whole image", run + ["--input", whole], 0)
        expect("sbr_detect --threshold abc", run + ["--input", whole, "--threshold", "abc"], 2, "--threshold")
        expect("sbr_detect, a missing folder", run + ["--input", w + "/none"], 2, "--input " + w + "/none: no such folder")
        expect("sbr_detect, an empty folder", run + ["--input", empty], 2, "no .jpg, .jpeg, .png or .ppm images in")
        expect("sbr_detect --roi outside", run + ["--input", whole, "--roi", "1300,700,200,200"], 2,
               "--roi 1300,700,200,200 does not lie inside the image (1360 x 800 pixels")
        expect("sbr_detect --roi 0,0,0,0", run + ["--input", whole, "--roi", "0,0,0,0"], 2, "--roi 0,0,0,0")
        expect("sbr_detect, a missing model file", run + ["--input", whole, "--model", w + "/none.sbrm"], 2,
               "none.sbrm")
        expect("sbr_detect --annotated = the input", run + ["--input", whole, "--annotated", whole], 2,
               "is the input folder")
        expect("sbr_detect, a truncated image beside a whole one", run + ["--input", mixed], 3,
               "00445.jpg: truncated JPEG")
        expect("sbr_detect, a 20000-pixel image beside a whole one", run + ["--input", big], 3,
               "20000 x 2 pixels; the recogniser takes at most 16384 on a side")
        expect("sbr_detect, every image failed", run + ["--input", broken], 1, "1 of 1 images failed")
        detect_outputs(w, run, whole, a.data)

        gt = os.path.join(w, "gt.txt")
        with open(gt, "w") as f:
            f.write("00444.ppm;379;528;427;573;20\n00444.ppm;389;569;419;600;7\n")
        good, bad = os.path.join(w, "good.txt"), os.path.join(w, "bad.txt")
        with open(good, "w") as f:
            f.write("00444.jpg;379;528;427;573;20;0.9\n00444.jpg;389;569;419;600;7;0.9\n")
        with open(bad, "w") as f:
            f.write("00444.jpg;379;528;427;573;20;0.9\n")
        plot = ["--plot", os.path.join(w, "pr.png")]
        expect("sbr_eval", [ev, "--detections", good, "--gt", gt] + plot, 0)
        expect("sbr_eval, a missing --gt file", [ev, "--detections", good, "--gt", w + "/no_gt.txt"] + plot, 2,
               w + "/no_gt.txt: cannot open it")
        expect("sbr_eval, a regression beyond --max-drop", [ev, "--detections", bad, "--gt", gt, "--baseline", good,
                                                            "--max-drop", "0.1"] + plot, 4, "REGRESSION")

        # sbr.sh: every case is refused before any set-up (a build root of its own, unused)
        env = dict(os.environ, SBR_BUILD_ROOT=os.path.join(w, "build"))
        sh = [a.sbr_sh]
        expect("./sbr.sh --help", sh + ["--help"], 0, "./sbr.sh detect", env=env)
        expect("./sbr.sh detect --help", sh + ["detect", "--help"], 0, "--baseline", env=env)
        expect("./sbr.sh (no command)", sh, 2, env=env)
        expect("./sbr.sh bogus", sh + ["bogus"], 2, "unknown command 'bogus'", env=env)
        expect("./sbr.sh detect --input (no value)", sh + ["detect", "--input"], 2, "--input needs a value", env=env)
        expect("./sbr.sh detect, a missing folder", sh + ["detect", "--input", w + "/none"], 2, "no such folder",
               env=env)
        expect("./sbr.sh detect, an empty folder", sh + ["detect", "--input", empty], 2, "no .jpg", env=env)
        expect("./sbr.sh detect --baseline missing", sh + ["detect", "--baseline", w + "/none.txt"], 2,
               "none.txt: no such file", env=env)
        malformed = os.path.join(w, "malformed.txt")
        with open(malformed, "w") as f:
            f.write("00444.jpg;379;528;427;573;20;0.9\n00444.jpg;379;528;427\n")
        expect("./sbr.sh detect --baseline malformed: refused before anything runs",
               sh + ["detect", "--input", whole, "--baseline", malformed], 2,
               f"--baseline {malformed}:2: 00444.jpg;379;528;427: not a detection line", env=env)
        linked = os.path.join(w, "linked")
        os.makedirs(linked)
        os.symlink(os.path.join(whole, "00444.jpg"), os.path.join(linked, "00444.jpg"))
        # the folder of links passes the image check: the next check (--out a file) refuses
        expect("./sbr.sh detect --input a folder of symbolic links to images",
               sh + ["detect", "--input", linked, "--out", malformed], 2, "is a file, not a folder", env=env)
        r = subprocess.run(sh + ["--help"], capture_output=True, text=True, env=env)
        first = r.stdout.splitlines()[0] if r.stdout else ""
        ok = r.returncode == 0 and "SPDX" not in r.stdout and first.startswith("sbr's one entry point")
        print(f"{'ok  ' if ok else 'FAIL'} ./sbr.sh --help starts with what it is, no licence line: {first!r}")
        if not ok:
            FAILURES.append("sbr.sh --help first line")
        if os.path.isdir(os.path.join(w, "build")):
            print("FAIL ./sbr.sh ran its set-up for a refused command")
            FAILURES.append("sbr.sh set-up")

        log = os.path.join(w, "c.log")
        subprocess.run(run + ["--input", whole, "--canlog", log], check=True, capture_output=True)
        dash = [a.dashboard]
        expect("sbr-dashboard, a log replayed", dash + ["--log", log, "--terminal", "--once", "--fast"], 0,
               "end of log")
        expect("sbr-dashboard --help", dash + ["--help"], 0, "--log")
        expect("sbr-dashboard, a missing log", dash + ["--log", w + "/none.log", "--terminal"], 2, "none.log")
        expect("sbr-dashboard --bogus", dash + ["--log", log, "--bogus"], 2, "unrecognized arguments: --bogus")
    finally:
        shutil.rmtree(w, ignore_errors=True)
    walk_table(os.path.join(os.path.dirname(os.path.abspath(a.sbr_sh)), "docs", "usage", "exit-status.md"),
               os.path.dirname(os.path.abspath(a.sbr_sh)))
    print(f"{len(FAILURES)} failures" if FAILURES else "every status as the table says")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
