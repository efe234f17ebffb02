"""Write the docs' tables that restate a registry, so that they cannot drift from the code.

    python scripts/gen_doc_tables.py          # rewrite the generated tables in docs/
    python scripts/gen_doc_tables.py --check  # exit 1 if one is out of date

A generated table sits between ``<!-- generated: NAME (scripts/gen_doc_tables.py) -->`` and
``<!-- end generated: NAME -->`` in its document; the rest of the document is written by hand.
Each NAME's rows come from its registry (:data:`TABLES`). tests/sweeps/test_doc_tables.py
checks that the committed documents are current (docs/inputs.md, the input files' fields, has its
own generator, scripts/gen_input_docs.py).
"""

from __future__ import annotations

import re
import sys
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def sweep_parameters() -> str:
    """The parameters a sweep or a design can vary (batcert.sweeps.variants.PARAMETERS)."""
    from batcert.sweeps.variants import PARAMETERS
    rows = ["| name | unit | changes | what a value does |", "|---|---|---|---|"]
    for p in PARAMETERS.values():
        unit = p.dimension.replace("_", " ") if p.dimension else "number"
        unit += f" [{p.unit}]" if p.unit else ""
        rows.append(f"| `{p.name}` | {unit} | {p.changes} | {' '.join(p.doc.split())} |")
    return "\n".join(rows) + "\n"


# name -> (document, the table's rows)
TABLES: dict[str, tuple[str, Callable[[], str]]] = {
    "sweep-parameters": ("docs/sweeps.md", sweep_parameters),
}


def _region(name: str) -> re.Pattern[str]:
    return re.compile(rf"(<!-- generated: {re.escape(name)} [^\n]*-->\n)(.*?)"
                      rf"(<!-- end generated: {re.escape(name)} -->)", re.S)


def generate(name: str, text: str) -> str:
    """``text`` (the document) with the table ``name`` written anew; ValueError if the
    document has no region for it."""
    pattern = _region(name)
    if not pattern.search(text):
        raise ValueError(f"{TABLES[name][0]} has no region `<!-- generated: {name} ... -->`")
    rows = TABLES[name][1]()
    return pattern.sub(lambda m: m.group(1) + rows + m.group(3), text, count=1)


def main(argv: list[str]) -> int:
    check = "--check" in argv
    stale = []
    for name, (doc, _) in TABLES.items():
        path = ROOT / doc
        text = path.read_text(encoding="utf-8")
        new = generate(name, text)
        if new != text:
            stale.append(doc)
            if not check:
                path.write_text(new, encoding="utf-8")
    if check and stale:
        print(f"out of date: {', '.join(stale)} (run python scripts/gen_doc_tables.py)")
        return 1
    for doc in stale:
        print(f"wrote {doc}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
