"""Exact guidance: visibility graph, oracle, homotopy-distinct routes, safe-interval search."""
