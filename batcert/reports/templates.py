"""The Jinja environment over the package's report templates (works from an installed wheel).

Compiling the templates costs about 50 ms, a fifth of a run's time, so their compiled form is
kept in a cache directory (:func:`cache_dir`: ``$BATCERT_CACHE_DIR``, else
``$XDG_CACHE_HOME/batcert`` or ``~/.cache/batcert``) and reused while the template's source is
unchanged (Jinja's bytecode cache checks it). The cache is an optimisation only: a directory
that cannot be made, read or written is passed over in silence, and deleting it is always safe.
"""

from __future__ import annotations

import os
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import jinja2


def cache_dir() -> Path | None:
    """Where compiled templates are kept (made if missing), or None where that cannot be."""
    root = os.environ.get("BATCERT_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"),
        "batcert")
    path = Path(root) / "templates"  # entries are keyed by their source's checksum
    try:
        path.mkdir(parents=True, exist_ok=True, mode=0o700)
    except OSError:
        return None
    return path if os.access(path, os.W_OK | os.X_OK) else None


def _bytecode_cache():
    import jinja2

    class QuietCache(jinja2.FileSystemBytecodeCache):
        """A bytecode cache whose failures (a full disk, a vanished directory) only cost the
        compile it would have saved."""

        def load_bytecode(self, bucket) -> None:
            try:
                super().load_bytecode(bucket)
            except (OSError, EOFError, ValueError):
                bucket.reset()

        def dump_bytecode(self, bucket) -> None:
            try:
                super().dump_bytecode(bucket)
            except OSError:
                pass

    where = cache_dir()
    return None if where is None else QuietCache(str(where))


@lru_cache(maxsize=1)
def environment() -> jinja2.Environment:
    import jinja2

    return jinja2.Environment(
        loader=jinja2.PackageLoader("batcert.reports", "templates"),
        autoescape=jinja2.select_autoescape(enabled_extensions=("html.j2",), default=False,
                                            default_for_string=False),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        bytecode_cache=_bytecode_cache(),
    )


def render_template(name: str, view: dict, filters: dict) -> str:
    env = environment().overlay()
    env.filters.update(filters)
    return env.get_template(name).render(**view)
