# SPDX-License-Identifier: MIT
"""python -m sbr.regress on a 2-worker LocalCluster (ctest python_package).

Environment: SBR_DETECT, SBR_EVAL (the host tools), SBR_DATA (the GTSDB folder).
  - 40 GTSDB images in chunks of 10: detections.txt and detections_all.txt byte-identical
    to sbr_detect's on the same images, detections.parquet holding the same detections,
    evaluation.txt from the package's own evaluation identical to sbr_eval's report; the
    same from one worker process of 3 threads sharing its recogniser (chunks of 5);
  - an earlier run's files in --out are removed; bad --baseline, --gt, --model and a
    missing or empty input are named in one line, exit 2, before anything is written;
  - a worker killed once while running a chunk: Dask runs it again elsewhere, the files
    are still identical;
  - a worker killed on every attempt at one chunk (--retries 0): that chunk is reported
    failed (exit status 3), the finished chunks' files are kept; --resume computes only
    the missing chunks and ends with files identical to sbr_detect's (nothing lost,
    nothing twice);
  - an unreadable image among readable ones is counted and listed, the rest processed;
  - without the 'regress' extra's modules: one line naming the extra, exit 2, nothing written.
"""
import os
import shutil
import subprocess
import sys

import pytest

DATA = os.environ.get("SBR_DATA", "")
DETECT = os.environ.get("SBR_DETECT", "")
EVAL = os.environ.get("SBR_EVAL", "")
pytestmark = pytest.mark.skipif(not (DATA and os.path.isdir(DATA) and DETECT and EVAL),
                                reason="SBR_DATA/SBR_DETECT/SBR_EVAL not set")
RANGE = "400-439"


def regress(*args, env=None, workers=("--workers", "2")):
    e = dict(os.environ)
    e.update(env or {})
    return subprocess.run([sys.executable, "-X", "faulthandler", "-m", "sbr.regress", "--input", DATA, "--range", RANGE,
                           *workers, *args], capture_output=True, text=True, env=e, timeout=300)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    d = tmp_path_factory.mktemp("sbr_detect")
    subprocess.run([DETECT, "--input", DATA, "--range", RANGE, "--quiet", "--detections", str(d / "detections.txt"),
                    "--all-detections", str(d / "detections_all.txt")], check=True, stdout=subprocess.DEVNULL)
    return {n: (d / n).read_text() for n in ("detections.txt", "detections_all.txt")}


def test_same_detections_as_sbr_detect(tmp_path, reference):
    out = tmp_path / "run"
    r = regress("--out", str(out), "--chunk", "10")
    assert r.returncode == 0, r.stdout + r.stderr
    for name, want in reference.items():
        assert (out / name).read_text() == want, name
    assert "4 chunks, 4 to compute" in r.stdout and "--resume" not in r.stdout  # issue 70, item 12
    assert "training-set figures" in r.stdout and "training-set figures" in (out / "evaluation.txt").read_text()
    # the package's own evaluation: sbr_eval's report on the same files, byte for byte
    ev = subprocess.run([EVAL, "--detections", str(out / "detections_all.txt"), "--gt",
                         os.path.join(os.path.dirname(first_image()), "gt.txt"), "--range", RANGE,
                         "--threshold", threshold_of(r.stdout), "--plot", str(out / "pr_curve.png")],
                        capture_output=True, text=True, check=True)
    # sbr_eval's report after the training-set note (the built-in models saw 400-439)
    text = (out / "evaluation.txt").read_text()
    assert text.startswith("note: the built-in models are trained on GTSDB 00000-00599 (40 of these images)")
    assert text.split("\n", 1)[1] == ev.stdout
    assert ev.stdout.startswith("images 40, ground-truth boxes")
    import pandas as pd
    df = pd.read_parquet(out / "detections.parquet")
    assert len(df) == reference["detections_all.txt"].count("\n")
    assert int(df["at_operating_point"].sum()) == reference["detections.txt"].count("\n")
    first = reference["detections_all.txt"].split("\n")[0].split(";")
    assert (df.iloc[0]["image"], int(df.iloc[0]["left"]), int(df.iloc[0]["class_id"])) == \
        (first[0], int(first[1]), int(first[5]))
    assert df.iloc[0]["class_name"]


def first_image():
    src = os.path.join(DATA, "FullIJCNN2013") if os.path.isdir(os.path.join(DATA, "FullIJCNN2013")) else DATA
    return os.path.join(src, "00400.jpg")


def threshold_of(stdout):
    import re
    return re.search(r"operating point \(score >= ([0-9.]+)\)", stdout).group(1)


def test_an_earlier_runs_files_are_removed(tmp_path):
    # a folder that held another run: its evaluation, plot and a chunk of other images go;
    # a file that is not the tool's stays
    src = os.path.dirname(first_image())
    d = tmp_path / "in"
    d.mkdir()
    shutil.copy(os.path.join(src, "00444.jpg"), d)  # no gt.txt: no evaluation this time
    out = tmp_path / "o"
    (out / "chunks").mkdir(parents=True)
    for name in ("evaluation.txt", "pr_curve.png", "chunks/chunk_000007.json", "notes.txt"):
        (out / name).write_text("an earlier run's")
    r = subprocess.run([sys.executable, "-m", "sbr.regress", "--input", str(d), "--out", str(out), "--workers", "1"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    assert sorted(os.listdir(out)) == ["chunks", "detections.parquet", "detections.txt", "detections_all.txt",
                                       "failures.txt", "images.txt", "notes.txt"]
    assert os.listdir(out / "chunks") == ["chunk_000000.json"]


@pytest.mark.parametrize("args,named", [
    (["--baseline", "/no/such/run"], "--baseline /no/such/run: no detections_all.txt"),
    (["--gt", "/no/such/gt.txt"], "--gt /no/such/gt.txt: no such file"),
    (["--model", "/no/such.sbrm"], "--model /no/such.sbrm: no such file"),
])
def test_bad_files_are_named_before_anything_is_written(tmp_path, args, named):
    out = tmp_path / "o"
    r = subprocess.run([sys.executable, "-m", "sbr.regress", "--input", DATA, "--out", str(out), *args],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stdout + r.stderr
    assert named in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert not out.exists()


def test_missing_and_empty_inputs_are_usage_errors(tmp_path):
    for where in (tmp_path / "missing", tmp_path):
        r = subprocess.run([sys.executable, "-m", "sbr.regress", "--input", str(where), "--out", str(tmp_path / "o")],
                           capture_output=True, text=True, timeout=120)
        assert r.returncode == 2, r.stdout + r.stderr
        assert str(where) in r.stderr
    assert not (tmp_path / "o").exists()


def test_threads_of_one_worker_share_its_recogniser(tmp_path, reference):
    out = tmp_path / "run"
    r = regress("--out", str(out), "--chunk", "5", workers=("--workers", "1", "--threads", "3"))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "1 worker processes, 3 threads" in r.stdout
    for name, want in reference.items():
        assert (out / name).read_text() == want, name


def test_a_worker_dies_once_and_the_run_goes_on(tmp_path, reference):
    out = tmp_path / "run"
    marker = tmp_path / "killed"
    r = regress("--out", str(out), "--chunk", "10",
                env={"SBR_REGRESS_TEST_KILL": "1", "SBR_REGRESS_TEST_KILL_ONCE": str(marker)})
    assert marker.exists(), "the worker running chunk 1 should have died"
    assert r.returncode == 0, r.stdout + r.stderr  # Dask ran chunk 1 again on another worker
    for name, want in reference.items():
        assert (out / name).read_text() == want, name


def test_resume_after_a_killed_worker(tmp_path, reference):
    out = tmp_path / "run"
    r = regress("--out", str(out), "--chunk", "10", "--retries", "0", env={"SBR_REGRESS_TEST_KILL": "1"})
    assert r.returncode == 3, r.stdout + r.stderr
    assert "chunk 1 " in r.stderr and "KilledWorker" in r.stderr
    kept = sorted(os.listdir(out / "chunks"))
    assert "chunk_000001.json" not in kept and len(kept) < 4, kept
    stamps = {k: os.stat(out / "chunks" / k).st_mtime_ns for k in kept}
    r = regress("--out", str(out), "--chunk", "10", "--resume")
    assert r.returncode == 0, r.stdout + r.stderr
    assert f"4 chunks, {len(kept)} already done (--resume), {4 - len(kept)} to compute" in r.stdout
    assert {k: os.stat(out / "chunks" / k).st_mtime_ns for k in kept} == stamps  # not computed again
    for name, want in reference.items():
        assert (out / name).read_text() == want, name  # nothing lost, nothing twice
    assert (out / "failures.txt").read_text() == ""


def test_unreadable_image_is_counted(tmp_path):
    src = os.path.join(DATA, "FullIJCNN2013") if os.path.isdir(os.path.join(DATA, "FullIJCNN2013")) else DATA
    d = tmp_path / "in"
    d.mkdir()
    for n in (444, 445):
        shutil.copy(os.path.join(src, f"{n:05d}.jpg"), d)
    data = (d / "00445.jpg").read_bytes()
    (d / "00445.jpg").write_bytes(data[: len(data) // 2])
    r = subprocess.run([sys.executable, "-m", "sbr.regress", "--input", str(d), "--out", str(tmp_path / "o"),
                        "--workers", "1"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 3, r.stdout + r.stderr
    failures = (tmp_path / "o" / "failures.txt").read_text()
    assert "00445.jpg" in failures and "00444.jpg" not in failures
    assert (tmp_path / "o" / "detections.txt").read_text().startswith("00444.jpg;")


def test_a_missing_extra_is_named_before_anything_is_written(tmp_path):
    # the 'regress' extra's import names made unfindable: one line naming the extra, exit 2,
    # no output folder
    code = ("import importlib.util, sys; real = importlib.util.find_spec; "
            "importlib.util.find_spec = lambda n, *a: None if n in ('dask', 'PIL') else real(n, *a); "
            "from sbr import regress; sys.exit(regress.main(sys.argv[1:]))")
    out = tmp_path / "o"
    r = subprocess.run([sys.executable, "-c", code, "--input", DATA, "--out", str(out)], capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 2, r.stdout + r.stderr
    # the extra from where the package came from (here the wheel the test installed), not
    # the package index's 'sbr'
    import re
    m = re.search(r"pip install '([^']+)\[regress\]'", r.stderr)
    assert m and "sbr[regress]" not in r.stderr, r.stderr
    assert os.path.exists(m.group(1)) or m.group(1) == "./python", m.group(1)
    assert "dask" in r.stderr and "pillow" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert not out.exists()


# Issue 70: nothing lost, nothing silent.

def finished_run(out):
    r = regress("--out", str(out), "--chunk", "10")
    assert r.returncode == 0, r.stdout + r.stderr
    return {n: (out / n).read_bytes() for n in ("detections.txt", "detections_all.txt", "detections.parquet",
                                                  "evaluation.txt", "images.txt", "failures.txt")}


def intact(out, earlier):
    return all((out / n).read_bytes() == b for n, b in earlier.items())


@pytest.mark.parametrize("address", ["garbage", "tcp://127.0.0.1:1"])
def test_a_bad_scheduler_touches_nothing(tmp_path, address):
    # item 1: connected (with a short, stated timeout) before OUT is touched: one line
    # naming the address and the reason, exit 2, the earlier run's files and chunks intact
    out = tmp_path / "run"
    earlier = finished_run(out)
    chunks = sorted(os.listdir(out / "chunks"))
    r = regress("--out", str(out), "--chunk", "10", "--scheduler", address, "--connect-timeout", "2", workers=())
    assert r.returncode == 2, r.stdout + r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and f"--scheduler {address}: cannot be reached within 2 s" in lines[0], r.stderr
    assert intact(out, earlier) and sorted(os.listdir(out / "chunks")) == chunks


def test_a_list_file_is_scored_on_its_own_images(tmp_path):
    # item 2: 20 images of a list scored on those 20 (not the whole gt.txt); a baseline
    # over other images says so and compares only what both ran
    src = os.path.dirname(first_image())
    lst = tmp_path / "drives.txt"
    lst.write_text("".join(os.path.join(src, f"{n:05d}.jpg") + "\n" for n in range(400, 420)))
    base = tmp_path / "base"
    r = subprocess.run([sys.executable, "-m", "sbr.regress", "--input", DATA, "--range", "270-279", "--out",
                        str(base), "--workers", "1"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    out = tmp_path / "r"
    r = subprocess.run([sys.executable, "-m", "sbr.regress", "--input", str(lst), "--out", str(out), "--workers", "1",
                        "--baseline", str(base)], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    text = (out / "evaluation.txt").read_text()
    assert "\nimages 20, ground-truth boxes" in text, text[:600]
    assert "the baseline " + str(base) + " ran on other images: 0 of this run's 20" in text
    assert "no image in common, nothing compared" in text and "signs lost" not in text
    # a gap in a list is not filled in: 400 and 410 only
    lst.write_text(os.path.join(src, "00400.jpg") + "\n" + os.path.join(src, "00410.jpg") + "\n")
    r = subprocess.run([sys.executable, "-m", "sbr.regress", "--input", str(lst), "--out", str(tmp_path / "g"),
                        "--workers", "1"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0 and "\nimages 2, ground-truth boxes" in (tmp_path / "g" / "evaluation.txt").read_text()


def small_disk(tmp_path):
    """A 1 MiB tmpfs (as root where mounting works), else None."""
    d = tmp_path / "disk"
    d.mkdir()
    if os.geteuid() != 0:
        return None
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs", str(d)], capture_output=True)
    return d if r.returncode == 0 else None


def test_fault_injection(tmp_path, reference):
    # a worker killed mid-run, a full disk, an unreachable scheduler: after each the
    # earlier results are intact, and --resume ends with files identical to an
    # uninterrupted run (sbr_detect's)
    def resume_matches(out):
        r = regress("--out", str(out), "--chunk", "10", "--resume")
        assert r.returncode == 0, r.stdout + r.stderr
        for name, want in reference.items():
            assert (out / name).read_text() == want, name
        assert not (out / "partial").exists() and not (out / "chunks.earlier").exists()
        return r

    # 1. a worker killed on every attempt at chunk 1: the earlier run's files stay, what
    # this run computed goes to partial/
    out = tmp_path / "killed"
    earlier = finished_run(out)
    r = regress("--out", str(out), "--chunk", "10", "--retries", "0", env={"SBR_REGRESS_TEST_KILL": "1"})
    assert r.returncode == 3, r.stdout + r.stderr
    assert intact(out, earlier), "a failed chunk overwrote the earlier run's files"
    assert (out / "partial" / "detections.txt").exists() and "the earlier files" in r.stdout
    print("fault injection: worker killed: exit 3, earlier files intact, partial/ written")
    resume_matches(out)
    print("fault injection: worker killed: --resume identical to sbr_detect")

    # 2. an unreachable scheduler: nothing touched, then --resume (a local cluster)
    out = tmp_path / "sched"
    earlier = finished_run(out)
    r = regress("--out", str(out), "--chunk", "10", "--scheduler", "tcp://127.0.0.1:1", "--connect-timeout", "1",
                workers=())
    assert r.returncode == 2 and intact(out, earlier), r.stdout + r.stderr
    resume_matches(out)
    print("fault injection: unreachable scheduler: exit 2, earlier files intact; --resume identical")

    # 3. a full disk: the run's writes fail (ENOSPC); the earlier files stay; with room
    # again --resume finishes
    disk = small_disk(tmp_path)
    if disk is None:
        print("fault injection: full disk: SKIPPED (no tmpfs can be mounted here)")
        return
    try:
        out = disk / "run"
        earlier = finished_run(out)
        st = os.statvfs(disk)
        filler = disk / "filler"
        with open(filler, "wb") as f:  # leave about 2 KiB: less than a chunk's file
            try:
                f.write(b"\0" * max(0, st.f_bavail * st.f_frsize - 2048))
            except OSError:
                pass
        r = regress("--out", str(out), "--chunk", "10")
        assert r.returncode in (1, 3), r.stdout + r.stderr
        assert intact(out, earlier), "a full disk cost the earlier run's files"
        assert not [f for f in os.listdir(out) if ".tmp-" in f]
        print(f"fault injection: full disk: exit {r.returncode}, earlier files intact, no temporary left")
        filler.unlink()
        resume_matches(out)
        print("fault injection: full disk: --resume identical to sbr_detect")
    finally:
        subprocess.run(["umount", "-l", str(disk)], capture_output=True)
