"""``python -m mawdo.cli``: the ``mawdo`` command."""

from mawdo.cli.main import app

if __name__ == "__main__":  # guard: worker processes re-import the main module
    app(prog_name="mawdo")
