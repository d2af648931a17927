"""Subcommands of the ``ballpass`` command, one module each (see :mod:`ballpass.cli`)."""
