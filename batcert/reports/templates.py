"""The Jinja environment over the package's report templates (works from an installed wheel).

Compiling the templates costs about 50 ms, a fifth of a run's time, so their compiled form is
kept in the cache directory (:func:`batcert.cache.cache_dir`: ``$BATCERT_CACHE_DIR``, else
``$XDG_CACHE_HOME/batcert`` or ``~/.cache/batcert``) and reused while the template's source is
unchanged (Jinja's bytecode cache checks it). The cache is an optimisation only: a directory
that cannot be made, read or written is passed over in silence, and deleting it is always safe.
"""

from __future__ import annotations

from functools import lru_cache
from typing import TYPE_CHECKING

from batcert.cache import cache_dir

if TYPE_CHECKING:
    import jinja2


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

    where = cache_dir("templates")  # entries are keyed by their source's checksum
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
