# SPDX-License-Identifier: MIT
"""A package installed as a user installs it, for the fresh-venv tests
(python/tests/fresh_venv.py, tests/python/test_dashboard_fresh_venv.py): a new venv from
the system's python3 (no project packages, no test requirements), then `pip install` of
what is given, held to the project's pins as constraints; and the two tests' common
start (options, the GTSDB frame they need, a fresh work folder)."""
import argparse
import os
import re
import shutil
import subprocess
import time

REQUIREMENTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "requirements.txt")


def install(work, target, cwd):
    """Makes work/venv and installs `target` (a wheel, a folder, with extras) into it.
    Returns (python of the venv, frozen package list, seconds, error output or "")."""
    t0 = time.time()
    venv = os.path.join(work, "venv")
    py = os.path.join(venv, "bin", "python")
    r = subprocess.run(["python3", "-m", "venv", venv], capture_output=True, text=True)
    if r.returncode != 0:
        return py, [], time.time() - t0, r.stdout + r.stderr
    # the project's pins as constraints: name==version lines only (a '-r' line there would
    # be read as requirements and install more than the package declares)
    constraints = os.path.join(work, "constraints.txt")
    with open(REQUIREMENTS) as f, open(constraints, "w") as c:
        c.writelines(line for line in f if re.match(r"^[A-Za-z0-9_.\-\[\]]+==", line))
    r = subprocess.run([py, "-m", "pip", "install", "-q", "--disable-pip-version-check", "-c", constraints, target],
                       capture_output=True, text=True, cwd=cwd)
    if r.returncode != 0:
        return py, [], time.time() - t0, r.stdout + r.stderr
    frozen = subprocess.run([py, "-m", "pip", "list", "--format=freeze", "--disable-pip-version-check"],
                            capture_output=True, text=True).stdout.split()
    return py, frozen, time.time() - t0, ""


def start(description, detect_help):
    """The tests' options (--work, --data GTSDB, --detect sbr_detect; a.images: the folder
    of GTSDB's frames) with a fresh, empty --work folder; None (the caller skips, 77) when GTSDB's frame 00444 is not there."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--work", required=True)
    ap.add_argument("--data", required=True, help="GTSDB folder")
    ap.add_argument("--detect", required=True, help=detect_help)
    a = ap.parse_args()
    images = os.path.join(a.data, "FullIJCNN2013") if os.path.isdir(os.path.join(a.data, "FullIJCNN2013")) else a.data
    if not os.path.isfile(os.path.join(images, "00444.jpg")):
        print(f"SKIP: no GTSDB images in {a.data}")
        return None
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    a.images = images
    return a
