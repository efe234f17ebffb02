"""A sweep's journal (:mod:`batcert.sweeps.execute` appends each finished chunk to it): what
``--resume`` continues from. A row is stored as JSON, which round-trips every float exactly, so a
resumed sweep gives the same numbers."""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import dataclass, field
from pathlib import Path

from batcert.errors import OutputError, UsageProblem
from batcert.sweeps.sweep import Chunk, Plan, Row, chunk_size, whole_row

JOURNAL = "the sweep's journal"  # what OutputError says cannot be written


class JournalRefused(UsageProblem):
    """A journal that cannot prove which sweep its rows belong to (another sweep's, or damaged
    anywhere but a last line cut short): refused, never read in part."""


@dataclass
class Journal:
    """A sweep's finished chunks on disk: a header line (the sweep's key and timestamp), then
    one JSON line per finished chunk, each carrying the sweep's key (so that every row proves
    which sweep it belongs to) and flushed and synced as it is written. Only a last line cut
    short by an interruption is passed over on resuming; anything else that is not a line of
    this sweep refuses the whole journal (:class:`JournalRefused`)."""

    path: Path
    key: str
    created: str
    lines: dict[int, int] = field(default_factory=dict)  # each chunk's line, as loaded

    def load(self) -> dict[int, list[Row]]:
        """The chunks already finished, by index (module notes)."""
        try:
            text = self.path.read_text(encoding="utf-8")
        except FileNotFoundError:
            return {}
        except UnicodeDecodeError:
            raise self._refused(None, "it is not a text file") from None
        except OSError as exc:
            raise OutputError(self.path, exc.strerror or str(exc), JOURNAL) from None
        lines = text.splitlines()
        cut_short = bool(text) and not text.endswith("\n")
        done: dict[int, list[Row]] = {}
        for k, line in enumerate(lines):
            try:
                entry = json.loads(line, parse_constant=_no_constant)
            # not JSON, a NaN/Infinity batcert never writes, or nested past Python's stack
            except (ValueError, RecursionError):
                if k == len(lines) - 1 and cut_short and k > 0:
                    continue  # the chunk being written when the sweep was stopped
                raise self._refused(k + 1, "the line is damaged") from None
            if not isinstance(entry, dict) or entry.get("key") != self.key:
                raise self._refused(k + 1, "the line is not of this sweep (other inputs, "
                                    "values, engine or batcert version)" if k else
                                    "it holds a sweep with other inputs, values, engine or "
                                    "batcert version")
            if k == 0:
                if not isinstance(entry.get("created"), str):
                    raise self._refused(1, "the header has no creation time")
                self.created = entry["created"]
                continue
            chunk, rows = entry.get("chunk"), entry.get("rows")
            if (not isinstance(chunk, int) or isinstance(chunk, bool) or chunk < 0
                    or not isinstance(rows, list) or not all(isinstance(r, dict) for r in rows)):
                raise self._refused(k + 1, "the line is not a finished chunk")
            if chunk in done and done[chunk] != rows:
                raise self._refused(k + 1, f"chunk {chunk} is recorded twice, differently")
            done[chunk] = rows
            self.lines.setdefault(chunk, k + 1)
        return done

    def check(self, done: dict[int, list[Row]], chunks: list[Chunk]) -> None:
        """:class:`JournalRefused` at a chunk of ``done`` (:meth:`load`) that does not hold the
        whole rows of its variants in ``chunks`` (a short chunk, a row without its fields: a
        line edited or damaged inside its JSON), or that the sweep does not have."""
        conditions = tuple(c.name for c in chunks[0].base.protocol.conditions) if chunks else ()
        for k, rows in sorted(done.items()):
            if k >= len(chunks):
                raise self._refused(self.lines.get(k), f"the sweep has no chunk {k}")
            want = [i for i, _ in chunks[k].points]
            if len(rows) != len(want) or not all(
                    whole_row(r, i, conditions) for r, i in zip(rows, want, strict=True)):
                raise self._refused(self.lines.get(k), f"the line does not hold the whole "
                                    f"rows of chunk {k} ({len(want)} variants)")

    def _refused(self, line: int | None, why: str) -> JournalRefused:
        where = f"{self.path}" + (f", line {line}" if line else "")
        return JournalRefused(f"{where}: {why}; the journal is not used. Remove it, or run "
                              "without --resume to start this sweep afresh")

    def start(self, done: dict[int, list[Row]]) -> None:
        """Write the header and the chunks kept (a fresh journal when ``done`` is empty) as a
        new file put in place whole: whatever was at the path (a link to another file, an old
        journal) is replaced, never written through."""
        lines = [json.dumps({"key": self.key, "created": self.created})]
        lines += [self._line(k, rows) for k, rows in sorted(done.items())]
        tmp = self.path.with_name(f".{self.path.name}.{os.getpid()}.tmp")
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            # a stale file of a crashed run with this process id is overwritten, a link refused
            self._write_to(tmp, os.O_CREAT | os.O_TRUNC | os.O_NOFOLLOW, "\n".join(lines) + "\n")
            os.replace(tmp, self.path)
        except OSError as exc:
            tmp.unlink(missing_ok=True)
            raise OutputError(self.path, exc.strerror or str(exc), JOURNAL) from None

    def add(self, chunk: int, rows: list[Row]) -> None:
        """Append a finished chunk, never through a link. A journal removed meanwhile (the same
        sweep run into the same folder at once finished first) is made anew: this run's
        journal then lacks its header, so a resume refuses it rather than trust it."""
        try:
            self._write_to(self.path, os.O_APPEND | os.O_CREAT | os.O_NOFOLLOW,
                           self._line(chunk, rows) + "\n")
        except OSError as exc:
            raise OutputError(self.path, exc.strerror or str(exc), JOURNAL) from None

    def discard(self) -> None:
        """Remove the journal (a sweep that could not start leaves nothing)."""
        self.path.unlink(missing_ok=True)

    def _line(self, chunk: int, rows: list[Row]) -> str:
        return json.dumps({"key": self.key, "chunk": chunk, "rows": rows}, allow_nan=False)

    @staticmethod
    def _write_to(path: Path, flags: int, text: str) -> None:
        """Write ``text`` and sync it (``flags``: how the file is opened, write-only)."""
        fd = os.open(path, os.O_WRONLY | flags, 0o644)
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())


def _no_constant(name: str) -> None:
    raise ValueError(f"{name} in a journal")


def sweep_key(plan: Plan) -> str:
    """What makes two sweeps the same: the input files, the varied values, the engine and
    the batcert version."""
    from batcert.version import __version__
    b, p = plan.base.bat, plan.base.protocol
    data = [b.sha256, p.sha256, plan.ball.sha256, plan.engine, __version__,
            [[a.name, list(a.values)] for a in plan.axes], chunk_size(len(plan.points))]
    return hashlib.sha256(json.dumps(data).encode()).hexdigest()
