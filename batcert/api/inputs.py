"""How the library's functions read their arguments: a bat or protocol given by name, path or
loaded object (an argument in the other's place said to be swapped), lists of names, the
engine, flags and texts, each checked as the command line checks it (:mod:`batcert.arguments`)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from batcert import arguments as args

if TYPE_CHECKING:
    from batcert.commands.inputs import LoadedBat, ProtocolInputs
def _loaded_types():
    from batcert.commands.inputs import LoadedBat, ProtocolInputs
    return LoadedBat, ProtocolInputs


def loaded_bat(bat) -> LoadedBat:
    from batcert.commands.inputs import LoadedBat, load_bat_any
    return _loaded(bat, "bat", "protocol", LoadedBat, load_bat_any)


def loaded_protocol(protocol) -> ProtocolInputs:
    from batcert.commands.inputs import ProtocolInputs, load_protocol_any
    return _loaded(protocol, "protocol", "bat", ProtocolInputs, load_protocol_any)


def _loaded(value, kind: str, other: str, loaded: type, load):
    """A loaded ``kind`` (bat or protocol) from a name, a path or what ``load_<kind>`` returned
    (an instance of ``loaded``); a shipped ``other`` given in its place (arguments swapped) is
    said to be one."""
    from batcert.specs.resolve import NotFound
    read = args.name_or_path(kind, value, kind, loaded)
    if not isinstance(read, str):
        return read
    try:
        return load(read)
    except NotFound:
        _swapped(kind, read, kind, other)
        raise


def _swapped(name: str, value: str, kind: str, other: str) -> None:
    """An :class:`~batcert.arguments.ArgumentError` when ``value``, not a ``kind``, is a
    shipped ``other`` (the arguments given in the wrong order)."""
    from batcert.specs.resolve import shipped_names
    if value in shipped_names(other):
        raise args.ArgumentError(name, f"{value!r} is a shipped {other}, not a {kind}: are the "
                                 "arguments in the wrong order?")


def named(values, name: str, kind: str, at_least: int = 0) -> list[str]:
    """Names or paths for the commands that take them: a loaded bat stands for its file."""
    loaded = _loaded_types()[0]
    if isinstance(values, loaded):
        values = [values]
    if isinstance(values, Sequence) and not isinstance(values, str):
        values = [str(v.path) if isinstance(v, loaded) else v for v in values]
    return args.names_or_paths(name, values, kind, at_least)


def one_named(value, name: str, kind: str) -> str:
    loaded = _loaded_types()[0]
    return str(value.path) if isinstance(value, loaded) else args.name_or_path(name, value, kind)


def engine_name(engine) -> str:
    from batcert.engines import available_engines
    return args.choice("engine", engine, available_engines())


def flag(name: str, value) -> bool:
    if not isinstance(value, bool):
        raise args.ArgumentError(name, f"expected True or False, got {value!r}")
    return value


def texts(name: str, values) -> list[str]:
    """A list of strings (``vary``); a single string is taken as a list of one."""
    items = [values] if isinstance(values, str) else values
    if not isinstance(items, Sequence) or not all(isinstance(v, str) for v in items):
        raise args.ArgumentError(name, f"expected a list of 'PARAM=START:STOP:N' strings, got "
                                 f"{values!r}"[:300])
    return list(items)


def uncertainty_options(uncertainty, seed, method, bound
                        ) -> tuple[int, int | None, str, float | None] | None:
    """``run``'s Monte Carlo options checked: the draws, the seed, the method and the bound, or
    None without ``uncertainty`` (then the others must not be given either)."""
    given = {"seed": seed, "uncertainty_method": method, "uncertainty_bound": bound}
    for name, value in given.items():
        if value is not None and uncertainty is None:
            raise args.ArgumentError(name, "needs uncertainty=N (the Monte Carlo's draws)")
    if uncertainty is None:
        return None
    return (args.whole("uncertainty", uncertainty),
            None if seed is None else args.whole("seed", seed),
            args.choice("uncertainty_method", "surrogate" if method is None else method,
                        args.UNCERTAINTY_METHODS),
            None if bound is None else args.positive("uncertainty_bound", bound))
