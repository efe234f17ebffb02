"""``python -m batcert.cli``: the same command line as the ``batcert`` script."""

from batcert.cli import entry

entry()
