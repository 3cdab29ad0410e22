"""``python -m ifgm_ref`` runs the command line."""

import sys

from ifgm_ref.apps.cli import main

if __name__ == "__main__":
    sys.exit(main())
