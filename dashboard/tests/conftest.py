# SPDX-License-Identifier: MIT
"""The dashboard's tests run against the installed package (./sbr.sh installs it into
build/venv: pip install -e dashboard)."""
import os

HERE = os.path.dirname(os.path.abspath(__file__))
DBC = os.path.join(os.path.dirname(os.path.dirname(HERE)), "dbc", "sbr.dbc")
