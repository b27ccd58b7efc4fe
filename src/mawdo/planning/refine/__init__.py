"""Refinement: the paper's path cost and its compiled kernel, seed candidates, polish."""
