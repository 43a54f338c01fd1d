"""artiplan.bench."""
