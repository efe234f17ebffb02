"""``python -m batcert``: the same command line as the ``batcert`` script."""

from batcert.cli import entry

entry()
