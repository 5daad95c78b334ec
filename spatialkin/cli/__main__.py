"""python -m spatialkin.cli: the command line (spatialkin.cli.main)."""
import sys

from . import main

sys.exit(main())
