"""Per-run random streams.

A batch of ``R`` independent runs draws every random number from each run's own
:class:`numpy.random.Generator`, so run ``r``'s result does not depend on which other runs share
its batch (docs/deviations.md#d-streams). ``RunStreams`` stacks one draw per run into arrays shaped
``(R, ...)``.
Each run owns two streams spawned from its seed: one for the algorithm, one for objective noise
(so adding noise to a function never shifts the algorithm's random numbers).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from mawdo.util.validate import check_int, check_seed


def run_seed_sequences(seed, runs: int, first: int = 0) -> list[np.random.SeedSequence]:
    """The seed sequences of runs ``first .. first+runs-1`` derived from one master ``seed``.

    Run ``k`` is the ``k``-th child ``SeedSequence.spawn`` would give, whatever ``runs`` and
    ``first`` are, so any run can be recomputed alone and batches can be cut anywhere.

    Parameters
    ----------
    seed : int, sequence of int, numpy.random.SeedSequence or None
        Master seed, integers >= 0 (bools and floats are refused, naming ``seed``). ``None``
        draws fresh entropy (not reproducible).
    runs : int
        Number of runs, >= 1.
    first : int
        Index of the first run, >= 0.
    """
    check_seed(seed)
    check_int("runs", runs, 1)
    check_int("first_run", first, 0)
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    return [
        np.random.SeedSequence(ss.entropy, spawn_key=(*ss.spawn_key, k), pool_size=ss.pool_size)
        for k in range(first, first + runs)
    ]


class RunStreams:
    """One generator per run; every method returns an array with a leading run axis.

    Parameters
    ----------
    generators : sequence of numpy.random.Generator
        One generator per run, in run order.
    """

    def __init__(self, generators: Sequence[np.random.Generator]) -> None:
        if len(generators) == 0:
            raise ValueError("RunStreams needs at least one generator")
        self.generators = list(generators)

    @classmethod
    def from_seed_sequences(cls, seqs: Sequence[np.random.SeedSequence]) -> RunStreams:
        return cls([np.random.default_rng(s) for s in seqs])

    @property
    def runs(self) -> int:
        return len(self.generators)

    def subset(self, index) -> RunStreams:
        """Streams of the selected runs (shared generator objects, not copies)."""
        return RunStreams([self.generators[i] for i in np.atleast_1d(index)])

    def random(self, shape=()) -> np.ndarray:
        """U[0, 1) draws, shape ``(R, *shape)``."""
        shape = (shape,) if np.isscalar(shape) else tuple(shape)
        out = np.empty((self.runs, *shape))
        # rows of a 2-D view: shape () gives length-1 rows (iterating (R,) would give scalars)
        for g, o in zip(self.generators, out.reshape(self.runs, -1), strict=True):
            g.random(out=o)
        return out

    def random_parts(self, *shapes) -> list[np.ndarray]:
        """U[0, 1) draws of several shapes, one generator call per run: the arrays
        ``(R, *shape)`` that successive :meth:`random` calls would give, bit for bit.

        Each run fills one row with all its numbers (its generator yields them in the order of
        ``shapes``), saving a Python call per run and extra shape (~1 us each).
        The arrays are views of one buffer, each C-contiguous per run.
        """
        shapes = [(s,) if np.isscalar(s) else tuple(s) for s in shapes]
        sizes = [int(np.prod(s, dtype=np.int64)) for s in shapes]
        buf = np.empty((self.runs, sum(sizes)))
        for g, row in zip(self.generators, buf, strict=True):
            g.random(out=row)
        cut = np.cumsum([0, *sizes])
        spans = zip(cut[:-1], cut[1:], shapes, strict=True)
        return [buf[:, a:b].reshape(self.runs, *s) for a, b, s in spans]

    def uniform(self, low, high, shape=()) -> np.ndarray:
        """U[low, high) draws, shape ``(R, *shape)``; bounds broadcast against ``shape``."""
        out = self.random(shape)
        width = np.asarray(high) - low
        if (
            np.broadcast_shapes(np.shape(width), np.shape(low), out.shape) == out.shape
            and np.result_type(width, low, out) == out.dtype
        ):
            # in place, no temporaries of the draw's size: ``r * w + low`` is ``low + w * r``
            # bit for bit (IEEE products and sums are commutative)
            out *= width
            out += low
            return out
        return low + width * out

    def normal(self, shape=()) -> np.ndarray:
        """Standard normal draws, shape ``(R, *shape)``."""
        shape = (shape,) if np.isscalar(shape) else tuple(shape)
        out = np.empty((self.runs, *shape))
        # rows of a 2-D view (as random()): filling a flat row is faster than an n-D one (75 vs
        # 100 us for 30 runs x 200 draws), with the same numbers in the same order
        for g, o in zip(self.generators, out.reshape(self.runs, -1), strict=True):
            g.standard_normal(out=o)
        return out

    def integers(self, high: int, shape=()) -> np.ndarray:
        """Integers in ``[0, high)``, shape ``(R, *shape)``."""
        return np.stack([g.integers(0, high, size=shape) for g in self.generators])

    def permutations(self, n: int, d: int) -> np.ndarray:
        """``n`` independent permutations of ``range(d)`` per run, shape ``(R, n, d)``."""
        # argsort of uniform keys: one vectorised sort for the whole batch
        return self.random((n, d)).argsort(axis=2)

    def shuffle_rows(self, out: np.ndarray) -> np.ndarray:
        """Fill ``out`` ``(R, n, d)`` with ``n`` independent uniform permutations of ``range(d)``
        per run, in O(d) per row (Fisher-Yates), and return it.

        Each run draws ``n * W(d)`` raw 64-bit words from its own generator (``W(30) = 4``) and
        spends each on several swaps (batched multiply-shift, see
        :func:`mawdo.optimizers.kernels.shuffle_from_words`). Every permutation has probability
        ``1/d!`` up to a relative bias below ``2**-32``.
        Replaces :meth:`permutations` (``argsort`` of ``n d`` uniform keys, O(d log d)) in the
        optimizers; the two give different streams.

        Parameters
        ----------
        out : numpy.ndarray
            Integer array ``(R, n, d)`` (int16 is enough for ``d < 32768``), overwritten.
        """
        from mawdo.util.shuffle import fisher_yates_batch, words_per_permutation

        if out.ndim != 3 or out.shape[0] != self.runs:
            raise ValueError(f"out must have shape ({self.runs}, n, d); got {out.shape}")
        n, d = out.shape[1:]
        words = self.raw_words(np.empty((self.runs, n * words_per_permutation(d)), np.uint64))
        fisher_yates_batch(words, out)
        return out

    def raw_words(self, out: np.ndarray) -> np.ndarray:
        """Fill each run's row of ``out`` ``(R, k)`` uint64 with raw 64-bit words of its generator.

        The optimizers' kernels turn them into permutations (see :meth:`shuffle_rows`, which
        consumes the same words in the same order and gives the same permutations).
        """
        if out.ndim != 2 or out.shape[0] != self.runs or out.dtype != np.uint64:
            raise ValueError(f"out must be uint64 of shape ({self.runs}, k); got {out.shape}")
        for g, w in zip(self.generators, out, strict=True):
            w[:] = g.bit_generator.random_raw(w.size)
        return out


def keyed_seed_sequence(seed, *key: int) -> np.random.SeedSequence:
    """The seed sequence at spawn key ``key`` below the master ``seed``.

    ``keyed_seed_sequence(s, k)`` is run ``k``'s sequence (:func:`run_seed_sequences`); longer
    keys name deeper descendants, e.g. ``(family, index, attempt)`` for a generated scene, so an
    item's stream depends only on its key, never on how many items were drawn or in which order.

    Parameters
    ----------
    seed : int or numpy.random.SeedSequence
        Master seed (an int >= 0).
    *key : int
        Spawn key below the master, each >= 0.
    """
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    if any(not isinstance(k, int | np.integer) or k < 0 for k in key):
        raise ValueError(f"spawn key entries must be integers >= 0, got {key!r}")
    return np.random.SeedSequence(
        ss.entropy, spawn_key=(*ss.spawn_key, *map(int, key)), pool_size=ss.pool_size
    )


# ---------------------------------------------------------------------- derived seeds
# Studies derive every per-run and per-problem seed here, so one module says how a seed follows
# from (master seed, names, indices).


def name_word(name: str) -> int:
    """A 32-bit word naming ``name`` in seed entropy: CRC-32 of its UTF-8 bytes.

    Stable across Python processes and versions (unlike ``hash``), so a seed derived from a
    function or scenario name is the same on every host.
    """
    import zlib

    return zlib.crc32(name.encode("utf-8"))


def seed_word(entropy) -> int:
    """One 32-bit seed drawn from ``SeedSequence(entropy)`` (``entropy``: int or list of ints).

    Used where a consumer needs a plain integer seed (a planning run, a shifted optimum) that
    depends on nothing but ``entropy``; distinct entropies give independent seeds.
    """
    return int(np.random.SeedSequence(entropy).generate_state(1, dtype=np.uint32)[0])


def replan_seed_sequences(seed, k: int) -> tuple[np.random.SeedSequence, np.random.SeedSequence]:
    """Seed sequences of (re)plan ``k`` of a planning run: the optimizer's and the planner's own.

    Child ``(k,)`` of the run's master seed drives the optimizer, ``(k, 1)`` the planner's draws
    (seed paths, perturbed copies), so replan ``k`` is the same whatever happened before it.
    """
    return keyed_seed_sequence(seed, k), keyed_seed_sequence(seed, k, 1)


def trajectory_seed_sequences(seed, k: int, j: int = 0):
    """Seed sequences of the trajectory refinement of timed route ``j`` (>= 0) at (re)plan
    ``k`` of a planning run: the optimizer's ``(k, 2, j)`` and its start draws' ``(k, 3, j)``
    below the run's master seed, apart from the replan's own (:func:`replan_seed_sequences`)."""
    return keyed_seed_sequence(seed, k, 2, j), keyed_seed_sequence(seed, k, 3, j)


#: The streams of a stepped episode, by name (spawn keys below the episode seed; the planner's
#: replans keep their own children ``(k,)``, ``(k, 1)`` of the per-step seed).
EPISODE_STREAMS = {"world": 1 << 20, "sensor": (1 << 20) + 1, "policy": (1 << 20) + 2}


def episode_seed_sequences(seed) -> dict[str, np.random.SeedSequence]:
    """Seed sequences of one stepped episode: ``world`` (the people's draws: new goals),
    ``sensor`` (noise and missed detections) and ``policy`` (the policy's own seed), so that a
    noisier sensor never changes where the people walk.

    Parameters
    ----------
    seed : int or numpy.random.SeedSequence
        The episode's seed (an int >= 0).
    """
    return {name: keyed_seed_sequence(seed, key) for name, key in EPISODE_STREAMS.items()}


def step_seed_sequence(seed, step: int) -> np.random.SeedSequence:
    """The seed of a policy's decision at ``step`` (>= 0) of an episode whose policy seed is
    ``seed``: each step's search is then the same whatever happened before it."""
    return keyed_seed_sequence(seed, int(step))
