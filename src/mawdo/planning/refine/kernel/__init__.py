"""Numba kernel: the path cost (paper Eqs. 24-28) of a whole population in one call.

The public wrapper is :class:`mawdo.planning.refine.cost.PathCost`; this module holds the compiled
geometry primitives and the population loop. All coordinates are pixels, times are time steps.

Hit test
--------
A segment hits an obstacle inflated by the robot radius iff its distance to the raw shape is
``<= thresh`` (exact inflation; touching counts as a hit):

* circle: distance from the centre to the segment ``<= R + r``;
* polygon (convex or not): the segment crosses or touches an edge, passes within ``r`` of an
  edge, or lies wholly inside (point-in-polygon of one endpoint; if no edge is within reach both
  endpoints are on the same side).

Moving obstacles (``spacetime`` mode) are tested in the obstacle's frame: over a time piece where
both the robot and the obstacle move with constant velocity, the robot's position relative to
the obstacle moves along a straight segment, which is tested against the shape at offset zero.

Speed
-----
The exact tests above decide every hit. Everything in front of them only skips work whose
outcome is certain, with room to spare for rounding (:data:`MARGIN`), so the counts are those of
the exact tests alone (which get the very numbers they would get without the filters):

* Candidates go in blocks of :data:`BLOCK`, their paths laid end to end, so that the passes
  over segments are long, branch-free loops that vectorise.
* Standing obstacles: one pass of distances to the bounding-circle centre. Within the *accept
  disc* (for a circle, the circle itself: the exact test; for a polygon, the largest disc about
  that centre inside it, grown by ``r``) a segment hits; beyond the bounding circle it misses;
  in between, the polygon test runs. The pass measures without a division (``cross^2 <= r^2
  |ab|^2`` where the foot of the perpendicular falls inside the segment, else the nearer end):
  a division made the loop several times slower. That distance only decides segments more than
  :data:`MARGIN` from both radii; a block with any segment closer is measured again exactly
  (:func:`_exact_distances`), so every verdict is the exact distance's. From
  :data:`INDEX_STANDING` standing obstacles on, each segment is measured only against those
  whose reach square its box meets (:mod:`.static_index`: a grid of each block's segments),
  with the same arithmetic per pair.
* Polygon test: separating axes (convex-hull edge normals and the segment's normal) reject. For
  a convex polygon they also accept (overlap on every axis means intersection) and otherwise
  prove the two disjoint, when the distance is attained at a polygon vertex or a segment end
  (vertex-segment and end-edge distances). Only what lies within :data:`MARGIN` of a decision
  boundary goes to the general test (edges, distances, point-in-polygon). For a convex polygon
  the tests of all a pass's segments run at once (:func:`classify_segments`, vectorised).
* Moving obstacles (``spacetime``): the obstacle's centre at each path time (few knots in the
  block's time span: each piece in turn, branch-free; many: interpolated in a grid of
  positions, filled as far as needed), then a *lens* test per segment: while the robot is on a
  segment the centre moves at most ``vmax`` from where it was at ``ta`` and will be at ``tb``,
  so it stays within ``sqrt(a^2 - d^2)`` (``a = vmax (tb - ta) / 2``, ``d`` half their
  distance) of the point that moves uniformly between the two; relative to that point the robot
  moves along a segment. Exact for a segment within one piece, up to the rounding room, which
  also covers measuring that segment's distance without a division
  (:func:`segment_reach_levels`; blocks with NaN or huge coordinates keep the division). A
  segment that comes within the accept radius less that deviation and the room is a sure hit,
  counted there; the other
  segments that pass it are walked piece by piece, as above; those spanning more than
  :data:`PIECES` pieces are first tested against the box of the obstacle's positions over them
  (sparse tables of knot boxes), and the pieces' relative segments are measured in one pass.
* Turning: ``|atan2|`` by a branch-free Cephes ``atan`` (within 2 ulp of the C library), one
  vectorised pass per block.

Modules (a package so that each job has its own file; names shared between them are public,
the package itself exports only the entry point): :mod:`.constants`, :mod:`.primitives`
(exact geometry tests), :mod:`.classify` (vectorised polygon verdicts, obstacle tables),
:mod:`.passes` (block layout, standing obstacles), :mod:`.moving` (moving obstacles, three
steps), :mod:`.index` (a space-time index of a block's segments, so that the moving pass runs on
those near each obstacle; used from :data:`.constants.INDEX_MOVERS` moving obstacles on),
:mod:`.static_index` (the same for the standing obstacles, from
:data:`.constants.INDEX_STANDING` on),
:mod:`.horizon` (the part of a block before a lookahead, which the moving obstacles are tested
against when one is given), :mod:`.population` (the entry point), :mod:`.threads` (the entry
point on chunks of rows at once, for ``PathCost(threads=k)``).
"""

from mawdo.planning.refine.kernel.constants import ZERO_LENGTH
from mawdo.planning.refine.kernel.population import population_cost, scratch_size

__all__ = ["ZERO_LENGTH", "population_cost", "scratch_size"]
