"""``python -m mstmm``: the command line."""

from .cli import main

raise SystemExit(main())
