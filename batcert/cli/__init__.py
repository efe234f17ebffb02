"""The batcert command line: a thin click layer over the library (:mod:`batcert.api`), the
commands (:mod:`batcert.commands`), the console and the reports. :func:`main` is the ``batcert``
group (:mod:`batcert.cli.base`); each command lives in a module of its own, imported here to
register it."""

from batcert.cli import (  # noqa: F401
    cache_cmd,
    checks,
    compare_cmd,
    field_cmd,
    reduce_cmd,
    run_cmd,
    sweep_cmd,
)
from batcert.cli.base import _exit_now, _use_cache, entry, main

__all__ = ["_exit_now", "_use_cache", "entry", "main"]
