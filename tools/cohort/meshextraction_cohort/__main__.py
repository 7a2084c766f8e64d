"""python3 -m meshextraction_cohort: the same as the meshextraction-cohort script."""

import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
