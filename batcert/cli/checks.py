"""``batcert inspect``, ``protocols``, ``validate`` and ``list``: looking at inputs."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from batcert import console
from batcert.cli.base import (
    CHECK_EXIT_CODES,
    _complete,
    _guard,
    main,
)
from batcert.errors import InputError


@main.command(epilog=CHECK_EXIT_CODES + """

\b
Examples:
  batcert inspect bats/aluminium-34.yaml
  batcert inspect ash-34 --pivot '6 in' --json
  batcert inspect protocols/balls/collegiate-baseball.yaml""")
@click.argument("file", shell_complete=_complete("bat"))
@click.option("--pivot", type=str, default=None, help="Pivot from the knob for the mass "
              "properties, e.g. '6 in' (default: the measured pivot, else 6 in).")
@click.option("--json", "as_json", is_flag=True, help="Print only JSON on stdout (SI units).")
@_guard
def inspect(file, pivot, as_json):
    """Show a bat's mass properties, COP and bending modes (or a ball's COR and contact time)."""
    from batcert.commands import inspect as inspecting
    from batcert.commands.inputs import detect_kind, load_bat_any
    from batcert.reports.inspect_view import ball_view, bat_view
    from batcert.specs.resolve import resolve
    from batcert.units import UnitError, parse_quantity
    if Path(file).is_file():
        path = file
    else:  # a shipped bat, else a shipped ball
        from batcert.specs.resolve import NotFound
        try:
            path = str(resolve("bat", file))
        except NotFound:
            try:
                path = str(resolve("ball", file))
            except NotFound:
                raise click.UsageError(f"{file!r} is neither a file nor a shipped bat or ball "
                                       "(batcert list bats, batcert list balls)") from None
    kind = detect_kind(path)
    if kind not in ("bat", "ball"):
        raise click.UsageError(f"{file} is a {kind} file; inspect takes a bat or a ball "
                               "(check it with `batcert validate`)")
    if kind == "ball":
        from batcert.commands.inputs import load_ball_lot
        info = inspecting.inspect_ball(load_ball_lot(path))
        console.print_results("inspect", [info]) if as_json else console.blocks(ball_view(info))
        return
    p = None
    if pivot is not None:
        try:
            p = parse_quantity(pivot, "length")
        except UnitError as exc:
            raise click.BadParameter(str(exc), param_hint="--pivot") from None
    info = inspecting.inspect_bat(load_bat_any(path).built, p)
    console.print_results("inspect", [info]) if as_json else console.blocks(bat_view(info))


@main.command(epilog=CHECK_EXIT_CODES + """

\b
Examples:
  batcert protocols
  batcert protocols --json | jq '.results[].id'""")
@click.option("--json", "as_json", is_flag=True, help="Print only JSON on stdout.")
def protocols(as_json):
    """List the shipped protocols."""
    from batcert.commands.listing import list_protocols
    from batcert.reports.format import metric_value
    from batcert.reports.table import Table
    items = list_protocols()
    if as_json:
        console.print_results("protocols", items)
        return
    console.table(Table(["id", "title", "metric", "impact rule", "limit", "conditions"],
                        [[p["id"], p["title"], p["metric"], p["rule"],
                          str(metric_value(p["limit"], p["metric"])),  # with its unit
                          ", ".join(p["conditions"])] for p in items]), "shipped protocols")


@main.command(epilog=CHECK_EXIT_CODES + """

\b
Examples:
  batcert validate bats/*.yaml protocols/*.yaml
  batcert validate my-bat.yaml ncaa-bbcor
  batcert validate examples/lab/synthetic-scatter.csv""")
@click.argument("files", nargs=-1, required=True, type=click.Path())
@click.option("--json", "as_json", is_flag=True, help="Print only JSON on stdout: each file "
              "with its kind and every problem (file, line, column, field, message).")
def validate(files, as_json):
    """Check spec files (bat, ball, protocol, league, study, lab session; paths or shipped
    names) and the files they name, and lab hits CSVs as `batcert reduce` reads them; report
    every problem of every file."""
    from batcert.commands.validate import shipped_path, validate_file
    from batcert.specs.resolve import NotFound
    failed = False
    report = []
    for f in files:
        entry: dict = {"file": f, "kind": None, "ok": True, "problems": []}
        try:
            entry["kind"] = validate_file(shipped_path(f))
            if not as_json:
                console.note_out(f"ok  {f} ({entry['kind']})")
        except InputError as exc:
            entry["ok"] = False
            entry["problems"] = [{"file": p.file, "line": p.line, "column": p.column,
                                  "field": p.field, "message": p.message}
                                 for p in exc.problems]
            if not as_json:
                console.input_error(exc.render())
        except NotFound as exc:
            entry["ok"] = False
            entry["problems"] = [{"file": f, "line": None, "column": None, "field": "",
                                  "message": str(exc)}]
            if not as_json:
                console.error(f"{f}: {exc}")
        failed = failed or not entry["ok"]
        report.append(entry)
    if as_json:
        console.print_results("validate", report)
    sys.exit(3 if failed else 0)



@main.command("list", epilog=CHECK_EXIT_CODES + """

\b
Examples:
  batcert list
  batcert list studies
  batcert list bats --json""")
@click.argument("kind", required=False,
                type=click.Choice(["bats", "balls", "protocols", "leagues", "studies",
                                  "batters"]))
@click.option("--json", "as_json", is_flag=True, help="Print only JSON on stdout.")
def list_(kind, as_json):
    """List the shipped bats, balls, protocols, leagues and studies (or one KIND of them):
    the names that every command accepts in place of a file path."""
    from batcert.commands.listing import LIST_KINDS, list_shipped
    from batcert.reports.table import Table
    kinds = [kind] if kind else list(LIST_KINDS)
    data = {k: list_shipped(k) for k in kinds}
    if as_json:
        console.print_results("list", [{"kind": k, "entries": v} for k, v in data.items()])
        return
    for k, items in data.items():
        console.table(Table(["name", "title", "file"],
                            [[i["name"], i["title"], i["path"]] for i in items]), k)
