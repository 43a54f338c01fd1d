"""artiplan.search."""
