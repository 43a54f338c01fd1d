"""artiplan.world."""
