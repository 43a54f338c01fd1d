"""artiplan.pddl."""
