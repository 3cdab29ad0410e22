"""``python -m ifgm_ref.apps.cli`` runs the command line (as ``python -m ifgm_ref`` does)."""

import sys

from ifgm_ref.apps.cli import main

if __name__ == "__main__":
    sys.exit(main())
