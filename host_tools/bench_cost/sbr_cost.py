#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""sbr's cost benchmark (./sbr.sh cost; docs/usage/cost.md).

Instructions per frame of sbr_recog_detect, which do not depend on the machine's load:
  - host (x86-64): valgrind's callgrind on fixed frames, collected inside sbr_recog_detect
    only (sbr_detect --callgrind), one dump per stage; the part stage is split into maps
    (sbr_map_make, sbr_map_make_bright), regions (sbr_mser_detect_in_place, the part stage's MSER) and contours + FDs (the rest: region masks,
    tracing, descriptors) by callgrind_annotate's inclusive counts;
  - Cortex-M4F: the bench image tests/bench_m4/sbr_cost_m4.c on qemu mps2-an386 with
    -icount shift=0 (1 instruction = 1 ns of virtual time, read from a timer), the same
    frames as PPM, built-in model and default options; its detections are compared with
    the host's on the same pixels (box edges within 1 px, scores within 1e-3, the
    tolerance of the scene test, cmake/compare_scene.py);
the Cortex-M4F's cost of one class-stage look (tests/bench_m4/sbr_picto_m4.c: features
and classifier apart, per box side); the strip configuration (sbr_detect --strips; on the
Cortex-M4F sbr_cost_m4_strips.elf beside the image, its workspace in the SRAM) on the same
frames; and both on the hostile frames of sbr_hostile_frames (noise, a checkerboard, a grid of
sign-like rings, random blocks: the worst case a schedule must allow for), next to
wall-clock figures of sbr_detect --repeat N on the development split (these do depend on
the machine; the fastest of N runs per frame).

usage: sbr_cost.py --bin DIR --m4-elf ELF --gtsdb DIR [--range A-B] [--m4-range A-B]
                   [--wall-range A-B] [--repeat N] [--out DIR] [--no-wall] [--no-m4]
                   [--no-hostile] [--no-strips] [-- sbr_detect options...]
Options after -- (e.g. --model F --picto F, --max-candidates N) go to the host runs; the
Cortex-M4 image always runs the built-in model with the default options.
Prints the tables and writes cost.txt and cost.json into --out.
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

STAGES = ["maps", "regions", "contours+FDs", "matching+votes", "grouping+cascade",
          "class stage", "set-up+output"]


def run(cmd, **kw):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)
    if r.returncode != 0:
        sys.exit("sbr_cost: %s failed (exit %d):\n%s%s" % (" ".join(cmd), r.returncode,
                                                           r.stdout[-2000:], r.stderr[-2000:]))
    return r.stdout


def parse_range(text):
    m = re.fullmatch(r"(\d+)-(\d+)", text)
    if not m or int(m.group(1)) > int(m.group(2)):
        sys.exit("sbr_cost: a range is A-B, A <= B: %s" % text)
    return int(m.group(1)), int(m.group(2))


def frames_of(gtsdb, rng):
    img_dir = os.path.join(gtsdb, "FullIJCNN2013") if os.path.isdir(os.path.join(gtsdb, "FullIJCNN2013")) else gtsdb
    lo, hi = rng
    out = []
    for n in range(lo, hi + 1):
        for ext in (".ppm", ".jpg", ".png"):
            p = os.path.join(img_dir, "%05d%s" % (n, ext))
            if os.path.exists(p):
                out.append(p)
                break
    if not out:
        sys.exit("sbr_cost: no images %05d-%05d in %s" % (lo, hi, img_dir))
    return out


def inclusive(cg_file, functions):
    """Inclusive instructions of the named functions in one callgrind dump."""
    text = run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", cg_file])
    got = {f: 0 for f in functions}
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+) \([^)]*\)\s+\S*:(\w+)", line)
        if m and m.group(2) in got:
            got[m.group(2)] = max(got[m.group(2)], int(m.group(1).replace(",", "")))
    return got


def host_callgrind(args, extra, work, inputs=None, name="callgrind"):
    """Per-frame, per-stage instructions of sbr_detect on `inputs` (sbr_detect options that
    name the frames; default the GTSDB frames of --range), dumps in work/<name>."""
    cg_dir = os.path.join(work, name)
    shutil.rmtree(cg_dir, ignore_errors=True)
    os.makedirs(cg_dir)
    if inputs is None:
        inputs = ["--input", args.gtsdb, "--range", "%d-%d" % args.range]
    cmd = ["valgrind", "--tool=callgrind", "--collect-atstart=no",
           "--callgrind-out-file=" + os.path.join(cg_dir, "cg.out"),
           os.path.join(args.bin, "sbr_detect")] + inputs + [
           "--detections", os.path.join(work, name + "_detections.txt"), "--callgrind", "--quiet"] + extra
    run(cmd)
    frames = {}
    for name in sorted(os.listdir(cg_dir)):
        path = os.path.join(cg_dir, name)
        desc = summary = None
        with open(path) as f:
            for line in f:
                if line.startswith("desc: Trigger: Client Request: "):
                    desc = line[len("desc: Trigger: Client Request: "):].strip()
                elif line.startswith("summary: "):
                    summary = int(line.split()[1])
                    break
        if desc is None or summary is None:
            continue  # the program-termination dump
        m = re.fullmatch(r"frame (\S+) (setup|stage (\d)|end|ecu)", desc)
        if not m:
            continue
        fr = frames.setdefault(m.group(1), {s: 0 for s in STAGES})
        if m.group(2) == "ecu":
            # the ECU job after the recogniser (sbr_detect --canlog): the core's part
            # without the port's writing, and the sign tracking with the restrictions
            inc = inclusive(path, ["sbr_ecu_output", "sbr_can_send", "sbr_signs_update", "sbr_rules_update"])
            fr["ecu"] = inc["sbr_ecu_output"] - inc["sbr_can_send"]
            fr["tracking+rules"] = inc["sbr_signs_update"] + inc["sbr_rules_update"]
            continue
        if m.group(2) in ("setup", "end"):
            fr["set-up+output"] += summary
            continue
        k = int(m.group(3))
        if k == 0:
            inc = inclusive(path, ["sbr_map_make", "sbr_map_make_bright", "sbr_mser_detect_in_place"])
            maps = inc["sbr_map_make"] + inc["sbr_map_make_bright"]
            fr["maps"] += maps
            fr["regions"] += inc["sbr_mser_detect_in_place"]
            fr["contours+FDs"] += summary - maps - inc["sbr_mser_detect_in_place"]
        elif k == 1:
            fr["matching+votes"] += summary
        elif k in (2, 3, 4):
            fr["grouping+cascade"] += summary
        else:
            fr["class stage"] += summary
    for fr in frames.values():
        fr["total"] = sum(fr[s] for s in STAGES)
    return frames


def wall_clock(args, extra, work):
    lo, hi = args.wall_range
    summary = os.path.join(work, "wall_summary.txt")
    run([os.path.join(args.bin, "sbr_detect"), "--input", args.gtsdb, "--range", "%d-%d" % (lo, hi),
         "--detections", os.path.join(work, "wall_detections.txt"), "--repeat", str(args.repeat),
         "--quiet", "--summary", summary] + extra)
    with open(summary) as f:
        text = f.read()
    m = re.search(r"time per frame \(one core[^)]*\): median ([\d.]+) ms, 95th percentile ([\d.]+) ms", text)
    ws = re.search(r"workspace: (\d+) bytes", text)
    return {"median_ms": float(m.group(1)), "p95_ms": float(m.group(2)),
            "workspace": int(ws.group(1)) if ws else None, "frames": hi - lo + 1, "repeat": args.repeat}


def read_dets(lines):
    out = []
    for line in lines:
        f = line.strip().split(";")
        if len(f) >= 6:
            out.append([int(f[-6]), int(f[-5]), int(f[-4]), int(f[-3]), int(f[-2]), float(f[-1])])
    return out


def same_dets(a, b):
    if len(a) != len(b):
        return False
    free = list(range(len(b)))
    for d in a:
        j = next((j for j in free if b[j][4] == d[4] and all(abs(b[j][i] - d[i]) <= 1 for i in range(4))
                  and abs(b[j][5] - d[5]) <= 1e-3), None)
        if j is None:
            return False
        free.remove(j)
    return True


def hostile_frames(args, work):
    """The hostile frames (sbr_hostile_frames) in work/hostile."""
    d = os.path.join(work, "hostile")
    shutil.rmtree(d, ignore_errors=True)
    run([os.path.join(args.bin, "sbr_hostile_frames"), "--out", d])
    return d


def cortex_m4(args, work, ppm_dir=None, elf=None, host_opts=()):
    """Per-frame Cortex-M4 figures of the bench image `elf` (default --m4-elf) on the GTSDB
    frames of --m4-range (converted to PPM), or on the PPM frames of ppm_dir; host_opts:
    the sbr_detect options of the same configuration on the host."""
    elf = elf or args.m4_elf
    if ppm_dir is None:
        ppm_dir = os.path.join(work, "ppm")
        if not os.path.isdir(ppm_dir):
            files = frames_of(args.gtsdb, args.m4_range)
            run([os.path.join(args.bin, "sbr_to_ppm"), "--out", ppm_dir] + files)
    # the host's detections on the same pixels, built-in model, the configuration's options
    # (floor 0.3)
    tag = os.path.basename(ppm_dir) + ("_strips" if "--strips" in host_opts else "")
    host_det = os.path.join(work, "m4_%s_host_detections.txt" % tag)
    run([os.path.join(args.bin, "sbr_detect"), "--input", ppm_dir, "--detections", host_det,
         "--threshold", "0.3", "--min-score", "0.3", "--quiet"] + list(host_opts))
    host = {}
    with open(host_det) as f:
        for line in f:
            host.setdefault(os.path.splitext(line.split(";")[0])[0], []).append(line)
    frames = {}
    run_dir = os.path.join(work, "qemu")
    os.makedirs(run_dir, exist_ok=True)
    for name in sorted(os.listdir(ppm_dir)):
        stem = name[:-4]
        link = os.path.join(run_dir, "frame.ppm")
        if os.path.lexists(link):
            os.remove(link)
        os.symlink(os.path.abspath(os.path.join(ppm_dir, name)), link)
        out = run(["qemu-system-arm", "-M", "mps2-an386", "-cpu", "cortex-m4", "-nographic",
                   "-icount", "shift=0", "-semihosting-config", "enable=on,target=native",
                   "-kernel", os.path.abspath(elf)], cwd=run_dir, timeout=1800)
        fr = {"stages": {}, "dets": []}
        for line in out.splitlines():
            if line.startswith("stage "):
                k, v = line[6:].split(":")
                fr["stages"][int(k)] = int(float(v))
            elif line.startswith("total: "):
                fr["total"] = int(float(line.split()[1]))
            elif line.startswith("init: "):
                fr["init"] = int(float(line.split()[1]))
            elif line.startswith("view: "):
                fr["view"] = line[6:]
            elif line.startswith("workspace: "):
                fr["workspace"] = int(line.split()[1])
            elif line.startswith("calibration: "):
                fr["calibration"] = float(line.split()[1])
            elif line.startswith("status: "):
                fr["status"] = line.split()[1]
            elif line.startswith("det: "):
                fr["dets"].append(line[5:])
        fr["same_as_host"] = same_dets(read_dets(host.get(stem, [])), read_dets(fr["dets"]))
        fr["host_dets"] = len(host.get(stem, []))
        frames[stem] = fr
    return frames


def picto_m4(args, work):
    """One class-stage look on the Cortex-M4F (tests/bench_m4/sbr_picto_m4.c, beside the
    frame image): features and classifier instructions per box side and outline."""
    elf = os.path.join(os.path.dirname(os.path.abspath(args.m4_elf)), "sbr_picto_m4.elf")
    if not os.path.exists(elf):
        return None
    out = run(["qemu-system-arm", "-M", "mps2-an386", "-cpu", "cortex-m4", "-nographic",
               "-icount", "shift=0", "-semihosting-config", "enable=on,target=native",
               "-kernel", elf], cwd=work, timeout=600)
    looks = {"looks": []}
    for line in out.splitlines():
        m = re.match(r"look (\d+) (\d+): features (\d+) classify (\d+)$", line)
        if m:
            looks["looks"].append([int(m.group(k)) for k in range(1, 5)])
        elif line.startswith("calibration: "):
            looks["calibration"] = float(line.split()[1])
        elif line.startswith("mean: "):
            f = line.split()
            looks["mean"] = {"features": int(f[2]), "classify": int(f[4])}
    return looks


def picto_table(looks, lines):
    """Appends picto_m4()'s figures: per box side, the box outline's and the triangle's."""
    lines.append("  %-10s%20s%20s%20s" % ("box side", "features (box)", "features (triangle)", "classify"))
    by_side = {}
    for side, outline, feat, cls in looks["looks"]:
        by_side.setdefault(side, {})[outline] = (feat, cls)
    for side in sorted(by_side):
        b = by_side[side]
        lines.append("  %-10s%20s%20s%20s" % ("%d px" % side, "%.3f" % (b[0][0] / 1e6),
                                              "%.3f" % (b[1][0] / 1e6), "%.3f" % (b[0][1] / 1e6)))


def mega(v):
    return "%.1f" % (v / 1e6)


def host_table(host, lines, summary):
    """Appends the per-frame, per-stage table of host_callgrind()'s figures (and with
    summary its median, mean and shares); returns the median and mean per column."""
    cols = STAGES + ["total"]
    width = max([8] + [len(n) for n in host])
    lines.append("  %-*s" % (width, "frame") + "".join("%17s" % c for c in cols))
    for name in sorted(host):
        lines.append("  %-*s" % (width, name) + "".join("%17s" % mega(host[name][c]) for c in cols))
    med = {c: statistics.median([host[n][c] for n in host]) for c in cols}
    mean = {c: statistics.mean([host[n][c] for n in host]) for c in cols}
    if summary:
        lines.append("  %-*s" % (width, "median") + "".join("%17s" % mega(med[c]) for c in cols))
        lines.append("  %-*s" % (width, "mean") + "".join("%17s" % mega(mean[c]) for c in cols))
        lines.append("  share of the mean: " + ", ".join("%s %.0f %%" % (c, 100.0 * mean[c] / mean["total"])
                                                         for c in STAGES))
    return med, mean


def m4_table(m4, lines):
    """Appends the per-frame table of cortex_m4()'s figures; returns the totals."""
    names = ["parts", "votes", "grouping", "cascade", "NMS", "class stage"]
    width = max([8] + [len(n) for n in m4])
    lines.append("  %-*s" % (width, "frame") + "".join("%13s" % c for c in names)
                 + "%13s%10s  %s" % ("total", "same dets", "view"))
    for name in sorted(m4):
        fr = m4[name]
        lines.append("  %-*s" % (width, name) + "".join("%13s" % mega(fr["stages"].get(k, 0)) for k in range(6))
                     + "%13s%10s  %s" % (mega(fr.get("total", 0)), "yes" if fr["same_as_host"] else "NO",
                                         fr.get("view", "?")))
    return [m4[n].get("total", 0) for n in m4]


def host_hostile(args, opts, hostile_dir, name, title, what, median, lines):
    """x86-64 on the hostile frames with sbr_detect options opts: the table under `title`,
    the worst frame's line (`what`: whose median it is set against). Returns the frames
    and the worst one's ratio to `median` (instructions)."""
    hh = host_callgrind(args, opts, args.out, ["--input", hostile_dir], name)
    lines.append("")
    lines.append(title)
    host_table(hh, lines, False)
    hw = max(hh, key=lambda n: hh[n]["total"])
    ratio = hh[hw]["total"] / median
    lines.append("%s: %.3f x 10^9 instructions (%s), %.2f x the %s" % (what[0], hh[hw]["total"] / 1e9, hw, ratio,
                                                                      what[1]))
    return hh, ratio


def m4_hostile(args, hostile_dir, elf, host_opts, title, what, median, lines):
    """The Cortex-M4F image `elf` on the hostile frames, as host_hostile()."""
    m4h = cortex_m4(args, args.out, hostile_dir, elf=elf, host_opts=host_opts)
    lines.append("")
    lines.append(title)
    m4_table(m4h, lines)
    hw = max(m4h, key=lambda n: m4h[n].get("total", 0))
    ratio = m4h[hw].get("total", 0) / median
    lines.append("%s: %.3f x 10^9 instructions (%s), %.2f x the %s; detections the same as the host's on %d of %d"
                 " frames" % (what[0], m4h[hw].get("total", 0) / 1e9, hw, ratio, what[1],
                              sum(1 for n in m4h if m4h[n]["same_as_host"]), len(m4h)))
    return m4h, ratio


def m4_summary(m4, heading, label, same_as, lines):
    """The Cortex-M4F's table of frames under `heading` and its summary line; returns the
    median instructions per frame."""
    lines.append("")
    lines.append(heading)
    tot = m4_table(m4, lines)
    same = sum(1 for n in m4 if m4[n]["same_as_host"])
    worst = max(m4, key=lambda n: m4[n].get("total", 0))
    median = statistics.median(tot)
    lines.append("%s: %.3f x 10^9 instructions per frame (worst %.3f x 10^9, %s); workspace %s bytes;"
                 " detections the same as %s on %d of %d frames"
                 % (label, median / 1e9, m4[worst].get("total", 0) / 1e9, worst,
                    next(iter(m4.values())).get("workspace"), same_as, same, len(m4)))
    return median


def strips(args, extra, lines, report, host_med, hostile_dir):
    """The strip configuration (sbr_detect --strips; sbr_cost_m4_strips.elf) on the frames
    of --range and --m4-range, and on the hostile frames (hostile_dir, unless None): tables
    and medians into lines and report."""
    st = host_callgrind(args, ["--strips"] + extra, args.out, name="callgrind_strips")
    report["host_strips"] = st
    lines.append("")
    lines.append("the strip configuration (--strips: bands of 256 rows overlapping by 128, one band's workspace), "
                 "x86-64, millions of instructions:")
    smed, _ = host_table(st, lines, True)
    report["host_strips_median"] = smed
    worst = max(st, key=lambda n: st[n]["total"])
    lines.append("host median, strips: %.3f x 10^9 instructions per frame (worst %.3f x 10^9, %s), %.2f x the whole "
                 "frame's" % (smed["total"] / 1e9, st[worst]["total"] / 1e9, worst, smed["total"] / host_med["total"]))
    if hostile_dir is not None:
        report["host_strips_hostile"], report["host_strips_hostile_worst_ratio"] = host_hostile(
            args, ["--strips"] + extra, hostile_dir, "callgrind_strips_hostile",
            "the strip configuration, x86-64, the hostile frames, millions of instructions:",
            ("host hostile worst, strips", "strips' GTSDB median"), smed["total"], lines)
    elf = os.path.join(os.path.dirname(os.path.abspath(args.m4_elf or ".")), "sbr_cost_m4_strips.elf")
    if args.no_m4 or not args.m4_elf or not os.path.exists(elf):
        return
    m4 = cortex_m4(args, args.out, elf=elf, host_opts=["--strips"])
    report["cortex_m4_strips"] = m4
    median = m4_summary(m4, "the strip configuration on the Cortex-M4F (sbr_cost_m4_strips.elf, workspace in the "
                        "SRAM), frames %05d-%05d, millions of instructions:" % args.m4_range,
                        "Cortex-M4 median, strips", "the host's --strips", lines)
    report["cortex_m4_strips_median"] = median
    if hostile_dir is not None:
        report["cortex_m4_strips_hostile"], report["cortex_m4_strips_hostile_worst_ratio"] = m4_hostile(
            args, hostile_dir, elf, ["--strips"],
            "the strip configuration on the Cortex-M4F, the hostile frames, millions of instructions:",
            ("Cortex-M4 hostile worst, strips", "strips' GTSDB median"), median, lines)


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        i = argv.index("--")
        argv, extra = argv[:i], argv[i + 1:]
    ap = argparse.ArgumentParser(description="sbr's cost benchmark", usage=__doc__)
    ap.add_argument("--bin", required=True, help="folder with sbr_detect and sbr_to_ppm")
    ap.add_argument("--m4-elf", help="tests/bench_m4 sbr_cost_m4.elf")
    ap.add_argument("--gtsdb", required=True)
    ap.add_argument("--range", type=parse_range, default=(400, 419))
    ap.add_argument("--m4-range", type=parse_range, default=None)
    ap.add_argument("--wall-range", type=parse_range, default=(400, 599))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default="cost")
    ap.add_argument("--no-wall", action="store_true")
    ap.add_argument("--no-m4", action="store_true")
    ap.add_argument("--no-hostile", action="store_true", help="skip the hostile frames")
    ap.add_argument("--no-strips", action="store_true", help="skip the strip configuration")
    args = ap.parse_args(argv)
    if args.m4_range is None:
        args.m4_range = args.range
    os.makedirs(args.out, exist_ok=True)
    t0 = time.time()
    report = {"range": "%05d-%05d" % args.range, "options": extra}
    lines = ["sbr cost benchmark: sbr_recog_detect, instructions per frame (inclusive)",
             "options: %s" % (" ".join(extra) if extra else "defaults, built-in model")]

    # the recogniser's frames, and the ECU job after it (the frames as one sequence)
    host = host_callgrind(args, extra + ["--sequence", "--canlog", os.path.join(args.out, "cost_canlog.log")],
                          args.out)
    report["host"] = host
    lines.append("")
    lines.append("x86-64 (valgrind callgrind), frames %05d-%05d (%d), millions of instructions:"
                 % (args.range[0], args.range[1], len(host)))
    med, mean = host_table(host, lines, True)
    report["host_median"] = med
    report["host_mean"] = mean
    worst = max(host, key=lambda n: host[n]["total"])
    lines.append("host median: %.3f x 10^9 instructions per frame (worst of the %d: %.3f x 10^9, %s)"
                 % (med["total"] / 1e9, len(host), host[worst]["total"] / 1e9, worst))
    ecu = sorted(fr.get("ecu", 0) for fr in host.values())
    trk = sorted(fr.get("tracking+rules", 0) for fr in host.values())
    if ecu and ecu[-1] > 0:
        report["ecu_median"] = ecu[len(ecu) // 2]
        report["tracking_rules_median"] = trk[len(trk) // 2]
        lines.append("ECU job after the recogniser (sbr_ecu_output without the port; frames as one sequence): "
                     "median %d instructions per frame (worst %d); sign tracking + restrictions median %d "
                     "(worst %d) = %.3f %% of the recogniser's median"
                     % (ecu[len(ecu) // 2], ecu[-1], trk[len(trk) // 2], trk[-1],
                        100.0 * trk[len(trk) // 2] / med["total"]))
    hostile_dir = None
    if not args.no_hostile:
        hostile_dir = hostile_frames(args, args.out)
        report["host_hostile"], report["host_hostile_worst_ratio"] = host_hostile(
            args, extra, hostile_dir, "callgrind_hostile",
            "x86-64, the hostile frames (sbr_hostile_frames), millions of instructions:",
            ("host hostile worst", "GTSDB median"), med["total"], lines)

    if not args.no_m4 and args.m4_elf:
        m4 = cortex_m4(args, args.out)
        report["cortex_m4"] = m4
        median = m4_summary(m4, "Cortex-M4F (qemu mps2-an386, -icount shift=0), built-in model, default options,"
                            " frames %05d-%05d, millions of instructions:" % args.m4_range,
                            "Cortex-M4 median", "the host's (1 px, 1e-3)", lines)
        report["cortex_m4_median"] = median
        looks = picto_m4(args, args.out)
        if looks is not None:
            report["cortex_m4_picto_look"] = looks
            lines.append("")
            lines.append("Cortex-M4F, one class-stage look (tests/bench_m4/sbr_picto_m4.c), millions of"
                         " instructions:")
            picto_table(looks, lines)
        if hostile_dir is not None:
            report["cortex_m4_hostile"], report["cortex_m4_hostile_worst_ratio"] = m4_hostile(
                args, hostile_dir, args.m4_elf, (), "Cortex-M4F, the hostile frames, millions of instructions:",
                ("Cortex-M4 hostile worst", "GTSDB median"), median, lines)
        inits = [m4[n]["init"] for n in m4 if "init" in m4[n]]
        if inits:
            lines.append("sbr_recog_init (once, not per frame: the configuration and models checked): "
                         "%.2f x 10^6 instructions" % (statistics.median(inits) / 1e6))
            report["cortex_m4_init"] = statistics.median(inits)

    if not args.no_strips:
        strips(args, extra, lines, report, med, hostile_dir)

    if not args.no_wall:
        w = wall_clock(args, extra, args.out)
        report["wall"] = w
        lines.append("")
        lines.append("wall clock, this machine, one core, sbr_detect --repeat %d (fastest run per frame), "
                     "frames %05d-%05d: median %.1f ms, 95th percentile %.1f ms; workspace %s bytes"
                     % (w["repeat"], args.wall_range[0], args.wall_range[1], w["median_ms"], w["p95_ms"], w["workspace"]))
    lines.append("")
    lines.append("time: %.1f min" % ((time.time() - t0) / 60.0))
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    with open(os.path.join(args.out, "cost.txt"), "w") as f:
        f.write(text)
    with open(os.path.join(args.out, "cost.json"), "w") as f:
        json.dump(report, f, indent=1, sort_keys=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
