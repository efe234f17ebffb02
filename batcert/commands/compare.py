"""``batcert compare``: every bat under every protocol (a study's, then any extra ones), side by
side. Every input is loaded before anything runs."""

from __future__ import annotations

from batcert.analysis.compare import bat_labels, compare
from batcert.commands.inputs import (
    LoadedBat,
    ProtocolInputs,
    load_bats,
    load_protocol_any,
    load_study_any,
    protocol_inputs,
    same_file,
)
from batcert.engines import get_engine
from batcert.errors import UsageProblem
from batcert.results.compare import BatEntry, ComparisonResult
from batcert.results.serialise import utc_now
from batcert.runner.runner import run_protocols
from batcert.specs.resolve import display_path, resolve
from batcert.specs.study import StudySpec


def _protocols(spec: StudySpec | None, extra: list[str]) -> list[ProtocolInputs]:
    out = [protocol_inputs(p) for p in spec.protocols] if spec else []
    out += [load_protocol_any(p) for p in extra]
    if not out:
        raise UsageProblem("give at least one --protocol, or a --study")
    ids = [p.protocol.id for p in out]
    dup = sorted({i for i in ids if ids.count(i) > 1})
    if dup:
        raise UsageProblem(f"protocol {', '.join(map(repr, dup))} given twice")
    return out


def _bats(bats: list[str], spec: StudySpec | None, reference: str | None
          ) -> tuple[list[LoadedBat], int]:
    """The bats to compare and the index of the reference bat (added when not among them)."""
    if bats:
        loaded = load_bats(bats)
    elif spec and spec.bats:
        loaded = load_bats([str(p) for p in spec.bats])
    else:
        raise UsageProblem("give the bats to compare (or a study that names default bats)")
    ref = 0
    if reference is not None:
        ref_path = resolve("bat", reference)
        ref = next((i for i, b in enumerate(loaded) if same_file(b.path, ref_path)), -1)
        if ref < 0:
            loaded = load_bats([reference]) + loaded
            ref = 0
    if len(loaded) < 2:
        raise UsageProblem("a comparison needs at least two bats")
    return loaded, ref


def run_comparison(bats: list[str], protocols: list[str], study: str | None = None,
                   reference: str | None = None, engine: str = "flexible",
                   on_step=None, figures: bool = False) -> ComparisonResult:
    """Run every bat under every protocol and compare them (Smith 2001 Eq. 6); with
    ``figures``, also a study's figures (sweeps of every bat: about 2 s warm for the 2001
    study's two, against 0.3 s for the rest; without them the claims that read a figure are
    not tested, and say so)."""
    spec = load_study_any(study) if study else None
    proto_inputs = _protocols(spec, protocols)
    loaded, ref = _bats(bats, spec, reference)
    eng = get_engine(engine)
    created = utc_now()
    labels = bat_labels([b.built.spec.name for b in loaded], [str(b.path) for b in loaded])
    planned = _figure_plans(spec, loaded, labels, ref, proto_inputs, engine, created) \
        if spec and figures else []  # checked before anything runs
    flat = run_protocols([(b.built, p.protocol, p.ball) for b in loaded for p in proto_inputs],
                         eng, created, on_step)  # every bat and protocol solved together
    runs = [flat[i * len(proto_inputs):(i + 1) * len(proto_inputs)] for i in range(len(loaded))]
    entries = [BatEntry(lab, b.built.spec.name, display_path(b.path), b.built.spec.sha256,
                        b.built.model.length, b.built.model.construction,
                        b.built.model.material.name) for lab, b in zip(labels, loaded, strict=True)]
    drawn = []
    if planned:  # a study's figures: sweeps (their modules cost 30 ms to import otherwise)
        from batcert.sweeps.study_figures import study_figure

        drawn = [study_figure(f, f.protocol, plans) for f, plans in planned]
    return compare(runs, ref, bats=entries, title=spec.title if spec else "", figures=drawn,
                   created=created,
                   study=spec.id if spec else None,
                   study_reference=spec.reference if spec else "",
                   study_notes=(spec.notes or "") if spec else "",
                   claims=spec.claims if spec else ())


def _figure_plans(spec: StudySpec, loaded: list[LoadedBat], labels: list[str], ref: int,
                  proto_inputs: list[ProtocolInputs], engine: str, created: str) -> list:
    """Each study figure with the planned sweeps of its bats (each a protocol condition)."""
    from batcert.sweeps.study_figures import figure_plans

    by_id = {p.protocol.id: p for p in proto_inputs}
    out = []
    for f in spec.figures:
        bats = [(lab, b.built) for i, (lab, b) in enumerate(zip(labels, loaded, strict=True))
                if f.bats == "all" or i != ref]
        p = by_id[f.protocol]
        out.append((f, figure_plans(f, bats, p.protocol, p.ball, engine, created)))
    return out
