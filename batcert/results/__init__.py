"""Result types: plain dataclasses in SI units, one module per kind of result, one
serialisation (:mod:`batcert.results.serialise`). Reports and the terminal only read them."""
