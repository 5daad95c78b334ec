"""tests/spatialkin: its oracle modules (oracles.py, ssi_oracle.py, ...) importable from the subfolders too."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
if HERE not in sys.path:
    sys.path.insert(0, HERE)
