"""A RunStreams stand-in that hands out prescribed draws, for equation tests."""

import numpy as np


class FixedStreams:
    """Returns queued arrays for each method, in call order; fails loudly on a mismatch."""

    def __init__(self, runs=1, **queues):
        self.runs = runs
        self.queues = {k: list(v) for k, v in queues.items()}

    def _next(self, kind, shape):
        q = self.queues.get(kind)
        if not q:
            raise AssertionError(f"unexpected draw: {kind}{shape}")
        arr = np.asarray(q.pop(0), dtype=float if kind != "permutations" else int)
        if arr.shape != (self.runs, *shape):
            raise AssertionError(f"{kind} draw shape {arr.shape} != {(self.runs, *shape)}")
        return arr

    def random(self, shape=()):
        shape = (shape,) if np.isscalar(shape) else tuple(shape)
        return self._next("random", shape)

    def random_parts(self, *shapes):
        """Successive ``random`` draws, as :meth:`mawdo.streams.RunStreams.random_parts`."""
        return [self.random(s) for s in shapes]

    def uniform(self, low, high, shape=()):
        return low + (np.asarray(high) - low) * self.random(shape)

    def normal(self, shape=()):
        shape = (shape,) if np.isscalar(shape) else tuple(shape)
        return self._next("normal", shape)

    def permutations(self, n, d):
        return self._next("permutations", (n, d))

    def shuffle_rows(self, out):
        """The in-place permutation draw of the optimizers: the queued ``permutations`` array."""
        out[...] = self._next("permutations", out.shape[1:])
        return out

    def exhausted(self):
        return all(not q for q in self.queues.values())
