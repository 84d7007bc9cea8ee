"""Plots, load maps and reports (matplotlib; pyvista imported lazily where used)."""
