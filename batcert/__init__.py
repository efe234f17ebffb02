"""batcert: bat certification from YAML specs with a reduced-order ball-bat impact engine.

As a library (docs/api.md)::

    import batcert
    result = batcert.run("ash-34", "ncaa-bbcor", engine="rigid")
    result.value, result.verdict

The functions of :mod:`batcert.api` are available here; they are imported on first use, so that
``import batcert`` (and every command line start-up) stays light. Every error they raise for
something the caller can fix is a :class:`BatcertError`: :class:`InputError` (a file's
problems, with file and line), :class:`NotFound` (an unknown name), :class:`UsageProblem` (an
argument or request that cannot mean anything).
"""

from batcert.errors import BatcertError, InputError, UsageProblem
from batcert.version import __version__

__all__ = ["BatcertError", "InputError", "NotFound", "UsageProblem", "__version__", "compare",
           "design", "field", "league", "load_bat", "load_protocol", "reduce", "run", "sweep",
           "use_cache"]


def __getattr__(name: str):
    if name == "NotFound":
        from batcert.specs.resolve import NotFound
        return NotFound
    if name in __all__:
        from batcert import api
        return getattr(api, name)
    raise AttributeError(f"module 'batcert' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted([*globals(), *__all__])
