#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""ctest dashboard_fresh_venv: the dashboard package as a user installs it.

    test_dashboard_fresh_venv.py --work DIR --data GTSDB_DIR --detect SBR_DETECT

1. sbr_detect writes the CAN log of two GTSDB images with speed-limit signs (00444, 00445);
2. a fresh venv from the system's python3 (no project packages, no test requirements)
   gets `pip install dashboard/` (a wheel built from the checkout): only what the package
   declares comes in (PyPI, held to the project's pins as constraints);
3. from an unrelated folder, with a PATH that holds no project tool and without --dbc,
   `sbr-dashboard --log LOG --terminal --once --fast` must exit 0, show the speed limit of
   the last image's best speed-limit detection (from sbr_detect's detections file) and
   every message of the DBC decoded (the DBC is installed with the package).
"""
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fresh_venv_install import install, start  # noqa: E402


def run(cmd, **kw):
    t0 = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    return r, time.time() - t0


# km/h of GTSDB's speed-limit classes
KMH = {0: 20, 1: 30, 2: 50, 3: 60, 4: 70, 5: 80, 7: 100, 8: 120}


def expected_limit(det_path):
    """The km/h of the best speed-limit detection of the last image in the file."""
    rows = [line.strip().split(";") for line in open(det_path) if line.strip()]
    last = max(row[0] for row in rows)
    best = max((float(row[6]), int(row[5])) for row in rows if row[0] == last and int(row[5]) in KMH)
    return KMH[best[1]]


def main():
    a = start(__doc__.split("\n\n")[0], "sbr_detect")
    if a is None:
        return 77
    log = os.path.join(a.work, "can.log")
    r, t = run([a.detect, "--input", a.data, "--range", "444-445", "--quiet", "--detections",
                os.path.join(a.work, "det.txt"), "--canlog", log])
    if r.returncode != 0 or not os.path.isfile(log):
        print(r.stdout + r.stderr)
        return 1
    print(f"1. sbr_detect wrote the CAN log of 00444-00445 in {t:.1f} s")

    pkg = os.path.join(a.work, "dashboard")  # a copy: the build leaves nothing in the checkout
    shutil.copytree(os.path.join(ROOT, "dashboard"), pkg, symlinks=False,
                    ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__", "tests"))
    py, frozen, t, err = install(a.work, pkg, a.work)
    if err:
        print(err)
        return 1
    venv = os.path.dirname(os.path.dirname(py))
    print(f"2. fresh venv, pip install dashboard/ in {t:.1f} s: " + ", ".join(frozen))

    elsewhere = os.path.join(a.work, "elsewhere")
    os.makedirs(elsewhere)
    env = {"PATH": "/usr/bin:/bin", "HOME": a.work}
    r, t = run([os.path.join(venv, "bin", "sbr-dashboard"), "--log", log, "--terminal", "--once", "--fast"],
               cwd=elsewhere, env=env)
    out = r.stdout + r.stderr
    decoded = all(re.search(rf"^{m}\s+ok\s+[1-9]", out, re.M)
                  for m in ("SBR_ConfirmedSign", "SBR_EcuStatus", "SBR_Detection", "SBR_TrackedObject"))
    want = f"SPEED LIMIT: {expected_limit(os.path.join(a.work, 'det.txt'))} km/h"
    good = r.returncode == 0 and want in out and decoded
    print(f"3. sbr-dashboard --log --terminal --once --fast (no --dbc): exit {r.returncode} in {t:.1f} s, "
          f"'{want}' {'shown' if want in out else 'MISSING'}, "
          f"every message decoded: {'yes' if decoded else 'NO'}")
    if not good:
        print(out)
    print("dashboard fresh venv: " + ("OK" if good else "FAILED"))
    return 0 if good else 1


if __name__ == "__main__":
    sys.exit(main())
