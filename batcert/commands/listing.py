"""``batcert protocols``: the shipped protocols, one line each."""

from __future__ import annotations

from batcert.specs.protocol import load_protocol
from batcert.specs.resolve import shipped_names


def list_protocols() -> list[dict]:
    out = []
    for path in shipped_names("protocol").values():
        p = load_protocol(path)
        out.append({"id": p.id, "title": p.title, "metric": p.metric,
                    "rule": p.impact_location.rule, "limit": p.limit.max if p.limit else None,
                    "conditions": [c.name for c in p.conditions], "path": str(path)})
    return out


LIST_KINDS = {"bats": "bat", "balls": "ball", "protocols": "protocol", "leagues": "league",
              "studies": "study", "batters": "batter"}


def list_shipped(kind: str) -> list[dict]:
    """The shipped files of one kind (``bats``, ``balls``, ``protocols``, ``leagues``,
    ``studies``, ``batters``): name, title and where it ships."""
    from batcert.specs.resolve import display_path
    from batcert.specs.yamlio import load_yaml
    out = []
    for name, path in shipped_names(LIST_KINDS[kind]).items():
        data = load_yaml(path)
        title = data.get("title") or data.get("name") or ""
        out.append({"name": name, "title": str(title), "path": display_path(path)})
    return out
