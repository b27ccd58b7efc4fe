"""``python -m mawdo.experiments run|report|presets``: the ``mawdo bench`` commands."""

from mawdo.experiments.cli import bench_app

if __name__ == "__main__":  # guard: worker processes re-import the main module
    bench_app(prog_name="mawdo bench")
