"""artiplan.semantics."""
