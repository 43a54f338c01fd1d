"""artiplan.backends."""
