# SPDX-License-Identifier: MIT
"""Regression over recorded images on Dask: python -m sbr.regress.

    python -m sbr.regress --input DIR|LIST --out DIR [--scheduler ADDRESS | --workers N [--threads T]]
                          [--baseline DIR] [--range A-B] [--chunk N] [--resume]
                          [--model F.sbrm --picto F.sbrp] [--gt FILE]

The images (a folder's .jpg/.jpeg/.png/.ppm files sorted by name, a GTSDB folder with
FullIJCNN2013/ inside, or a text file with one path per line) are cut into chunks of
--chunk files (default 20); each chunk is one Dask task that runs sbr.Recognizer on its
images (decoded with Pillow as RGB: the same pixels as sbr_detect's OpenCV on GTSDB) and
writes its results to OUT/chunks/ at once (a file per chunk, written whole or not at all).
Without --scheduler a LocalCluster of --workers processes (default 1) with --threads
threads each (default: the machine's cores over the workers) runs them: the core releases
the GIL, so a process's threads run in parallel, and one process per machine is the
cheapest (each process has its own event loop, heartbeats and memory; a process that
dies is restarted by its nanny and its chunk retried either way). With --scheduler, any
Dask cluster (docs/usage/regress.md: Kubernetes, Slurm). Every worker loads the models
before the first chunk starts. Dask's progress bar shows the run when stdout is a terminal. An image that cannot be read is counted and listed; a chunk
whose task fails (its worker died more often than Dask retries, or any error) is
reported and the others go on; nothing computed is lost: --resume skips the chunks whose
files are there and computes only the rest.

Then OUT/ gets detections.txt and detections_all.txt in sbr_detect's format and order
(score >= the operating point, and every detection down to 0.05), detections.parquet
(one row per detection of either file: image, box, class id and name, score, share,
parts, at_operating_point), failures.txt, and, when the images have GTSDB ground truth
(gt.txt beside them, or --gt), evaluation.txt and pr_curve.png from the package's own
evaluation (sbr.evaluate: sbr_eval's report; --baseline DIR: compared with the
detections_all.txt of an earlier run), and images.txt (the images this run was given:
the evaluation scores exactly those, and a later run's --baseline knows what this one
covered). An earlier run's results are never lost to this one: with --scheduler the
cluster is reached (--connect-timeout, default 10 s) before anything in OUT is touched;
the earlier chunks are set aside (OUT/chunks.earlier/) rather than deleted, and every
file is written under a temporary name and renamed over the earlier one only when the
run has finished: a run with failed chunks writes what it has to OUT/partial/ and leaves
the earlier files as they were. When a run has finished, OUT holds its files only (an
earlier run's files it did not write again, and the set-aside chunks, are removed).

Every option is checked before anything is written: the input, --baseline's
detections_all.txt, --gt, --model and --picto, and the scheduler's address. Exit status
(docs/usage/exit-status.md): 0 done; 2 refused before the run (a bad option, a file or
folder that is not there, no images, the 'regress' extra missing, a scheduler that cannot
be reached); 3 done, some images or chunks failed (listed); 1 the run failed (its output
could not be written: the earlier files are kept).
"""
import argparse
import json
import os
import re
import shutil
import sys
import threading
import time

IMAGE_EXT = (".jpg", ".jpeg", ".png", ".ppm")
ALL_FLOOR = 0.05  # sbr_detect --all-detections


def list_inputs(source, span=None):
    """The image paths of a folder (or GTSDB folder) or of a list file, in order."""
    if os.path.isdir(source):
        d = os.path.join(source, "FullIJCNN2013") if os.path.isdir(os.path.join(source, "FullIJCNN2013")) else source
        paths = sorted(os.path.join(d, f) for f in os.listdir(d) if f.lower().endswith(IMAGE_EXT))
    elif os.path.isfile(source):
        with open(source) as f:
            paths = [ln.strip() for ln in f if ln.strip() and not ln.startswith("#")]
    else:
        return []
    if span is not None:
        paths = [p for p in paths if (n := image_number(p)) is not None and span[0] <= n <= span[1]]
    return paths


def image_number(path):
    stem = os.path.splitext(os.path.basename(path))[0]
    return int(stem) if stem.isdigit() else None


def out_name(path):
    """The image's name in the detection files: NNNNN.jpg, as sbr_detect writes it."""
    return os.path.splitext(os.path.basename(path))[0] + ".jpg"


_RECOGNIZERS = {}
_RECOGNIZERS_LOCK = threading.Lock()


def _recognizer(model, picto):
    """One Recognizer per worker process and model pair (building one loads the models),
    shared by the process's threads (detect() is thread-safe: a workspace per call)."""
    import sbr
    key = (model, picto)
    with _RECOGNIZERS_LOCK:
        if key not in _RECOGNIZERS:
            base = sbr.Recognizer(model=model, picto=picto)
            _RECOGNIZERS[key] = sbr.Recognizer(model=model, picto=picto,
                                               min_score=min(base.config["min_score"], ALL_FLOOR))
        return _RECOGNIZERS[key]


def warm_up(model, picto):
    """Run on every worker before the chunks: imports and the models, so that the timed
    span is the images' (returns the process id)."""
    _recognizer(model, picto)
    import numpy  # noqa: F401 - the chunks' imports
    from PIL import Image  # noqa: F401
    return os.getpid()


def _read_rgb(path):
    """The image as an RGB array, or the reason it cannot be read whole."""
    import numpy as np
    from PIL import Image
    try:
        with Image.open(path) as im:
            im.load()  # a truncated file raises here (Pillow does not pad by default)
            return np.asarray(im.convert("RGB")), None
    except Exception as e:  # noqa: BLE001 - every reason is reported
        return None, f"{type(e).__name__}: {e}"


def run_chunk(index, paths, out_dir, model, picto):
    """A Dask task: the chunk's detections into OUT/chunks/chunk_NNNNNN.json."""
    # tests only: the worker running chunk SBR_REGRESS_TEST_KILL dies (every time, or only
    # the first time when SBR_REGRESS_TEST_KILL_ONCE names a marker file to leave)
    hook = os.environ.get("SBR_REGRESS_TEST_KILL")
    if hook is not None and int(hook) == index:
        marker = os.environ.get("SBR_REGRESS_TEST_KILL_ONCE")
        if not marker or not os.path.exists(marker):
            if marker:
                open(marker, "w").close()
            os._exit(1)
    rec = _recognizer(model, picto)
    images = []
    for p in paths:
        img, err = _read_rgb(p)
        entry = dict(path=p, name=out_name(p), error=err, dets=[])
        if img is not None:
            try:
                for d in rec.detect(img, order="rgb"):
                    entry["dets"].append([d.class_id, *d.box, round(d.score, 6), round(d.share, 6), d.parts,
                                          d.gtsdb_line(entry["name"])])
            except ValueError as e:
                entry["error"] = f"refused by the recogniser: {e}"
        images.append(entry)
    record = dict(index=index, threshold=rec.threshold, images=images)
    path = chunk_path(out_dir, index)
    tmp = f"{path}.{os.getpid()}.tmp"
    try:
        with open(tmp, "w") as f:
            json.dump(record, f)
        os.replace(tmp, path)  # whole or not at all
    finally:
        if os.path.exists(tmp):  # a failed write (a full disk) leaves no partial file
            os.remove(tmp)
    return index


def chunk_path(out_dir, index):
    return os.path.join(out_dir, "chunks", f"chunk_{index:06d}.json")


def chunk_done(out_dir, index, paths):
    """A chunk file that is there, readable, and holds exactly these images."""
    try:
        with open(chunk_path(out_dir, index)) as f:
            rec = json.load(f)
        return [im["path"] for im in rec["images"]] == list(paths)
    except (OSError, ValueError, KeyError, TypeError):
        return False


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="python -m sbr.regress", description=__doc__.split("\n\n")[0])
    ap.add_argument("--input", required=True, help="folder of images (or GTSDB folder), or a file listing images")
    ap.add_argument("--out", required=True, help="output folder")
    where = ap.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler (tcp://host:8786)")
    ap.add_argument("--connect-timeout", type=float, default=10.0, metavar="S",
                    help="seconds to reach --scheduler before giving up (default 10; nothing is written then)")
    where.add_argument("--workers", type=int, default=1, help="LocalCluster processes without --scheduler (default 1)")
    ap.add_argument("--threads", type=int,
                    help="threads per LocalCluster process (default: the machine's cores over --workers)")
    ap.add_argument("--chunk", type=int, default=20, help="images per task (default 20)")
    ap.add_argument("--range", help="images numbered A-B only")
    ap.add_argument("--resume", action="store_true", help="keep the chunks already in OUT/chunks, compute the rest")
    ap.add_argument("--retries", type=int, default=3,
                    help="workers that may die running one chunk before it counts as failed (Dask's "
                         "allowed-failures; default 3)")
    ap.add_argument("--model", help="prototype library file (sbr_train --out-model); default built-in")
    ap.add_argument("--picto", help="class-stage file (sbr_train_picto --out); default built-in")
    ap.add_argument("--gt", help="GTSDB ground truth (default: gt.txt beside the images, when there)")
    ap.add_argument("--baseline", metavar="DIR", help="an earlier run's folder (its detections_all.txt)")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar (there is none when stdout is not a terminal)")
    a = ap.parse_args(argv)
    if a.chunk < 1 or (a.scheduler is None and a.workers < 1) or a.retries < 0 or (a.threads is not None
                                                                                  and a.threads < 1):
        ap.error("--chunk, --workers and --threads must be at least 1, --retries at least 0")
    if not (a.connect_timeout > 0 and a.connect_timeout <= 3600):  # refuses nan too
        ap.error(f"--connect-timeout {a.connect_timeout}: a number of seconds in (0, 3600]")
    if a.scheduler and a.threads is not None:
        ap.error("--threads is for the LocalCluster: a cluster's workers have their own")
    if a.threads is None:
        a.threads = max(1, (os.cpu_count() or 1) // a.workers)
    a.span = None
    if a.range:
        m = re.fullmatch(r"(\d+)-(\d+)", a.range)
        if not m or int(m.group(1)) > int(m.group(2)):
            ap.error(f"--range {a.range}: A-B with A <= B is needed")
        a.span = (int(m.group(1)), int(m.group(2)))
    return a


def connect(a):
    """The Dask client (and the LocalCluster without --scheduler), before anything in OUT is
    touched: (client, cluster, None), or (None, None, the reason) when the scheduler cannot
    be reached within --connect-timeout."""
    import dask
    from dask.distributed import Client, LocalCluster
    dask.config.set({"distributed.scheduler.allowed-failures": a.retries})
    if a.scheduler:
        try:
            return Client(a.scheduler, timeout=f"{a.connect_timeout}s"), None, None
        except Exception as e:  # noqa: BLE001 - every reason is named: a bad address, a timeout, DNS
            why = str(e).splitlines()[0] if str(e) else type(e).__name__
            return None, None, f"{type(e).__name__}: {why}"
    # the control plane shares the machine's cores with the chunks: the workers'
    # sampling profiler (a thread walking every stack every 10 ms, for the dashboard)
    # is off, and the event loops' 20 ms tick (blocked-loop warnings), the nannies'
    # 100 ms memory polls and the 0.5 s system monitor run less often; on a 2-core
    # machine this gave the chunks about 4 % more (docs/results/python.md)
    dask.config.set({"distributed.worker.profile.enabled": False,
                     "distributed.admin.tick.interval": "1s",
                     "distributed.worker.memory.monitor-interval": "1s",
                     "distributed.admin.system-monitor.interval": "2s"})
    cluster = LocalCluster(n_workers=a.workers, threads_per_worker=a.threads, processes=True,
                           dashboard_address=":0")
    return Client(cluster), cluster, None


def compute(a, chunks, client):
    """Runs the chunks not yet done on Dask; returns the indices of the chunks that failed."""
    from dask.distributed import as_completed, progress
    todo = [i for i, c in enumerate(chunks) if not (a.resume and chunk_done(a.out, i, c))]
    skipped = len(chunks) - len(todo)
    print(f"sbr.regress: {len(chunks)} chunks, " + (f"{skipped} already done (--resume), " if a.resume else "")
          + f"{len(todo)} to compute", flush=True)
    if not todo:
        return []
    model = os.path.abspath(a.model) if a.model else None
    picto = os.path.abspath(a.picto) if a.picto else None
    from sbr import regress as task_module
    t_warm = time.time()
    ready = client.run(task_module.warm_up, model, picto)
    threads = sum(client.nthreads().values())
    print(f"sbr.regress: {len(ready)} worker processes, {threads} threads, ready in {time.time() - t_warm:.1f} s",
          flush=True)
    t0 = time.time()
    # the task by reference to the importable module (under `python -m` this file is
    # __main__, whose functions would travel by value with fresh globals each time)
    futures = [client.submit(task_module.run_chunk, i, chunks[i], os.path.abspath(a.out), model, picto,
                             key=f"sbr-chunk-{i}", pure=False) for i in todo]
    if not a.no_progress and sys.stdout.isatty():
        progress(futures, notebook=False)  # Dask's progress bar, until every task has settled
        print(flush=True)
    # each task's outcome when it first settles; then every future is let go, so a
    # finished task whose worker dies later is not computed again (its file is written)
    errors = {}
    for f in as_completed(futures):
        if f.status == "error":
            errors[f.key] = f.exception()
    client.cancel(futures)
    took = time.time() - t0
    n = sum(len(chunks[i]) for i in todo)
    print(f"sbr.regress: computed {n} images in {took:.1f} s on the cluster ({n / took:.2f} images/s, "
          f"from the first task submitted to the last settled)", flush=True)
    failed = []
    for i, f in zip(todo, futures):
        if chunk_done(a.out, i, chunks[i]):
            continue
        err = errors.get(f.key)
        why = f"{type(err).__name__}: {err}" if err is not None else "no result file"
        print(f"sbr.regress: chunk {i} ({chunks[i][0]} ...) failed: {why}", file=sys.stderr)
        failed.append(i)
    return failed


def disconnect(client, cluster):
    """The results are on disk: a cluster slow to shut down (a worker still restarting
    after a death) is not waited for beyond the timeout."""
    try:
        client.close(timeout=20)
        if cluster is not None:
            cluster.close(timeout=20)
    except Exception as e:  # noqa: BLE001
        print(f"sbr.regress: the cluster did not shut down cleanly ({type(e).__name__}); results are kept",
              file=sys.stderr)


def write_whole(path, write):
    """write(f) into a temporary file beside `path`, renamed over it once written whole
    (a failed write raises OSError and leaves the earlier file as it was)."""
    tmp = f"{path}.tmp-{os.getpid()}"
    try:
        with open(tmp, "w") as f:
            write(f)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def gather(a, chunks, failed_chunks, dest):
    """The chunk files into the detection files, the Parquet file, failures.txt and
    images.txt in `dest` (each written whole, then renamed)."""
    import pandas as pd
    lines_op, lines_all, rows, failures = [], [], [], []
    for i, c in enumerate(chunks):
        if i in failed_chunks or not chunk_done(a.out, i, c):
            failures += [f"{p}: its chunk {i} failed" for p in c]
            continue
        with open(chunk_path(a.out, i)) as f:
            rec = json.load(f)
        for im in rec["images"]:
            if im["error"]:
                failures.append(f"{im['path']}: {im['error']}")
            for cls, x, y, w, h, score, share, parts, line in im["dets"]:
                at_op = score >= rec["threshold"]
                lines_all.append(line)
                if at_op:
                    lines_op.append(line)
                rows.append(dict(image=im["name"], left=x, top=y, right=x + w - 1, bottom=y + h - 1, class_id=cls,
                                 score=score, share=share, parts=parts, at_operating_point=at_op))
    os.makedirs(dest, exist_ok=True)
    for name, lines in (("detections.txt", lines_op), ("detections_all.txt", lines_all)):
        write_whole(os.path.join(dest, name), lambda f, lines=lines: f.writelines(ln + "\n" for ln in lines))
    import sbr
    df = pd.DataFrame(rows, columns=["image", "left", "top", "right", "bottom", "class_id", "score", "share",
                                     "parts", "at_operating_point"])
    df.insert(6, "class_name", [sbr.class_name(c) for c in df["class_id"]])
    pq = os.path.join(dest, "detections.parquet")
    tmp = f"{pq}.tmp-{os.getpid()}"
    try:
        df.to_parquet(tmp, index=False)
        os.replace(tmp, pq)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    write_whole(os.path.join(dest, "failures.txt"), lambda f: f.writelines(x + "\n" for x in failures))
    write_whole(os.path.join(dest, "images.txt"),
                lambda f: f.writelines(out_name(p) + "\n" for c in chunks for p in c))
    return len(lines_op), len(lines_all), failures


TRAINING_NOTE = ("note: the built-in models are trained on GTSDB 00000-00599 ({n} of these images): their "
                 "figures there are training-set figures, not what unseen images give (for those: ./sbr.sh crossval, "
                 "docs/usage/crossval.md)")


def training_note(a, paths):
    """The note ./sbr.sh detect adds when the built-in models score images they were
    trained on, or None."""
    if a.model or a.picto:
        return None
    n = sum(1 for p in paths if (k := image_number(p)) is not None and 0 <= k <= 599)
    return TRAINING_NOTE.format(n=n) if n else None


def baseline_images(a):
    """The image names an earlier run was given (its images.txt), or None when it did not
    record them."""
    try:
        with open(os.path.join(a.baseline, "images.txt")) as f:
            return {ln.strip() for ln in f if ln.strip()}
    except OSError:
        return None


def evaluate(a, paths, threshold, dest):
    """evaluation.txt and pr_curve.png in `dest` from the package's own evaluation
    (sbr.evaluate: sbr_eval's report) over exactly the images this run was given, when
    they have ground truth; with --baseline, compared over the images both runs were given
    (the report says so when that is not all of this run's)."""
    gt = ground_truth(a, paths)
    if gt is None:
        return None
    import sbr
    nums = sorted({n for n in (image_number(p) for p in paths) if n is not None})
    unnumbered = len(paths) - sum(1 for p in paths if image_number(p) is not None)
    plot = os.path.join(dest, "pr_curve.png")
    tmp_plot = os.path.join(dest, f"pr_curve.tmp-{os.getpid()}.png")
    dets = os.path.join(dest, "detections_all.txt")
    base = os.path.join(a.baseline, "detections_all.txt") if a.baseline else None
    notes = []
    if unnumbered:
        notes.append(f"note: {unnumbered} of the {len(paths)} images have no GTSDB number (NNNNN.ext) and are not "
                     "scored")
    note = training_note(a, paths)
    if note:
        notes.append(note)
    compare_over = None  # with a baseline over other images: the images both were given
    if base:
        theirs = baseline_images(a)
        if theirs is None:
            notes.append(f"note: the baseline {a.baseline} does not record its images (no images.txt): it is "
                         "compared as if it ran on these images")
        elif not {out_name(p) for p in paths} <= theirs:
            compare_over = [n for n in nums if f"{n:05d}.jpg" in theirs]
            notes.append(f"note: the baseline {a.baseline} ran on other images: {len(compare_over)} of this run's "
                         f"{len(nums)} are among its {len(theirs)}; the comparison below is over those "
                         f"{len(compare_over)} only")
    try:
        ev = sbr.evaluate(dets, gt, images=nums, threshold=threshold, plot=tmp_plot,
                          baseline=base if compare_over is None else None)
        text = ev.text
        if compare_over:
            cmp_text = sbr.evaluate(dets, gt, images=compare_over, threshold=threshold, baseline=base).text
            text += cmp_text[cmp_text.find("against the baseline"):]
        elif compare_over is not None:
            text += f"against the baseline {a.baseline}: no image in common, nothing compared\n"
        text = ("".join(n + "\n" for n in notes) + text).replace(tmp_plot, plot)
        write_whole(os.path.join(dest, "evaluation.txt"), lambda f: f.write(text))
        os.replace(tmp_plot, plot)
    finally:
        if os.path.exists(tmp_plot):
            os.remove(tmp_plot)
    return text


def ground_truth(a, paths):
    """The ground truth: --gt, else gt.txt beside the images, else None."""
    if a.gt:
        return a.gt
    gt = os.path.join(os.path.dirname(paths[0]), "gt.txt")
    return gt if os.path.isfile(gt) else None


# What sbr.regress imports beyond the package's own dependencies: the 'regress' extra.
EXTRA_MODULES = {"dask": "dask", "distributed": "distributed", "pandas": "pandas", "pyarrow": "pyarrow",
                 "PIL": "pillow"}


def missing_extra():
    """The distributions of the 'regress' extra that are not installed (by import name)."""
    import importlib.util
    return [dist for mod, dist in EXTRA_MODULES.items() if importlib.util.find_spec(mod) is None]


# The files a finished run writes into OUT (chunks/ aside): an earlier run's that this one
# did not write again are removed at its end.
RUN_FILES = ("detections.txt", "detections_all.txt", "detections.parquet", "failures.txt", "images.txt",
             "evaluation.txt", "pr_curve.png")


def extra_hint():
    """How to install the 'regress' extra from where this package came from: the folder
    it was installed from (pip's direct_url.json), else the checkout's ./python."""
    where = "./python"
    try:
        from importlib.metadata import distribution
        url = json.loads(distribution("sbr").read_text("direct_url.json") or "{}").get("url", "")
        if url.startswith("file://"):
            where = url[len("file://"):]
    except Exception:  # noqa: BLE001 - no metadata: the checkout's folder
        pass
    return f"pip install '{where}[regress]' (where this package was installed from, with its 'regress' extra)"


def refuse(message):
    """A usage error: one line, exit status 2, nothing written."""
    print(f"sbr.regress: {message} (nothing was written)", file=sys.stderr)
    return 2


def check_files(a):
    """What is wrong with the options' files and folders, or None."""
    if not os.path.exists(a.input):
        return f"--input {a.input}: no such folder or list file"
    if a.baseline and not os.path.isfile(os.path.join(a.baseline, "detections_all.txt")):
        return f"--baseline {a.baseline}: no detections_all.txt there (an earlier run's --out folder is expected)"
    for opt, path in (("--gt", a.gt), ("--model", a.model), ("--picto", a.picto)):
        if path and not os.path.isfile(path):
            return f"{opt} {path}: no such file"
    if os.path.exists(a.out) and not os.path.isdir(a.out):
        return f"--out {a.out}: a file, not a folder"
    return None


def set_aside(a):
    """OUT for this run: its chunks folder; without --resume an earlier run's chunks are
    set aside in chunks.earlier/ (removed when this run has finished), never deleted first."""
    chunks = os.path.join(a.out, "chunks")
    if not a.resume and os.path.isdir(chunks) and os.listdir(chunks):
        earlier = os.path.join(a.out, "chunks.earlier")
        shutil.rmtree(earlier, ignore_errors=True)
        os.replace(chunks, earlier)
    os.makedirs(chunks, exist_ok=True)


def finish(a, wrote):
    """A finished run: the earlier run's files that this one did not write again, its
    set-aside chunks and a partial result of an interrupted run are removed."""
    for name in RUN_FILES:
        p = os.path.join(a.out, name)
        if name not in wrote and os.path.isfile(p):
            os.remove(p)
    shutil.rmtree(os.path.join(a.out, "chunks.earlier"), ignore_errors=True)
    shutil.rmtree(os.path.join(a.out, "partial"), ignore_errors=True)


def main(argv=None):
    a = parse_args(argv)
    missing = missing_extra()
    if missing:
        # before anything is read or written
        print(f"sbr.regress: needs the 'regress' extra (missing: {', '.join(missing)}): {extra_hint()}",
              file=sys.stderr)
        return 2
    problem = check_files(a)
    if problem:
        return refuse(problem)
    paths = list_inputs(a.input, a.span)
    if not paths:
        return refuse(f"no .jpg, .jpeg, .png or .ppm images in {a.input}"
                      + (f" numbered {a.range}" if a.range else ""))
    import sbr
    try:
        threshold = sbr.Recognizer(model=a.model, picto=a.picto).threshold
    except ValueError as e:  # a model file the loader refuses
        return refuse(str(e))
    t0 = time.time()
    client, cluster, why = connect(a)  # before anything in OUT is touched
    if client is None:
        return refuse(f"--scheduler {a.scheduler}: cannot be reached within {a.connect_timeout:g} s ({why})")
    chunks = [paths[i:i + a.chunk] for i in range(0, len(paths), a.chunk)]
    try:
        set_aside(a)
        failed = compute(a, chunks, client)
    finally:
        disconnect(client, cluster)
    # a run with failed chunks leaves the earlier files as they were: what it has goes to
    # OUT/partial/, and --resume computes the rest
    dest = os.path.join(a.out, "partial") if failed else a.out
    try:
        n_op, n_all, failures = gather(a, chunks, failed, dest)
        ev = evaluate(a, paths, threshold, dest)
    except OSError as e:
        print(f"sbr.regress: cannot write the results into {dest}: {e} (the finished chunks are kept in "
              f"{os.path.join(a.out, 'chunks')}: --resume goes on from them; the earlier files are unchanged)",
              file=sys.stderr)
        return 1
    if not failed:
        finish(a, {"detections.txt", "detections_all.txt", "detections.parquet", "failures.txt", "images.txt"}
               | ({"evaluation.txt", "pr_curve.png"} if ev is not None else set()))
    print(f"sbr.regress: {len(paths)} images in {len(chunks)} chunks, {time.time() - t0:.1f} s; "
          f"{n_op} detections at the operating point (score >= {threshold:g}), {n_all} in all; "
          f"{len(failures)} images failed, {len(failed)} chunks failed")
    if failed:
        print(f"sbr.regress: {len(failed)} chunks failed: what was computed is in {dest}; the earlier files in "
              f"{a.out} are unchanged; --resume computes the missing chunks")
    if ev:
        print(ev, end="")
    for x in failures[:10]:
        print(f"  failed: {x}")
    if len(failures) == len(paths):
        return 1  # nothing usable
    return 3 if failures or failed else 0


if __name__ == "__main__":
    sys.exit(main())
