"""``python -m mawdo.jit``: compile the jit table's missing kernels (see :mod:`mawdo.jit.warm`)."""

import sys

from mawdo.jit.warm import main

if __name__ == "__main__":
    sys.exit(main())
