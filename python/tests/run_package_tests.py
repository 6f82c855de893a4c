#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""ctest python_package: the sbr wheel built from this checkout, installed, tested.

    run_package_tests.py --work DIR [pytest args]

1. `pip wheel --no-build-isolation --no-deps ./python` with the environment's pinned
   scikit-build-core and nanobind (what `pip install ./python` does, without fetching the
   build tools again): prints the wheel's build time and size;
2. installs it into DIR/site (`pip install --no-deps --target`);
3. runs pytest on python/tests against that installed copy (not the source folder), with
   SBR_DETECT, SBR_EVAL, SBR_DATA passed through from the environment.
"""
import glob
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = os.path.dirname(HERE)


def main():
    args = sys.argv[1:]
    if len(args) < 2 or args[0] != "--work":
        print(__doc__)
        return 2
    work, rest = args[1], args[2:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    t0 = time.time()
    subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--disable-pip-version-check", "--no-build-isolation",
                    "--no-deps", "-w", os.path.join(work, "wheel"), PACKAGE], check=True)
    built = time.time() - t0
    wheel = glob.glob(os.path.join(work, "wheel", "sbr-*.whl"))[0]
    print(f"wheel: {os.path.basename(wheel)}, built in {built:.1f} s, {os.path.getsize(wheel) / 1024:.0f} KiB",
          flush=True)
    site = os.path.join(work, "site")
    subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--disable-pip-version-check", "--no-deps",
                    "--target", site, wheel], check=True)
    env = dict(os.environ, PYTHONPATH=site, PYTHONDONTWRITEBYTECODE="1")
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs", HERE, *rest],
                          env=env, cwd=work).returncode


if __name__ == "__main__":
    sys.exit(main())
