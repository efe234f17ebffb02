"""The vocabulary of a test method, as registries: the performance metrics and how conditions
are aggregated (:mod:`batcert.methods.metrics`) and the impact-location rules
(:mod:`batcert.methods.rules`). Each entry holds a name (as written in protocol files and JSON),
its display words, its documentation and its function; protocol files take their names from
here, the runner applies the functions and the reports show the words."""
