"""RunStreams draws: each run's numbers are its own generator's, in its own order."""

import numpy as np
import pytest

from mawdo.streams import RunStreams


@pytest.mark.parametrize("shape", [(), (5,), (4, 3), (2, 3, 4)])
@pytest.mark.parametrize("kind", ["normal", "random"])
def test_each_run_draws_what_its_generator_alone_would(kind, shape):
    streams = RunStreams([np.random.default_rng(s) for s in (3, 1, 4)])
    alone = [np.random.default_rng(s) for s in (3, 1, 4)]
    for _ in range(2):  # the second call goes on where the first stopped
        got = getattr(streams, kind)(shape)
        draw = "standard_normal" if kind == "normal" else "random"
        expect = np.stack([getattr(g, draw)(size=shape) for g in alone])
        assert got.shape == (3, *shape)
        assert np.array_equal(got, expect)
