"""Sub-commands of the ``artiplan`` CLI, one module each: ``add_arguments(p)`` and ``run(args)``."""


class FilePath(str):
    """A command-line path: a ``str`` that is ``os.PathLike``, so that the loader reads it as
    a file, never as PDDL text (``pathlib`` costs ``artiplan plan``'s start-up ~5 ms)."""

    __slots__ = ()

    def __fspath__(self) -> str:
        return str(self)
