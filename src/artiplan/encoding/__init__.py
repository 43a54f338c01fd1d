"""artiplan.encoding."""
