"""``python -m mawdo.cli``: the ``mawdo`` command."""

from mawdo.cli import program

if __name__ == "__main__":  # guard: worker processes re-import the main module
    program()
