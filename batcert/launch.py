"""The ``batcert`` command's first lines: Ctrl-C means exit 130 and one line, from the first
instant.

Loading the command line (click, rich, the commands) takes a tenth of a second or more; a Ctrl-C
in that window would print a Python traceback, and one while click parses the arguments would
print click's "Aborted!" with exit 1, which every script reads as "a verdict fails". Until the
command line is loaded, an interrupt ends the process at once (nothing has been written yet);
from then on it is a KeyboardInterrupt, which the commands clean up after
(:func:`batcert.cli.base.entry` maps it to exit 130).

This module imports nothing of batcert at load time, so that ``import batcert.launch`` is as
light as ``import batcert``.

The command also runs its linear algebra on one thread (:data:`ONE_THREAD`) unless the user set
the thread count: the engine's matrix products are small (pieces of about 1,300 impacts by at
most 112 columns), sweeps run in parallel over processes, and on a machine that is busy (or
with two workers on two cores) the multithreaded BLAS's threads wait for each other: a hollow
batch of 2,000 impacts took 3.5-4.3 times as long with the default threads as with one, on
this project's 2-core machine under load (docs/performance.md).
"""

from __future__ import annotations

import os
import signal

INTERRUPTED = 130
# BLAS thread counts the command sets to one where the environment does not give them (read by
# OpenBLAS, MKL and OpenMP when numpy loads: before any import of numpy)
ONE_THREAD = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
MESSAGE = b"error: interrupted\n"  # as batcert.console.error("interrupted") writes it


def _interrupted_while_loading(signum, frame) -> None:
    os.write(2, MESSAGE)
    os._exit(INTERRUPTED)


def _load_cli():
    """The command line's entry function (the costly import)."""
    from batcert.cli.base import entry
    return entry


def entry() -> None:
    """The installed ``batcert`` command and ``python -m batcert``. (``python -m batcert.cli``
    starts at :func:`batcert.cli.base.entry`, without this guard and the BLAS setting: the
    layer rule keeps the command line from importing this module.)"""
    previous = signal.signal(signal.SIGINT, _interrupted_while_loading)
    for name in ONE_THREAD:
        os.environ.setdefault(name, "1")
    run = _load_cli()
    signal.signal(signal.SIGINT, signal.default_int_handler if previous is None else previous)
    run()
