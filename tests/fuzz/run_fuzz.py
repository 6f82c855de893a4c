#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Run sbr's libFuzzer harnesses and report executions, coverage and findings.

    run_fuzz.py --bin DIR --corpus DIR [--seeds DIR] [--targets a,b,...]
                (--runs N | --seconds S) [--jobs J] [--report FILE]

Each target fuzz_NAME in --bin runs on its corpus folder (--corpus/NAME, kept between
runs, so a nightly campaign resumes where it stopped) after the seed folder
(--seeds/NAME, made from real data at set-up) if there is one. --runs N: a fixed number
of inputs after the corpus (the smoke in ./sbr.sh test; seed 1, so a run is repeatable);
--seconds S: as long as asked (./sbr.sh fuzz). Findings (crash-, timeout-, oom-, leak-
files) are written to --corpus/findings/NAME and listed; the exit status is 1 when there
is one, so a finding fails the test command.
"""
import argparse
import concurrent.futures
import os
import re
import subprocess
import sys
import time


def run_one(name, a):
    exe = os.path.join(a.bin, f"fuzz_{name}")
    corpus = os.path.join(a.corpus, name)
    findings = os.path.join(a.corpus, "findings", name)
    os.makedirs(corpus, exist_ok=True)
    os.makedirs(findings, exist_ok=True)
    before = set(os.listdir(findings))
    cmd = [exe, "-print_final_stats=1", "-rss_limit_mb=4096", "-timeout=25", "-max_len=16384",
           f"-artifact_prefix={findings}/"]
    if a.runs is not None:
        cmd += [f"-runs={a.runs}", "-seed=1"]
    else:
        cmd += [f"-max_total_time={a.seconds}"]
    cmd.append(corpus)
    seeds = os.path.join(a.seeds, name) if a.seeds else None
    if seeds and os.path.isdir(seeds):
        cmd.append(seeds)
    start = time.monotonic()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
    secs = time.monotonic() - start
    out = p.stdout
    with open(os.path.join(a.corpus, f"{name}.log"), "w") as f:
        f.write(out)
    execs = re.findall(r"stat::number_of_executed_units: (\d+)", out)
    cov = re.findall(r"cov: (\d+) ft: (\d+) corp: (\d+)/", out)
    new = sorted(set(os.listdir(findings)) - before)
    return {
        "name": name,
        "rc": p.returncode,
        "execs": int(execs[-1]) if execs else 0,
        "secs": secs,
        "cov": int(cov[-1][0]) if cov else 0,
        "ft": int(cov[-1][1]) if cov else 0,
        "corpus": int(cov[-1][2]) if cov else len(os.listdir(corpus)),
        "findings": new,
        "tail": "\n".join(out.splitlines()[-25:]),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", required=True)
    ap.add_argument("--corpus", required=True)
    ap.add_argument("--seeds")
    ap.add_argument("--targets", default="")
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--runs", type=int)
    g.add_argument("--seconds", type=int)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--report")
    a = ap.parse_args()
    if (a.runs is not None and a.runs < 0) or (a.seconds is not None and a.seconds < 1):
        ap.error("--runs >= 0, --seconds >= 1")
    names = [t for t in a.targets.split(",") if t] or sorted(
        f[len("fuzz_"):] for f in os.listdir(a.bin) if f.startswith("fuzz_") and os.access(os.path.join(a.bin, f), os.X_OK))
    missing = [n for n in names if not os.access(os.path.join(a.bin, f"fuzz_{n}"), os.X_OK)]
    if missing:
        print("no harness: " + ", ".join(missing), file=sys.stderr)
        return 2
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        results = list(ex.map(lambda n: run_one(n, a), names))
    mode = f"{a.runs} runs a target after the corpus" if a.runs is not None else f"{a.seconds} s a target"
    lines = [f"fuzzing ({mode}, {a.jobs} at a time; libFuzzer + ASan + UBSan)",
             "| target | executions | time (s) | coverage (edges) | features | corpus | findings |",
             "| --- | ---: | ---: | ---: | ---: | ---: | --- |"]
    bad = 0
    for r in results:
        problem = r["findings"] or r["rc"] != 0
        bad += 1 if problem else 0
        found = ", ".join(r["findings"]) if r["findings"] else ("0" if r["rc"] == 0 else f"exit {r['rc']}")
        lines.append(f"| {r['name']} | {r['execs']} | {r['secs']:.0f} | {r['cov']} | {r['ft']} | {r['corpus']} | {found} |")
    text = "\n".join(lines)
    print(text)
    for r in results:
        if r["findings"] or r["rc"] != 0:
            print(f"\n---- fuzz_{r['name']} (log {a.corpus}/{r['name']}.log):\n{r['tail']}")
    if a.report:
        with open(a.report, "w") as f:
            f.write(text + "\n")
    print(f"fuzz: {len(results) - bad} passed, {bad} failed")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
