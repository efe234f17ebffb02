"""Whether the library keeps its costly intermediate results in batcert's cache directory."""

from __future__ import annotations

_chosen = [False]  # whether use_cache was called (else the first call turns the cache on)


def use_cache(on: bool = True) -> None:
    """Keep (``on``) or stop keeping costly intermediate results in batcert's cache directory
    as well as in the process.

    Parameters
    ----------
    on : bool
        Keep them in ``$BATCERT_CACHE_DIR``, else ``~/.cache/batcert`` (:mod:`batcert.cache`),
        besides the active :class:`batcert.workspace.Workspace`. Deleting the directory is
        always safe.
    """
    from batcert import workspace
    _chosen[0] = True
    if not on:
        workspace.current().attach(None)
        return
    from batcert.cache import disk_stores
    workspace.current().attach(disk_stores())


def ready() -> None:
    if not _chosen[0]:
        use_cache()
