"""How an engine's jobs are cut and joined: batches flattened, jobs cut into passes of bounded
size (memory, cache) and the pieces' outcomes joined again, batches of one bat concatenated.
Speed machinery only: an outcome never depends on how its job was cut.
"""

from __future__ import annotations

import numpy as np

from batcert.engines.base import ImpactBatch, ImpactOutcome


def flat(batch: ImpactBatch) -> ImpactBatch:
    """``batch`` with its arrays flattened to one axis of impacts."""
    if batch.impact_location.ndim == 1:
        return batch
    return ImpactBatch(*(np.ravel(a) for a in (batch.impact_location, batch.pitch_speed,
                                               batch.bat_angular_speed)))


def rows(batch: ImpactBatch, a: int, b: int) -> ImpactBatch:
    """The impacts ``a .. b`` of ``batch``."""
    return ImpactBatch(batch.impact_location[a:b], batch.pitch_speed[a:b],
                       batch.bat_angular_speed[a:b])


def passes(sizes: list[int], limit: int) -> list[list[tuple[int, int, int]]]:
    """The jobs' rows as pieces ``(job, start, stop)`` in passes of at most ``limit`` rows, in
    order: a job of more rows is cut, smaller jobs share a pass."""
    out: list[list[tuple[int, int, int]]] = [[]]
    filled = 0
    for i, n in enumerate(sizes):
        for a in range(0, max(n, 1), limit):
            b = min(a + limit, n)
            if out[-1] and filled + b - a > limit:
                out.append([])
                filled = 0
            out[-1].append((i, a, b))
            filled += b - a
    return out


def joined(parts: list[ImpactOutcome]) -> ImpactOutcome:
    """One outcome of the consecutive pieces of a job."""
    if len(parts) == 1:
        return parts[0]

    def cat(arrays):
        return None if arrays[0] is None else np.concatenate(arrays)
    fields = ("exit_speed", "bat_angular_speed_after", "cor", "recoil_factor")
    return ImpactOutcome(**{f: cat([getattr(p, f) for p in parts]) for f in fields},
                         diagnostics={k: cat([p.diagnostics[k] for p in parts])
                                      for k in parts[0].diagnostics})


def concatenate(batches: list[ImpactBatch]) -> ImpactBatch:
    """One batch of the impacts of ``batches``, in order."""
    if len(batches) == 1:
        return batches[0]
    return ImpactBatch(*(np.concatenate([getattr(b, a) for b in batches]) for a in (
        "impact_location", "pitch_speed", "bat_angular_speed")))
