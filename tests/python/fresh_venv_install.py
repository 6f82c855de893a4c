# SPDX-License-Identifier: MIT
"""A package installed as a user installs it, for the fresh-venv tests
(python/tests/fresh_venv.py, tests/python/test_dashboard_fresh_venv.py): a new venv from
the system's python3 (no project packages, no test requirements), then `pip install` of
what is given, held to the project's pins as constraints."""
import os
import re
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
