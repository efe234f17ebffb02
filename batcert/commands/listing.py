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
