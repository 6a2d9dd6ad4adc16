"""`throng plot` (scripts/plot.py): the geometry of the measurement lines and areas, and the figures."""
