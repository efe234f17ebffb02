"""``batcert cache``: the cache directory's folder, size and bound, and clearing it (the logic
is :mod:`batcert.cache.folder`'s)."""

from __future__ import annotations

import sys

import click

from batcert import console
from batcert.cli.base import main

CACHE_EPILOG = """\b
Exit codes:
  0  shown, or cleared
  2  usage error
  3  the folder is not batcert's cache (no CACHEDIR.TAG of batcert's): nothing
     was deleted

\b
Examples:
  batcert cache
  batcert cache show --json
  BATCERT_CACHE_DIR=/tmp/bc batcert cache clear"""


@main.group(invoke_without_command=True, epilog=CACHE_EPILOG)
@click.pass_context
def cache(ctx):
    """Show batcert's cache directory ($BATCERT_CACHE_DIR, else ~/.cache/batcert): its folder,
    size, entries per kind and the bound on each kind (the least recently used entries go
    past it). Deleting the cache is always safe; the next runs are slower."""
    if ctx.invoked_subcommand is None:
        ctx.invoke(show)


def _size(n: int) -> str:
    return f"{n / 2**20:.1f} MiB" if n >= 2**20 else f"{n / 2**10:.1f} kiB"


@cache.command(epilog=CACHE_EPILOG)
@click.option("--json", "as_json", is_flag=True, help="Print only JSON on stdout (sizes in "
              "bytes).")
def show(as_json):
    """Show the cache directory: folder, size, entries per kind, the bound."""
    from dataclasses import asdict

    from batcert.cache.folder import survey
    from batcert.reports.table import Table
    s = survey()
    if as_json:
        console.print_results("cache", [{**asdict(s), "bytes": s.bytes, "entries": s.entries}])
        return
    state = ("batcert's (CACHEDIR.TAG)" if s.batcerts else "not made yet" if not s.exists
             else "not batcert's: not used, not cleared")
    console.kv_table("cache directory", [
        ("folder", s.root), ("state", state),
        ("size", f"{_size(s.bytes)} in {s.entries} entries"),
        ("bound", f"{_size(s.kind_limit)} per kind, least recently used out first")])
    if s.kinds:
        console.table(Table(["kind", "entries", "size", "bound", "other files"],
                            [[k.kind, str(k.entries), _size(k.bytes),
                              _size(k.limit) if k.limit else "not trimmed", str(k.other_files)]
                             for k in s.kinds], [False, True, True, True, True]))


@cache.command(epilog=CACHE_EPILOG)
def clear():
    """Delete batcert's own entries from the cache directory, and nothing else: only in a
    folder that holds batcert's CACHEDIR.TAG, only the files batcert names, never a link."""
    from batcert.cache.folder import cache_root
    from batcert.cache.folder import clear as clear_cache
    try:
        removed, freed = clear_cache()
    except ValueError as exc:
        console.error(str(exc))
        sys.exit(3)
    console.note_out(f"removed {removed} entries ({_size(freed)}) from {cache_root()}")
