"""The error every command raises when it cannot run as asked (exit status 2)."""


class UsageError(Exception):
    """The command cannot run as asked: a bad option, an unknown name, an unreadable input."""
