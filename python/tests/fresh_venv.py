#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""ctest python_wheel_fresh_venv: the sbr wheel as a user installs it.

    fresh_venv.py --work DIR --data GTSDB_DIR --detect SBR_DETECT

1. builds the wheel from this checkout (`pip wheel`, the environment's pinned build tools);
2. makes a fresh venv from the system's python3 (no project packages, no test
   requirements) and installs the wheel with its 'regress' and 'notebook' extras: only
   what the wheel declares comes in (from PyPI, held to the project's pins of
   tests/python/requirements.txt as constraints, which add nothing);
3. from an unrelated folder, with a PATH that holds no project tool, runs
   `python -m sbr.regress` on ten GTSDB images: exit 0, evaluation.txt (the package's
   own evaluation) and pr_curve.png written;
4. runs the README's Python example verbatim in a folder holding 00444.jpg: the classes
   it prints are those sbr_detect finds on the image, and it writes its figure.
Prints what was installed and how long each step took.
"""
import glob
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = os.path.dirname(HERE)
ROOT = os.path.dirname(PACKAGE)
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
from fresh_venv_install import install, start  # noqa: E402  (the project's test helpers)


def run(cmd, **kw):
    t0 = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    return r, time.time() - t0


def readme_example():
    """The README's Python example: the first ```python block under 'Using sbr from Python'."""
    with open(os.path.join(ROOT, "README.md")) as f:
        text = f.read()
    section = text[text.index("## Using sbr from Python"):]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def main():
    a = start(__doc__.split("\n\n")[0], "sbr_detect, for the classes on 00444")
    if a is None:
        return 77
    ok = True

    r, t = run([sys.executable, "-m", "pip", "wheel", "-q", "--disable-pip-version-check", "--no-build-isolation",
                "--no-deps", "-w", os.path.join(a.work, "wheel"), PACKAGE])
    if r.returncode != 0:
        print(r.stdout + r.stderr)
        return 1
    wheel = glob.glob(os.path.join(a.work, "wheel", "sbr-*.whl"))[0]
    print(f"1. wheel {os.path.basename(wheel)} built in {t:.1f} s")

    py, frozen, t, err = install(a.work, f"{wheel}[regress,notebook]", a.work)
    if err:
        print(err)
        return 1
    venv = os.path.dirname(os.path.dirname(py))
    names = sorted(x.split("==")[0].lower() for x in frozen)
    print(f"2. fresh venv, pip install 'sbr[regress,notebook]' in {t:.1f} s: {len(names)} packages: "
          f"{', '.join(names)}")
    for unwanted in ("pytest", "playwright", "cantools", "opencv-python"):
        if unwanted in names:
            print(f"FAIL: {unwanted} is installed, and nothing declares it")
            ok = False

    elsewhere = os.path.join(a.work, "elsewhere")
    os.makedirs(elsewhere)
    env = {"PATH": "/usr/bin:/bin", "HOME": os.environ.get("HOME", a.work), "LANG": "C.UTF-8"}
    out = os.path.join(a.work, "run")
    r, t = run([py, "-m", "sbr.regress", "--input", a.data, "--range", "400-409", "--out", out, "--workers", "1"],
               cwd=elsewhere, env=env, timeout=600)
    ev = os.path.join(out, "evaluation.txt")
    report = open(ev).read() if os.path.isfile(ev) else ""
    print(f"3. python -m sbr.regress --input GTSDB --range 400-409 --out run --workers 1: exit {r.returncode} in "
          f"{t:.1f} s; evaluation.txt: {report.splitlines()[0] if report else 'MISSING'}")
    print("\n".join("   " + x for x in r.stdout.strip().splitlines()[-3:]))
    if r.returncode != 0 or not next((ln for ln in report.splitlines() if not ln.startswith("note:")), "").startswith(
                "images 10, ground-truth boxes") or \
            not os.path.isfile(os.path.join(out, "pr_curve.png")):
        print(r.stderr)
        ok = False

    nb = os.path.join(a.work, "notebook")
    os.makedirs(nb)
    shutil.copy(os.path.join(a.images, "00444.jpg"), nb)
    with open(os.path.join(nb, "example.py"), "w") as f:
        f.write(readme_example())
    r, t = run([py, "example.py"], cwd=nb, env=dict(env, MPLBACKEND="Agg"), timeout=300)
    printed = sorted(line.split()[0] for line in r.stdout.strip().splitlines() if line.strip())
    ref, _ = run([a.detect, "--input", nb, "--quiet", "--detections", os.path.join(a.work, "d444.txt")])
    names = dbc_class_names()
    with open(os.path.join(a.work, "d444.txt")) as f:
        want = sorted(names[int(line.split(";")[5])] for line in f if line.strip())
    figure = [x for x in os.listdir(nb) if x.endswith(".png")]
    print(f"4. the README's example in a folder with 00444.jpg: exit {r.returncode} in {t:.1f} s, printed {printed}, "
          f"sbr_detect finds {want}; figure {figure}")
    if r.returncode != 0 or printed != want or not figure:
        print(r.stderr)
        ok = False
    print("ok" if ok else "FAILED")
    return 0 if ok else 1


def dbc_class_names():
    """The DBC's value names of the classes (dbc/sbr.dbc), the names the package prints."""
    with open(os.path.join(ROOT, "dbc", "sbr.dbc")) as f:
        line = next(x for x in f if x.startswith("VAL_ 768 SBR_Sign_Class "))
    return {int(k): v for k, v in re.findall(r'(\d+) "([^"]+)"', line)}


if __name__ == "__main__":
    sys.exit(main())
