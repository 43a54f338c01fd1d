"""Sub-commands of the ``artiplan`` CLI, one module each: ``add_arguments(p)`` and ``run(args)``."""
