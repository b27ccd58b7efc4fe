"""Internal helpers shared across the package: argument checks (:mod:`~mawdo.util.validate`),
Ctrl-C told apart from errors (:mod:`~mawdo.util.interrupts`), the driver's blocks of runs
(:mod:`~mawdo.util.blocks`), and two compiled building blocks of the optimizer kernels
(:mod:`~mawdo.util.shuffle`, :mod:`~mawdo.util.stablesort`). Not public API: names may change."""
