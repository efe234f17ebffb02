"""``python -m batcert``: the same command line as the ``batcert`` script."""

from batcert.launch import entry

entry()
