"""``python -m batcert``: the same command line as the ``batcert`` script."""

from batcert.cli import main

main(prog_name="batcert")
