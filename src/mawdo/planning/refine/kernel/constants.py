"""Constants of the cost kernel: tolerances, block sizes and the Cephes atan coefficients."""

from __future__ import annotations

#: Segments shorter than this (pixels) have no direction and contribute no turning.
ZERO_LENGTH = 1e-9
# Separating-axis rejections only fire with this much room to spare (pixels), so that rounding
# can never reject a true hit; anything closer goes to the exact test.
SLACK = 1e-9
# Fast decisions keep this much room (pixels, and relative): rounding is below 1e-9 px for
# coordinates up to 1e7 px, so a fast decision is always the exact one.
MARGIN = 1e-6
# Candidates with a coordinate beyond this (pixels), or NaN, skip the fast accepts.
SANE = 1e7
# A segment spanning more of an obstacle's pieces than this is first tested against a box.
PIECES = 3
# Candidates per block (the loops over a block's segments vectorise).
BLOCK = 128
# A block's path times find their pieces by counting knots when it spans at most this many.
COUNT = 10
# Cells of the moving obstacles' position grids.
GRID_CELLS = 2048

# |atan2| (Cephes atan.c, double precision: peak relative error 1.9e-16)
P0 = -8.750608600031904122785e-1
P1 = -1.615753718733365076637e1
P2 = -7.500855792314704667340e1
P3 = -1.228866684490136173410e2
P4 = -6.485021904942025371773e1
Q0 = 2.485846490142306297962e1
Q1 = 1.650270098316988542046e2
Q2 = 4.328810604912902668951e2
Q3 = 4.853903996359136964868e2
Q4 = 1.945506571482613964425e2
MOREBITS = 6.123233995736765886130e-17
T3P8 = 2.41421356237309504880  # tan(3 pi / 8)
# Index of the moving pass: cell side (pixels), time slices of the robot's time to cross
# INDEX_SPAN cells, buckets at most (cells x slices), slices at most.
INDEX_CELL = 64.0
INDEX_SPAN = 2.0
INDEX_CELLS = 32768
INDEX_SLICES = 128
# The moving pass uses the index from this many moving obstacles on (with fewer, building it
# cost more than it saved: measured on the planner's calls, benchmarks/log/scaling.md).
INDEX_MOVERS = 500
# The indexed moving pass walks an obstacle's table of at most this many knots (else its grid).
WALK_KNOTS = 64
# The standing obstacles are measured through a grid of each block's segments
# (kernel.static_index) from this many on (at about 100 on a 1000 px map the two cost the same;
# with fewer, the branch-free pass over every segment costs less: measured on the planner's
# calls, benchmarks/log/scaling.md).
INDEX_STANDING = 128
