"""artiplan.execution."""
