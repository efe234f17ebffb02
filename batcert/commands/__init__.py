"""What the CLI's commands do, without the CLI: one module per use case (run, inspect, validate,
listing, compare, league), all sharing :mod:`batcert.commands.inputs`. Everything here returns
result objects or plain data; :mod:`batcert.cli` only parses options and hands results to
:mod:`batcert.console` and the report writers."""
