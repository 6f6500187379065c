"""python -m fastrest: the command-line interface (fastrest/cli.py)."""
import sys

from .cli import main

sys.exit(main())
