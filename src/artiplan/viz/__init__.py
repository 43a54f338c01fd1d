"""artiplan.viz."""
