# ruff: noqa: E501  (a data file: one case per line reads best)
"""Cases of the corpus for the newer surfaces: lab hits and sessions (9-lab), sweep and design
ranges (10-sweep), workers, schedulers and --resume (11-scale), user text that could act on a
reader of a report or a terminal (12-inject), where the outputs go (13-output) and
``run --uncertainty`` (14-monte-carlo). corpus.py builds them with its own cases; the cases that
need more than files (a FIFO, a full disk, two writers at once, a journal) are in
test_corpus_output.py.

Every case is cheap: the rigid engine, ``--no-reports`` where the reports are not the point,
two or three variants per sweep. A case that finds a defect not fixed yet carries ``known``
(what is wrong), and the test expects it to fail until the marker is removed.
"""

from __future__ import annotations

import json

import corpus
from corpus import BALL, BBCOR, HOLLOW, LEAGUE, SOLID, STUDY, Case, sub

RIGID = ["--engine", "rigid"]


def case(cid: str, category: str, desc: str, kind: str, content: str | bytes = "", *,
         expect: str = "either", files: dict | None = None, commands: list | None = None,
         main: str | None = None, known: str = "", links: dict | None = None) -> None:
    main = main or ("." if kind == "cmd" else f"{kind}.yaml")
    corpus.ALL.append(Case(cid, category, desc, kind, main, expect, content, files or {},
                           commands, known, links or {}))


def command(cid: str, category: str, argv: list[str], *, desc: str = "", expect: str = "either",
            files: dict | None = None, known: str = "", links: dict | None = None) -> None:
    """A case that is one command line (and the files it reads)."""
    case(cid, category, desc or "command: batcert " + " ".join(argv)[:200], "cmd",
         expect=expect, files=files, commands=[argv], known=known, links=links)


# ------------------------------------------------------------------------------------------
# 9. Lab hits and sessions
# ------------------------------------------------------------------------------------------
SESSION = """name: Lab session (surfaces)
bat: aluminium-34
ball: collegiate-baseball
pivot: 6 in
hits: hits.csv
"""
COLS = ["hit", "ball", "inbound_speed [m/s]", "rebound_speed [m/s]",
        "impact_location [in from tip]", "valid", "note"]
HEAD = ",".join(COLS) + "\n"


def rows(n: int = 6, row: str = "{n},B1,60.80,13.00,6,yes,") -> str:
    return "".join(row.format(n=i) + "\n" for i in range(1, n + 1))


HITS = HEAD + rows()
REDUCE = ["reduce", "{f}", "-p", "ncaa-bbcor", *RIGID, "--out", "{out}"]
BARE = ["reduce", "{d}/hits.csv", "--bat", "aluminium-34", "-p", "ncaa-bbcor", *RIGID,
        "--no-reports"]


def lab() -> None:
    c = "9-lab"

    def hits(cid, desc, text, expect="invalid", session=SESSION, bare=False, known="",
             files=None):
        cmds = [["validate", "{f}"], REDUCE] + ([BARE] if bare else [])
        case(cid, c, desc, "session", session, expect=expect, main="session.yaml",
             files={"hits.csv": text, **(files or {})}, commands=cmds, known=known)

    def session(cid, desc, text, expect="invalid", hits_text=HITS, known="", files=None,
                commands=None):
        case(cid, c, desc, "session", text, expect=expect, main="session.yaml",
             files={"hits.csv": hits_text, **(files or {})},
             commands=commands or [["validate", "{f}"], REDUCE], known=known)

    # line endings, encodings, blank lines and comments
    hits("lab9-crlf", "CRLF line endings", HITS.replace("\n", "\r\n").encode(), "valid", bare=True)
    hits("lab9-cr-only", "old-Mac CR line endings", HITS.replace("\n", "\r").encode(), "either", bare=True)
    hits("lab9-bom-crlf", "a BOM and CRLF line endings", ("\ufeff" + HITS).replace("\n", "\r\n").encode(), "either", bare=True)
    hits("lab9-utf16", "a UTF-16 file", HITS.encode("utf-16"), bare=True)
    hits("lab9-utf16-le-nobom", "UTF-16-LE without a BOM (NUL every other byte)", HITS.encode("utf-16-le"), bare=True)
    hits("lab9-bom-second-line", "a BOM at the start of the first hit", HEAD + "\ufeff" + rows())
    hits("lab9-latin1-note", "a Latin-1 note in a bare hits CSV", (HEAD + rows(5) + "6,B1,60.8,13,6,yes,caf\xe9\n").encode("latin-1"), bare=True)
    hits("lab9-nul-in-row", "a NUL byte inside a row", HEAD + rows(5) + "6,B1,60.8\x00,13,6,yes,\n")
    hits("lab9-trailing-blank", "blank lines after the hits", HITS + "\n\n   \n", "valid")
    hits("lab9-leading-comments", "comments and blank lines before the header", "# lab A\n\n# x\n" + HITS, "valid", bare=True)
    hits("lab9-comment-between", "a comment line between hits", HEAD + rows(3) + "# pause\n" + rows(6)[len(rows(3)):], "valid")
    hits("lab9-whitespace-only", "a file of spaces and newlines", "   \n\t\n  ", bare=True)
    hits("lab9-comments-only", "a file of comments only", "# a\n# b\n", bare=True)
    hits("lab9-header-twice", "the header repeated in the middle", HEAD + rows(3) + HEAD + rows(3))
    # the header: names, units
    hits("lab9-header-spaces", "spaces around the header names", " , ".join(COLS) + "\n" + rows(), "either")
    hits("lab9-header-upper", "header names in capitals", HEAD.upper() + rows())
    hits("lab9-header-trailing-comma", "a trailing comma on every line", HEAD.rstrip("\n") + ",\n" + rows(row="{n},B1,60.80,13.00,6,yes,,"))
    hits("lab9-unit-mph", "speeds in mph", HEAD.replace("[m/s]", "[mph]") + rows(row="{n},B1,136,29.08,6,yes,"), "valid")
    hits("lab9-unit-kmh", "speeds in km/h", HEAD.replace("[m/s]", "[km/h]") + rows(row="{n},B1,218.88,46.8,6,yes,"), "valid")
    hits("lab9-unit-spaces", "a unit with spaces inside its brackets ('[ m / s ]')", HEAD.replace("[m/s]", "[ m / s ]") + rows(), "either")
    hits("lab9-unit-empty", "empty unit brackets", HEAD.replace("inbound_speed [m/s]", "inbound_speed []") + rows())
    hits("lab9-unit-unclosed", "an unclosed unit bracket", HEAD.replace("inbound_speed [m/s]", "inbound_speed [m/s") + rows())
    hits("lab9-unit-two-brackets", "two bracket groups", HEAD.replace("inbound_speed [m/s]", "inbound_speed [m/s] [mph]") + rows())
    hits("lab9-unit-dimensionless", "a speed in percent", HEAD.replace("inbound_speed [m/s]", "inbound_speed [percent]") + rows())
    hits("lab9-unit-one", "a speed in '[1]'", HEAD.replace("inbound_speed [m/s]", "inbound_speed [1]") + rows())
    hits("lab9-unit-accel", "a speed in m/s^2", HEAD.replace("inbound_speed [m/s]", "inbound_speed [m/s^2]") + rows())
    hits("lab9-unit-offset", "a speed in degC", HEAD.replace("inbound_speed [m/s]", "inbound_speed [degC]") + rows())
    hits("lab9-unit-markup", "a unit that is console markup", HEAD.replace("inbound_speed [m/s]", "inbound_speed [[/]]") + rows())
    hits("lab9-speeds-no-unit", "speed columns without units", HEAD.replace(" [m/s]", "") + rows())
    hits("lab9-location-cm", "locations in cm from the tip", HEAD.replace("[in from tip]", "[cm from tip]") + rows(row="{n},B1,60.80,13.00,15.24,yes,"), "valid")
    hits("lab9-location-from-knob", "a header 'from knob' with location_from tip", HEAD.replace("from tip", "from knob") + rows())
    hits("lab9-location-from-middle", "a header 'from middle'", HEAD.replace("from tip", "from middle") + rows())
    hits("lab9-location-speed-unit", "locations in m/s", HEAD.replace("[in from tip]", "[m/s from tip]") + rows())
    hits("lab9-location-no-unit", "locations without a unit", HEAD.replace(" [in from tip]", "") + rows())
    session("lab9-location-from-pivot", "locations from the pivot, header and session agree",
            SESSION + "location_from: pivot\n", "valid",
            hits_text=HEAD.replace("[in from tip]", "[mm from pivot]") + rows(row="{n},B1,60.80,13.00,555.2,yes,"))
    # columns
    hits("lab9-missing-hit", "no hit column", HEAD.replace("hit,", "", 1) + rows(row="B1,60.80,13.00,6,yes,"))
    hits("lab9-missing-ball", "no ball column", HEAD.replace("ball,", "") + rows(row="{n},60.80,13.00,6,yes,"))
    hits("lab9-missing-location", "no impact_location column", HEAD.replace("impact_location [in from tip],", "") + rows(row="{n},B1,60.80,13.00,yes,"))
    hits("lab9-only-inbound", "inbound speed without rebound speed", HEAD.replace("rebound_speed [m/s],", "") + rows(row="{n},B1,60.80,6,yes,"))
    hits("lab9-extra-column", "an unknown column (temperature)", HEAD.replace(",note", ",note,temperature [degC]") + rows(row="{n},B1,60.80,13.00,6,yes,,21"))
    hits("lab9-columns-reordered", "the columns in another order", "note,valid,impact_location [in from tip],rebound_speed [m/s],inbound_speed [m/s],ball,hit\n" + rows(row=",yes,6,13.00,60.80,B1,{n}"), "valid", bare=True)
    hits("lab9-minimal-columns", "only the required columns", "hit,ball,inbound_speed [m/s],rebound_speed [m/s],impact_location [in from tip]\n" + rows(row="{n},B1,60.8,13,6"), "valid")
    hits("lab9-long-row", "a row with too many fields", HITS + "7,B1,60.8,13,6,yes,,extra,extra\n")
    hits("lab9-semicolons", "a semicolon-separated file", HITS.replace(",", ";"))
    hits("lab9-tabs", "a tab-separated file", HITS.replace(",", "\t"))
    hits("lab9-decimal-comma", "decimal commas in quoted numbers", HEAD + rows(row='{n},B1,"60,80","13,00",6,yes,'))
    # quotes
    hits("lab9-quoted-numbers", "every number quoted", HEAD + rows(row='"{n}","B1","60.80","13.00","6","yes",""'), "valid")
    hits("lab9-quoted-header", "a quoted header", ",".join(f'"{h}"' for h in COLS) + "\n" + rows(), "either")
    hits("lab9-unbalanced-quote", "a note with an unbalanced quote", HEAD + rows(5) + '6,B1,60.8,13,6,yes,"oops\n', "either")
    hits("lab9-quote-in-field", "a quote inside an unquoted field", HEAD + rows(5) + '6,B"1,60.8,13,6,yes,a"b\n', "either")
    hits("lab9-quoted-newline", "a quoted note that spans two lines", HEAD + rows(5) + '6,B1,60.8,13,6,yes,"line one\nline two"\n', "either")
    hits("lab9-quoted-comma-header", "a quoted comma in the note column of every row", HEAD + rows(row='{n},B1,60.8,13,6,yes,"a,b"'), "valid")
    hits("lab9-escaped-quotes", "doubled quotes in a note", HEAD + rows(row='{n},B1,60.8,13,6,yes,"say ""hi"""'), "valid")
    # numbers
    hits("lab9-number-underscore", "a speed '60_8' (Python reads it as 608)", HEAD + rows(5) + "6,B1,6_0.8,13,6,yes,\n")
    hits("lab9-number-hex", "a hex speed", HEAD + rows(5) + "6,B1,0x3c,13,6,yes,\n")
    hits("lab9-number-with-unit", "a speed cell with its unit", HEAD + rows(5) + "6,B1,60.8 m/s,13,6,yes,\n")
    hits("lab9-number-thousands", "a thousands separator (splits the row)", HEAD + rows(5) + "6,B1,1,060.8,13,6,yes,\n")
    hits("lab9-number-1e400", "a speed 1e400 (overflows to inf)", HEAD + rows(5) + "6,B1,1e400,13,6,yes,\n")
    hits("lab9-number-minus-zero", "an inbound speed -0", HEAD + rows(5) + "6,B1,-0,13,6,yes,\n")
    hits("lab9-number-subnormal", "an inbound speed 5e-324 m/s", HEAD + rows(5) + "6,B1,5e-324,13,6,yes,\n", "either")
    hits("lab9-huge-mph", "a speed of 1e30 mph", HEAD.replace("[m/s]", "[mph]") + rows(5, "{n},B1,136,29,6,yes,") + "6,B1,1e30,29,6,yes,\n")
    hits("lab9-rebound-zero", "a rebound speed of zero on every hit", HEAD + rows(row="{n},B1,60.80,0,6,yes,"), "either")
    hits("lab9-rebound-above-inbound", "rebound faster than inbound (COR above 1)", HEAD + rows(row="{n},B1,60.80,120,6,yes,"), "either")
    hits("lab9-location-at-tip", "every hit at the tip", HEAD + rows(row="{n},B1,60.80,13.00,0,yes,"), "either")
    hits("lab9-location-1e-300", "every hit 1e-300 in from the tip", HEAD + rows(row="{n},B1,60.80,13.00,1e-300,yes,"), "either")
    hits("lab9-location-1e308", "a hit 1e308 in from the tip", HEAD + rows(5) + "6,B1,60.8,13,1e308,yes,\n")
    hits("lab9-hit-text", "a hit number that is text", HEAD + rows(5) + "six,B1,60.8,13,6,yes,\n")
    hits("lab9-hit-inf", "a hit number 1e400", HEAD + rows(5) + "1e400,B1,60.8,13,6,yes,\n")
    hits("lab9-hit-fraction", "hit numbers 1.5, -2, 0", HEAD + "1.5,B1,60.8,13,6,yes,\n-2,B1,60.8,13,6,yes,\n0,B1,60.8,13,6,yes,\n" + rows(3), "either")
    hits("lab9-hit-duplicate", "every hit numbered 1", HEAD + rows(row="1,B1,60.80,13.00,6,yes,"), "either")
    hits("lab9-rows-duplicated", "every row twice", HEAD + rows() + rows(), "either")
    hits("lab9-ball-empty", "an empty ball identifier", HEAD + rows(row="{n},,60.80,13.00,6,yes,"), "either")
    hits("lab9-ball-long", "a 10,000-character ball identifier", HEAD + rows(row="{n}," + "B" * 10_000 + ",60.80,13.00,6,yes,"), "either")
    hits("lab9-valid-case", "valid written YES, No, TRUE, 0", HEAD + rows(2, "{n},B1,60.8,13,6,YES,") + rows(2, "{n},B1,60.8,13,6,No,").replace("1,", "3,", 1).replace("2,", "4,", 1) + "5,B1,60.8,13,6,TRUE,\n6,B1,60.8,13,6,0,\n", "either")
    hits("lab9-valid-spaces", "valid with spaces (' yes ')", HEAD + rows(row="{n},B1,60.80,13.00,6, yes ,"), "valid")
    hits("lab9-600-hits", "600 hits at 100 locations", HEAD + "".join(f"{i},B{i // 6},60.8,13,{2 + (i // 6) * 0.1:.2f},yes,\n" for i in range(600)), "either")
    hits("lab9-over-max-hits", "100,001 hits (the limit is 100,000)", HEAD + "".join(f"{i},B,60.8,13,6,yes,\n" for i in range(100_001)))
    # gate times
    gates = "hit,ball,inbound_gate_time [ms],rebound_gate_time [ms],impact_location [in from tip]\n"
    gs = SESSION + "gate_spacing: 0.5 m\n"
    hits("lab9-gates-valid", "gate times with the gate spacing", gates + rows(row="{n},B1,8.2237,38,6"), "valid", session=gs)
    hits("lab9-gates-negative", "a negative gate time", gates + rows(5, "{n},B1,8.2237,38,6") + "6,B1,-8.2,38,6\n", session=gs)
    hits("lab9-gates-tiny", "a gate time of 1e-300 ms (a speed beyond any plausible one)", gates + rows(5, "{n},B1,8.2237,38,6") + "6,B1,1e-300,38,6\n", session=gs)
    hits("lab9-gates-huge", "a gate time of 1e300 s (a speed of zero)", gates.replace("[ms],impact", "[s],impact") + rows(5, "{n},B1,0.0082237,0.038,6") + "6,B1,0.0082237,1e300,6\n", "either", session=gs)
    hits("lab9-gates-nan", "a gate time nan", gates + rows(5, "{n},B1,8.2237,38,6") + "6,B1,nan,38,6\n", session=gs)
    hits("lab9-gates-hz", "gate times in Hz", gates.replace("inbound_gate_time [ms]", "inbound_gate_time [Hz]") + rows(row="{n},B1,8.2237,38,6"), session=gs)
    hits("lab9-gate-spacing-huge", "a gate spacing of 1e300 m (speeds beyond any plausible one)", gates + rows(row="{n},B1,8.2237,38,6"), session=SESSION + "gate_spacing: 1e300 m\n")
    hits("lab9-gate-spacing-tiny", "a gate spacing of 1e-300 m (speeds of almost zero)", gates + rows(row="{n},B1,8.2237,38,6"), "either", session=SESSION + "gate_spacing: 1e-300 m\n")
    hits("lab9-gates-and-speeds", "both speeds and gate times", HEAD.replace(",valid", ",inbound_gate_time [ms],rebound_gate_time [ms],valid") + rows(row="{n},B1,60.8,13,6,8.2237,38,yes,"), "either", session=gs)
    # bat angular speed after the hit (BPF)
    w2 = HEAD.replace(",valid", ",bat_angular_speed_after [rad/s],valid")
    hits("lab9-w2-blank", "bat_angular_speed_after given, every cell blank", w2 + rows(row="{n},B1,60.8,13,6,,yes,"), "valid")
    hits("lab9-w2-nan", "bat_angular_speed_after nan", w2 + rows(row="{n},B1,60.8,13,6,nan,yes,"))
    hits("lab9-w2-huge", "bat_angular_speed_after 1e308 rad/s", w2 + rows(row="{n},B1,60.8,13,6,1e308,yes,"))
    hits("lab9-w2-rpm", "bat_angular_speed_after in rpm", w2.replace("[rad/s]", "[rpm]") + rows(row="{n},B1,60.8,13,6,100,yes,"), "valid")
    # the session file
    session("lab9-hits-per-ball-1", "one hit per ball (the rest invalid)", SESSION + "hits_per_ball: 1\n", "valid")
    session("lab9-speed-tol-tiny", "a speed tolerance of 1e-300 m/s (every hit invalid)", SESSION + "speed_tolerance: 1e-300 m/s\n", "valid")
    session("lab9-speed-tol-huge", "a speed tolerance of 1e300 m/s", SESSION + "speed_tolerance: 1e300 m/s\n", "either")
    session("lab9-location-step-tiny", "a location step of 1e-300 m", SESSION + "location_step: 1e-300 m\n", "either")
    session("lab9-location-step-huge", "a location step of 1e300 m", SESSION + "location_step: 1e300 m\n", "either")
    session("lab9-hits-required-1000", "1000 hits required of six", SESSION + "hits_required: 1000\n", "valid")
    session("lab9-unc-speed-huge", "a speed uncertainty of 1e300 m/s", SESSION + "uncertainty:\n  speed: 1e300 m/s\n", "either")
    session("lab9-unc-negative", "a negative location uncertainty", SESSION + "uncertainty:\n  impact_location: -1 mm\n")
    session("lab9-unc-moi-huge", "an MOI uncertainty of 1e30 kg*m^2", SESSION + "uncertainty:\n  moi: 1e30 kg*m^2\n", "either")
    session("lab9-unc-ball-mass-unit", "a ball-mass uncertainty in metres", SESSION + "uncertainty:\n  ball_mass: 1 m\n")
    session("lab9-pivot-zero", "a pivot at the knob", SESSION.replace("pivot: 6 in", "pivot: 0 in"), "either")
    session("lab9-pivot-beyond", "a pivot 40 in from the knob (off the bat)", SESSION.replace("pivot: 6 in", "pivot: 40 in"))
    session("lab9-pivot-inf", "a pivot of 1e309 in", SESSION.replace("pivot: 6 in", "pivot: 1e309 in"))
    session("lab9-hits-abs-example", "hits: the shipped example by absolute path", SESSION.replace("hits: hits.csv", "hits: @REPO@/examples/lab/synthetic-exact.csv"), "valid")
    session("lab9-hits-traversal", "hits: ../../nope.csv", SESSION.replace("hits: hits.csv", "hits: ../../nope.csv"))
    session("lab9-hits-devnull", "hits: /dev/null", SESSION.replace("hits: hits.csv", "hits: /dev/null"))
    session("lab9-hits-self", "hits: the session file itself", SESSION.replace("hits: hits.csv", "hits: session.yaml"))
    session("lab9-hits-empty-name", "hits: ''", SESSION.replace("hits: hits.csv", "hits: ''"))
    session("lab9-hits-list", "hits: [a.csv, b.csv]", SESSION.replace("hits: hits.csv", "hits: [a.csv, b.csv]"))
    session("lab9-bat-local-invalid", "bat: a local bat file with a unit typo", SESSION.replace("bat: aluminium-34", "bat: bad.yaml"), files={"bad.yaml": sub(HOLLOW, "length: 860 mm", "length: 860 mms")})
    session("lab9-bat-is-session", "bat: the session file itself", SESSION.replace("bat: aluminium-34", "bat: session.yaml"))
    session("lab9-ball-unknown", "ball: an unknown ball", SESSION.replace("ball: collegiate-baseball", "ball: softball-x"))
    session("lab9-ball-is-bat", "ball: a bat file", SESSION.replace("ball: collegiate-baseball", "ball: @REPO@/bats/ash-34.yaml"))
    session("lab9-lab-signatures-empty", "lab signatures: []", SESSION + "lab:\n  signatures: []\n")
    session("lab9-lab-unknown-key", "an unknown key in the lab block", SESSION + "lab:\n  operatr: A. B.\n")
    session("lab9-lab-is-list", "lab: a list", SESSION + "lab: [a, b]\n")
    session("lab9-no-name", "a session without a name", SESSION.replace("name: Lab session (surfaces)\n", ""))
    session("lab9-top-list", "a session that is a list", "- a\n- b\n")
    session("lab9-yaml-in-csv-name", "a session file named .csv (read as a bare hits CSV)", SESSION, commands=[["reduce", "{d}/session.csv", "-p", "ncaa-bbcor", "--bat", "aluminium-34", *RIGID, "--no-reports"]], files={"session.csv": SESSION})
    # the command line
    cmd = ["reduce", "{f}", *RIGID, "--no-reports"]
    session("lab9-bat-with-session", "--bat given with a session YAML", SESSION, commands=[[*cmd, "-p", "ncaa-bbcor", "--bat", "ash-34"]])
    session("lab9-bare-no-bat", "a bare hits CSV without --bat", SESSION, commands=[["reduce", "{d}/hits.csv", "-p", "ncaa-bbcor", *RIGID, "--no-reports"]])
    session("lab9-bare-unknown-bat", "a bare hits CSV with an unknown --bat", SESSION, commands=[["reduce", "{d}/hits.csv", "-p", "ncaa-bbcor", "--bat", "aluminium-35", *RIGID, "--no-reports"]])
    session("lab9-bare-upper-suffix", "a bare hits CSV named HITS.CSV", SESSION, "valid", files={"HITS.CSV": HITS}, commands=[["reduce", "{d}/HITS.CSV", "-p", "ncaa-bbcor", "--bat", "aluminium-34", *RIGID, "--no-reports"]])
    for proto, exp in [("astm-bpf", "either"), ("ncaa-besr", "invalid"), ("proposed", "either"),
                       ("stationary-ball", "invalid")]:
        session(f"lab9-protocol-{proto}", f"a BBCOR session reduced under {proto}", SESSION, exp,
                commands=[[*cmd, "-p", proto]])
    session("lab9-guarded", "the guarded decision rule", SESSION, "valid", commands=[[*cmd, "-p", "ncaa-bbcor", "--decision-rule", "guarded", "--json"]])
    session("lab9-decision-rule-bad", "an unknown decision rule", SESSION, commands=[[*cmd, "-p", "ncaa-bbcor", "--decision-rule", "strict"]])
    session("lab9-format-json-only", "reports in JSON only", SESSION, "valid", commands=[["reduce", "{f}", "-p", "ncaa-bbcor", *RIGID, "--format", "json", "--out", "{out}"]])
    session("lab9-session-dir", "the session argument is a directory", SESSION, commands=[["reduce", "{d}", "-p", "ncaa-bbcor", *RIGID, "--no-reports"]])
    session("lab9-session-missing", "the session file does not exist", SESSION, commands=[["reduce", "{d}/nope.yaml", "-p", "ncaa-bbcor", *RIGID, "--no-reports"]])


# ------------------------------------------------------------------------------------------
# 10. Sweep and design ranges
# ------------------------------------------------------------------------------------------
def sweeps() -> None:
    c = "10-sweep"

    def sweep(cid, varies, bat="aluminium-34", proto="ncaa-bbcor", expect="either", extra=(),
              known=""):
        argv = ["sweep", bat, "-p", proto, *RIGID, "--no-reports", *extra]
        for v in varies:
            argv += ["--vary", v]
        command(cid, c, argv, expect=expect, known=known)

    for cid, v in [
        ("no-equals", "wall"), ("empty-range", "wall="), ("no-name", "=60%:140%:3"),
        ("empty", ""), ("one-value", "wall=110%"), ("no-count", "wall=60%:140%"),
        ("count-zero", "wall=60%:140%:0"), ("count-one", "wall=60%:140%:1"),
        ("count-one-equal", "wall=100%:100%:1"), ("count-negative", "wall=60%:140%:-3"),
        ("count-fraction", "wall=60%:140%:2.5"), ("count-exponent", "wall=60%:140%:1e3"),
        ("count-over-cap", "wall=60%:140%:100001"), ("count-huge", "wall=60%:140%:" + "9" * 40),
        ("count-leading-zero", "wall=90%:110%:03"), ("count-arabic-digit", "wall=90%:110%:\u0663"),
        ("count-fullwidth-digit", "wall=90%:110%:\uff13"), ("reversed", "wall=110%:90%:3"),
        ("zero-step", "wall=100%:100%:3"), ("units", "wall=2.5mm:3mm:2"),
        ("units-spaced", "wall=2.5 mm : 3 mm : 2"), ("shorthand-unit", "wall=2.5:3mm:2"),
        ("second-bare", "wall=2.5mm:3:2"), ("both-bare", "wall=2.5:3:2"),
        ("wrong-unit", "wall=2kg:3kg:2"), ("mixed-percent", "wall=2.5mm:110%:2"),
        ("unit-typo", "wall=2.5mmm:3mm:2"), ("nan-percent", "wall=nan%:110%:2"),
        ("inf-percent", "wall=inf%:110%:2"), ("nan-unit", "wall=nan mm:3mm:2"),
        ("huge-unit", "wall=1e309mm:3mm:2"), ("negative-percent", "wall=-50%:110%:2"),
        ("zero-percent", "wall=0%:110%:2"), ("tiny-percent", "wall=1e-300%:110%:2"),
        ("double-percent", "wall=90%%:110%:2"), ("spaced-percent", "wall=90 %:110 %:2"),
        ("four-parts", "wall=90%:110%:2:4"), ("letters", "wall=a:b:2"),
        ("semicolons", "wall=90%;110%;2"), ("zero-width-space", "wall\u200b=90%:110%:2"),
        ("capitalised", "Wall=90%:110%:2"), ("typo", "wal=90%:110%:2"),
        ("spaces-around", " wall = 90% : 110% : 2 "), ("two-equals", "wall==90%:110%:2"),
        ("markup", "[bold]wall[/]=90%:110%:2"), ("ansi", "wall\x1b[31m=90%:110%:2"),
        ("outside-bounds", "wall=25mm:30mm:2"),
    ]:
        sweep(f"sweep-vary-{cid}", [v])
    sweep("sweep-wall-solid-bat", ["wall=90%:110%:2"], bat="ash-34")
    sweep("sweep-youngs-modulus", ["youngs_modulus=80%:120%:2"], bat="ash-34", expect="valid")
    sweep("sweep-youngs-modulus-zero", ["youngs_modulus=0GPa:10GPa:2"], bat="ash-34")
    sweep("sweep-density-units", ["density=500kg/m^3:700kg/m^3:2"], bat="ash-34", expect="valid")
    sweep("sweep-density-wrong-unit", ["density=500kg:700kg:2"], bat="ash-34")
    sweep("sweep-barrel-below-handle", ["barrel_diameter=0.5in:2.6in:2"])
    sweep("sweep-barrel-valid", ["barrel_diameter=2.5in:2.7in:2"], expect="valid")
    sweep("sweep-mass", ["mass=800g:900g:2"], bat="ash-34", expect="valid")
    sweep("sweep-moi-percent", ["moi=90%:110%:2"], bat="ash-34", expect="valid")
    sweep("sweep-hoop-percent-no-nominal", ["hoop_frequency=90%:110%:2"])
    sweep("sweep-hoop-absolute", ["hoop_frequency=1200Hz:2400Hz:2"], expect="either")
    sweep("sweep-pitch-zero", ["pitch_speed=0mph:10mph:2"])
    sweep("sweep-pitch-speed", ["pitch_speed=120mph:140mph:2"], expect="valid")
    sweep("sweep-bat-speed-stationary", ["bat_angular_speed=10rad/s:20rad/s:2"])
    sweep("sweep-relative-below-pitch", ["relative_speed=20m/s:70m/s:2"], proto="proposed")
    sweep("sweep-relative-shorthand", ["relative_speed=50:70m/s:2"], proto="proposed", expect="valid")
    sweep("sweep-unknown-length", ["length=80%:120%:2"])
    sweep("sweep-unknown-pivot", ["pivot=5in:7in:2"])
    sweep("sweep-grid-2x2", ["wall=90%:110%:2", "pitch_speed=130mph:140mph:2"], expect="valid")
    sweep("sweep-grid-same-twice", ["wall=90%:110%:2", "wall=80%:120%:2"])
    sweep("sweep-grid-three", ["wall=90%:110%:2", "pitch_speed=130mph:140mph:2", "mass=800g:900g:2"])
    sweep("sweep-grid-one-bad", ["wall=90%:110%:2", "pitch_speed=130mph:140:2"])
    sweep("sweep-grid-bounds", ["wall=90%:110%:2", "pitch_speed=130mph:1e9mph:2"])
    command("sweep-protocol-no-limit", c, ["sweep", "aluminium-34", "-p", "proposed", *RIGID, "--vary", "wall=90%:110%:2", "--json"], expect="valid")
    command("sweep-format-md", c, ["sweep", "aluminium-34", "-p", "ncaa-bbcor", *RIGID, "--vary", "wall=90%:110%:2", "--format", "md", "--out", "{out}"], expect="valid")

    def design(cid, extra, bat="aluminium-34", proto="ncaa-bbcor", expect="either", known=""):
        command(cid, c, ["design", bat, "-p", proto, *RIGID, "--no-reports", *extra],
                expect=expect, known=known)

    design("design-wall-valid", ["--solve", "wall", "--range", "80%:120%", "--points", "3"], expect="valid")
    design("design-unknown", ["--solve", "walls"])
    design("design-range-one", ["--solve", "wall", "--range", "80%", "--points", "3"])
    design("design-range-with-n", ["--solve", "wall", "--range", "80%:120%:5", "--points", "3"])
    design("design-range-reversed", ["--solve", "wall", "--range", "120%:80%", "--points", "3"])
    design("design-range-zero-width", ["--solve", "wall", "--range", "100%:100%", "--points", "3"])
    design("design-range-letters", ["--solve", "wall", "--range", "a:b"])
    design("design-range-negative", ["--solve", "wall", "--range", "-10%:10%"])
    design("design-range-empty", ["--solve", "wall", "--range", "", "--points", "3"])
    design("design-points-2", ["--solve", "wall", "--points", "2"])
    design("design-points-1002", ["--solve", "wall", "--points", "1002"])
    design("design-tolerance-zero", ["--solve", "wall", "--range", "80%:120%", "--points", "3", "--tolerance", "0 mm"])
    design("design-tolerance-negative", ["--solve", "wall", "--range", "80%:120%", "--points", "3", "--tolerance", "-1 mm"])
    design("design-tolerance-nan", ["--solve", "wall", "--range", "80%:120%", "--points", "3", "--tolerance", "nan mm"])
    design("design-tolerance-inf", ["--solve", "wall", "--range", "80%:120%", "--points", "3", "--tolerance", "1e309 mm"])
    design("design-tolerance-huge", ["--solve", "wall", "--range", "80%:120%", "--points", "3", "--tolerance", "1 km"])
    design("design-tolerance-tiny", ["--solve", "wall", "--range", "80%:120%", "--points", "3", "--tolerance", "1e-300 m"])
    design("design-tolerance-unit", ["--solve", "wall", "--range", "80%:120%", "--points", "3", "--tolerance", "1 kg"])
    design("design-tolerance-percent", ["--solve", "wall", "--range", "80%:120%", "--points", "3", "--tolerance", "1%"])
    design("design-no-limit", ["--solve", "wall", "--range", "80%:120%", "--points", "3"], proto="proposed")
    design("design-pitch-speed", ["--solve", "pitch_speed", "--range", "100mph:140mph", "--points", "3"], expect="valid")
    design("design-mass-solid", ["--solve", "mass", "--range", "80%:120%", "--points", "3"], bat="ash-34", expect="valid")
    design("design-hoop-rigid", ["--solve", "hoop_frequency", "--range", "1200Hz:3000Hz", "--points", "3"], bat="bbcor-alloy-34", expect="valid")
    command("design-resume", c, ["design", "aluminium-34", "-p", "ncaa-bbcor", "--solve", "wall", "--resume"])


# ------------------------------------------------------------------------------------------
# 11. Workers, schedulers and --resume
# ------------------------------------------------------------------------------------------
def scale() -> None:
    c = "11-scale"
    base = ["sweep", "aluminium-34", "-p", "ncaa-bbcor", *RIGID, "--vary", "wall=90%:110%:2"]
    for cid, w in [("zero", "0"), ("negative", "-1"), ("257", "257"), ("text", "two"),
                   ("fraction", "1.5"), ("empty", ""), ("huge", "9" * 30)]:
        command(f"scale-workers-{cid}", c, [*base, "--workers", w, "--no-reports"])
    command("scale-design-workers-zero", c, ["design", "aluminium-34", "-p", "ncaa-bbcor", "--solve", "wall", "--workers", "0"])
    command("scale-workers-2", c, [*base, "--workers", "2", "--out", "{out}"], expect="valid")
    for cid, s in [("empty", ""), ("words", "not an address"), ("scheme-only", "tcp://"),
                   ("port-text", "tcp://127.0.0.1:notaport"), ("no-port", "127.0.0.1"),
                   ("ipv6-unclosed", "tcp://[::1"), ("http", "http://127.0.0.1:1"),
                   ("file", "file:///etc/passwd"), ("inproc", "inproc://nothing"),
                   ("query", "tcp://127.0.0.1:1/?x=1"),
                   ("newline", "tcp://127.0.0.1:1\nx"), ("markup", "[bold]tcp://x[/]"),
                   ("ansi", "\x1b[31mtcp://127.0.0.1:1")]:
        command(f"scale-scheduler-{cid}", c, [*base, "--scheduler", s, "--no-reports"])
    command("scale-scheduler-refused", c, [*base, "--scheduler", "tcp://127.0.0.1:1", "--out", "{out}"],
            desc="a scheduler at a closed localhost port: exit 5 after the connect timeout, nothing written")
    command("scale-scheduler-tls", c, [*base, "--scheduler", "tls://127.0.0.1:1", "--no-reports"])
    command("scale-scheduler-ucx", c, [*base, "--scheduler", "ucx://127.0.0.1:1", "--no-reports"])
    command("scale-scheduler-and-workers", c, [*base, "--scheduler", "not an address", "--workers", "2", "--no-reports"])
    command("scale-design-scheduler-bad", c, ["design", "aluminium-34", "-p", "ncaa-bbcor", *RIGID, "--solve", "wall", "--points", "3", "--scheduler", "tcp://", "--no-reports"])
    command("scale-resume-no-reports", c, [*base, "--resume", "--no-reports"])
    command("scale-resume-json-no-out", c, [*base, "--resume", "--json"])
    command("scale-resume-no-journal", c, [*base, "--resume", "--out", "{out}"], expect="valid")
    command("scale-resume-json-out", c, [*base, "--resume", "--json", "--out", "{out}"], expect="valid")
    command("scale-resume-out-is-file", c, [*base, "--resume", "--out", "{d}/f.txt"], files={"f.txt": "x"})
    case("scale-resume-after-finished", c, "--resume into a directory whose sweep finished (its journal "
         "removed): runs again", "cmd", expect="valid",
         commands=[[*base, "--out", "{d}/rep"], [*base, "--resume", "--out", "{d}/rep"]])


# ------------------------------------------------------------------------------------------
# 12. User text that could act on a reader (reports, terminal)
# ------------------------------------------------------------------------------------------
PAYLOADS = {
    "script": "<script>alert(1)</script>",
    "img": "<img src=x onerror=alert(2)>",
    "md-html-block": "a\n\n<div onmouseover=alert(3)>x</div>\n\nb",
    "md-pipe": "a | b || c |",
    "md-heading": "x\n\n# PWNHEAD\n\ny",
    "md-link": "[click](javascript:alert(4))",
    "rich": "[bold]x[/bold] [/] [link=http://x]y",
    "ansi": "\x1b[31mred\x1b[0m \x1b]0;title\x07 \x1b[2J",
    "mathtext": "$\\frac{1}$ $x^$ $$ \\$",
    "rtl": "\u202eevil\u202c \u200b\u200f\u2066x\u2069 \ufeff",
    "long": "L" * 20_000 + "<script>alert(9)</script>",
    "backtick": "x` <img src=y onerror=alert(5)> `y",
}


def y(text: str) -> str:
    """A YAML double-quoted scalar holding ``text`` exactly."""
    return json.dumps(text, ensure_ascii=False)


def inject() -> None:
    c = "12-inject"
    run = [["run", "{f}", "-p", "ncaa-bbcor", *RIGID, "--out", "{out}"]]
    ident = "identification:\n  maker: Maker\n  model: Model\n  serial: S-1\n  lot: L-1\n"
    for pname, p in PAYLOADS.items():
        # control characters and bidirectional controls (in labels) may be refused
        exp = "either" if pname in ("long", "ansi", "rtl") else "valid"
        case(f"inj-bat-name-{pname}", c, f"bat name: {pname} payload", "bat",
             sub(SOLID, "name: Ash 34 in (fuzz)", f"name: {y(p)}"), expect=exp, commands=run,
             known="")
        case(f"inj-bat-maker-{pname}", c, f"identification maker: {pname} payload", "bat",
             SOLID + ident.replace("maker: Maker", f"maker: {y(p)}"), expect=exp, commands=run)
        case(f"inj-bat-serial-{pname}", c, f"identification serial: {pname} payload", "bat",
             SOLID + ident.replace("serial: S-1", f"serial: {y(p)}"), expect=exp, commands=run)
    for field in ["description", "reference"]:
        for pname in ["script", "md-html-block", "md-heading", "md-pipe", "ansi", "rich", "backtick"]:
            case(f"inj-bat-{field}-{pname}", c, f"bat {field}: {pname} payload", "bat",
                 sub(SOLID, "reference: fuzz copy of bats/ash-34.yaml",
                     f"reference: {y(PAYLOADS[pname])}" if field == "reference" else
                     f"reference: fuzz copy of bats/ash-34.yaml\ndescription: {y(PAYLOADS[pname])}"),
                 expect="either" if pname == "ansi" else "valid", commands=run)
    for field in ["model", "lot"]:
        for pname in ["img", "md-link", "ansi", "md-pipe"]:
            case(f"inj-bat-{field}-{pname}", c, f"identification {field}: {pname} payload", "bat",
                 SOLID + ident.replace(f"{field}: " + ("Model" if field == "model" else "L-1"),
                                       f"{field}: {y(PAYLOADS[pname])}"),
                 expect="valid", commands=run)
    case("inj-bat-ident-all", c, "every identification field a different payload", "bat",
         SOLID + f"identification:\n  maker: {y(PAYLOADS['script'])}\n  model: {y(PAYLOADS['md-pipe'])}\n"
         f"  serial: {y(PAYLOADS['rtl'])}\n  lot: {y(PAYLOADS['md-heading'])}\n",
         expect="either",  # a label's bidirectional controls may be refused
         commands=[["run", "{f}", "-p", "ncaa-bbcor", *RIGID, "--json", "--out", "{out}"],
                                   ["validate", "{f}"], ["inspect", "{f}"]])
    # protocol, ball, league and study text
    prun = [["run", "ash-34", "-p", "{f}", *RIGID, "--out", "{out}"]]
    for pname in ["script", "md-html-block", "md-pipe", "md-heading", "ansi", "rich"]:
        case(f"inj-proto-title-{pname}", c, f"protocol title: {pname} payload", "protocol",
             sub(BBCOR, "title: NCAA BBCOR (fuzz)", f"title: {y(PAYLOADS[pname])}"),
             expect="valid", commands=prun)
    for pname in ["img", "md-pipe", "ansi"]:
        case(f"inj-proto-condition-{pname}", c, f"condition name: {pname} payload", "protocol",
             sub(BBCOR, "  - name: stationary-bat", f"  - name: {y(PAYLOADS[pname])}"),
             expect="either", commands=prun)
        case(f"inj-ball-name-{pname}", c, f"ball name: {pname} payload", "ball",
             sub(BALL, "name: Collegiate baseball (fuzz)", f"name: {y(PAYLOADS[pname])}"),
             expect="valid", files={"proto.yaml": corpus.BALL_PROTO},
             commands=[["run", "ash-34", "-p", "{d}/proto.yaml", *RIGID, "--out", "{out}"]])
    lrun = [["league", "{f}", "ash-34", *RIGID, "--out", "{out}"]]
    for pname in ["script", "md-pipe", "md-heading", "ansi"]:
        case(f"inj-league-title-{pname}", c, f"league title and a rule's source: {pname} payload",
             "league", sub(sub(LEAGUE, "title: Fuzz league (copy of ncaa)", f"title: {y(PAYLOADS[pname])}"),
                           "    source: fuzz", f"    source: {y(PAYLOADS[pname])}"),
             expect="valid", commands=lrun)
    srun = [["compare", "--study", "{f}", *RIGID, "--out", "{out}"]]
    for pname in ["script", "md-pipe", "ansi"]:
        case(f"inj-study-claim-{pname}", c, f"study title and a claim statement: {pname} payload",
             "study", sub(sub(STUDY, "title: Fuzz study (copy of smith2001)", f"title: {y(PAYLOADS[pname])}"),
                          "    statement: methods disagree", f"    statement: {y(PAYLOADS[pname])}"),
             expect="valid", commands=srun)
    # lab sessions: the session's text, its lab block, the hits' notes and ball ids
    red = [["reduce", "{f}", "-p", "ncaa-bbcor", *RIGID, "--out", "{out}"]]
    for pname in ["script", "img", "md-html-block", "md-pipe", "md-heading", "md-link", "ansi", "rich", "rtl"]:
        p = PAYLOADS[pname]
        case(f"inj-session-name-{pname}", c, f"session name: {pname} payload", "session",
             sub(SESSION, "name: Lab session (surfaces)", f"name: {y(p)}"), main="session.yaml",
             expect="either" if pname == "rtl" else "valid", files={"hits.csv": HITS}, commands=red)
        case(f"inj-session-lab-{pname}", c, f"session lab block (laboratory, operator, signatures): {pname} payload",
             "session", SESSION + f"lab:\n  laboratory: {y(p)}\n  operator: {y(p)}\n  bat_serial: {y(p)}\n"
             f"  certificate_number: {y(p)}\n  signatures: [{y(p)}, ok]\n",
             main="session.yaml", expect="valid", files={"hits.csv": HITS}, commands=red)
    for pname in ["script", "md-pipe", "ansi", "md-heading"]:
        p = PAYLOADS[pname].replace("\n", " ")
        q = '"' + p.replace('"', '""') + '"'
        case(f"inj-hits-note-{pname}", c, f"hits note and ball id: {pname} payload", "session",
             SESSION, main="session.yaml", expect="valid",
             files={"hits.csv": HEAD + rows(row="{n}," + q + ",60.80,13.00,6,yes," + q)},
             commands=red)
    case("inj-session-description-html", c, "session description and reference: raw HTML block", "session",
         SESSION + f"description: {y(PAYLOADS['md-html-block'])}\nreference: {y(PAYLOADS['script'])}\n",
         main="session.yaml", expect="valid", files={"hits.csv": HITS}, commands=red)
    # sweeps and designs carry the bat's name and identification
    hollow = sub(HOLLOW, "name: Aluminium 34 in (fuzz)", f"name: {y(PAYLOADS['script'] + ' | ' + PAYLOADS['md-heading'])}")
    case("inj-sweep-bat-name", c, "sweep of a bat whose name is HTML, a table breaker and a heading", "bat",
         hollow + f"identification:\n  serial: {y(PAYLOADS['img'])}\n", expect="valid",
         commands=[["sweep", "{f}", "-p", "ncaa-bbcor", *RIGID, "--vary", "wall=90%:110%:2", "--out", "{out}"]])
    case("inj-design-bat-name", c, "design of a bat whose name is HTML and ANSI", "bat",
         sub(HOLLOW, "name: Aluminium 34 in (fuzz)", f"name: {y(PAYLOADS['script'] + PAYLOADS['ansi'])}"),
         expect="either",
         commands=[["design", "{f}", "-p", "ncaa-bbcor", *RIGID, "--solve", "wall", "--range", "80%:120%", "--points", "3", "--out", "{out}"]])
    # mathtext and figures: text that matplotlib would read as mathtext
    math = PAYLOADS["mathtext"]
    case("inj-figures-bat-name-mathtext", c, "--figures with a bat name that is broken mathtext", "bat",
         sub(SOLID, "name: Ash 34 in (fuzz)", f"name: {y(math)}"), expect="valid",
         commands=[["run", "{f}", "-p", "ncaa-bbcor", *RIGID, "--no-reports", "--figures", "{d}/fig"]])
    case("inj-figures-proto-title-mathtext", c, "--figures with a protocol title and condition that are broken mathtext", "protocol",
         sub(sub(BBCOR, "title: NCAA BBCOR (fuzz)", f"title: {y(math)}"), "  - name: stationary-bat", "  - name: '$x_{'"),
         expect="valid",
         commands=[["run", "ash-34", "-p", "{f}", *RIGID, "--no-reports", "--figures", "{d}/fig"]])
    case("inj-figures-session-mathtext", c, "--figures of a reduction whose session name is broken mathtext", "session",
         sub(SESSION, "name: Lab session (surfaces)", f"name: {y(math)}"), main="session.yaml",
         expect="valid", files={"hits.csv": HITS},
         commands=[["reduce", "{f}", "-p", "ncaa-bbcor", *RIGID, "--no-reports", "--figures", "{d}/fig"]])
    case("inj-sweep-mathtext", c, "a sweep whose bat name is broken mathtext (reports; the figures are "
         "drawn by run, reduce above)", "bat",
         sub(HOLLOW, "name: Aluminium 34 in (fuzz)", f"name: {y(math)}"), expect="valid",
         commands=[["sweep", "{f}", "-p", "ncaa-bbcor", *RIGID, "--vary", "wall=90%:110%:2", "--out", "{out}"]])
    # text on the terminal from the command line itself
    command("inj-cli-bat-ansi", c, ["run", "\x1b[31mash-34\x1b[0m", "-p", "ncaa-bbcor", *RIGID, "--no-reports"])
    command("inj-cli-protocol-ansi", c, ["run", "ash-34", "-p", "\x1b]0;x\x07ncaa", *RIGID, "--no-reports"])
    command("inj-cli-vary-ansi-value", c, ["sweep", "aluminium-34", "-p", "ncaa-bbcor", *RIGID, "--vary", "wall=\x1b[2J90%:110%:2", "--no-reports"])
    command("inj-cli-out-ansi", c, ["run", "ash-34", "-p", "ncaa-bbcor", *RIGID, "--out", "{d}/f.txt/\x1b[31m"], files={"f.txt": "x"})
    for k in corpus.ALL:  # a loader may refuse control characters in text (exit 3): either is clean
        if k.category == c and "-ansi" in k.id and k.expect == "valid":
            k.expect = "either"


# ------------------------------------------------------------------------------------------
# 13. Where the outputs go: --write-calibration, --out, --figures
# ------------------------------------------------------------------------------------------
CAL_SESSION = SESSION.replace("bat: aluminium-34", "bat: bat.yaml").replace(
    "ball: collegiate-baseball", "ball: ball.yaml")


def outputs() -> None:
    c = "13-output"
    files = {"hits.csv": HITS, "bat.yaml": HOLLOW, "ball.yaml": BALL}

    def cal(cid, target, desc, expect="either", known="", links=None, extra=(), engine=RIGID):
        case(cid, c, f"--write-calibration {desc}", "session", CAL_SESSION, main="session.yaml",
             expect=expect, files=files, links=links, known=known,
             commands=[["reduce", "{f}", "-p", "ncaa-bbcor", *engine, "--out", "{out}",
                        "--write-calibration", target, *extra]])

    cal("out-cal-session", "{f}", "to the session file itself")
    cal("out-cal-hits", "{d}/hits.csv", "to the hits CSV")
    cal("out-cal-bat", "{d}/bat.yaml", "to the session's bat file")
    cal("out-cal-bat-relative", "bat.yaml", "to the bat file by a relative path")
    cal("out-cal-bat-dotted", "{d}/./x/../bat.yaml", "to the bat file through ./x/.. (x missing)")
    cal("out-cal-ball", "{d}/ball.yaml", "to the session's ball file (an input known only after the run)")
    cal("out-cal-dir", "{d}", "to a directory")
    cal("out-cal-devnull", "/dev/null", "to /dev/null")
    cal("out-cal-under-file", "{d}/hits.csv/bat.yaml", "to a path under a file")
    cal("out-cal-symlink-bat", "{d}/link.yaml", "to a symlink to the bat file", links={"link.yaml": "{d}/bat.yaml"})
    cal("out-cal-symlink-session", "{d}/link.yaml", "to a symlink to the session", links={"link.yaml": "session.yaml"})
    cal("out-cal-dangling-symlink", "{d}/link.yaml", "to a dangling symlink", links={"link.yaml": "{d}/nowhere/x.yaml"})
    cal("out-cal-symlink-loop", "{d}/loop.yaml", "to a symlink loop", links={"loop.yaml": "loop.yaml"})
    cal("out-cal-shipped-bat", "@REPO@/bats/aluminium-34.yaml", "to a shipped bat file (not an input of this run)")
    cal("out-cal-new-file-rigid", "{d}/calibrated.yaml", "to a new file with the rigid engine (no calibration possible)")
    cal("out-cal-long-name", "{d}/" + "c" * 300 + ".yaml", "to a name longer than 255 bytes")
    cal("out-cal-empty", "", "to ''")
    cal("out-cal-missing-dir", "{d}/new/dir/cal.yaml", "into directories that do not exist")
    case("out-cal-bare-hits", c, "--write-calibration to the bare hits CSV being reduced", "session", CAL_SESSION,
         main="session.yaml", files=files,
         commands=[["reduce", "{d}/hits.csv", "--bat", "{d}/bat.yaml", "-p", "ncaa-bbcor", *RIGID,
                    "--no-reports", "--write-calibration", "{d}/hits.csv"]])
    case("out-cal-bare-bat", c, "--write-calibration to the --bat of a bare hits CSV", "session", CAL_SESSION,
         main="session.yaml", files=files,
         commands=[["reduce", "{d}/hits.csv", "--bat", "{d}/bat.yaml", "-p", "ncaa-bbcor", *RIGID,
                    "--no-reports", "--write-calibration", "{d}/bat.yaml"]])
    # report and figure locations
    run = ["run", "ash-34", "-p", "ncaa-bbcor", *RIGID]
    for cid, argv, f in [
        ("out-figures-file", [*run, "--no-reports", "--figures", "{d}/f.txt"], {"f.txt": "x"}),
        ("out-figures-devnull", [*run, "--no-reports", "--figures", "/dev/null"], None),
        ("out-figures-under-file", [*run, "--no-reports", "--figures", "{d}/f.txt/fig"], {"f.txt": "x"}),
        ("out-out-long", [*run, "--out", "{d}/" + "o" * 300], None),
        ("out-out-empty", [*run, "--out", ""], None),
        ("out-reduce-out-is-session", ["reduce", "{d}/session.yaml", "-p", "ncaa-bbcor", *RIGID, "--out", "{d}/session.yaml"], {"session.yaml": SESSION, "hits.csv": HITS}),
        ("out-reduce-out-is-hits", ["reduce", "{d}/session.yaml", "-p", "ncaa-bbcor", *RIGID, "--out", "{d}/hits.csv"], {"session.yaml": SESSION, "hits.csv": HITS}),
        ("out-sweep-out-devnull", ["sweep", "aluminium-34", "-p", "ncaa-bbcor", *RIGID, "--vary", "wall=90%:110%:2", "--out", "/dev/null"], None),
        ("out-sweep-out-under-file", ["sweep", "aluminium-34", "-p", "ncaa-bbcor", *RIGID, "--vary", "wall=90%:110%:2", "--out", "{d}/f.txt/x"], {"f.txt": "x"}),
        ("out-design-out-file", ["design", "aluminium-34", "-p", "ncaa-bbcor", *RIGID, "--solve", "wall", "--points", "3", "--out", "{d}/f.txt"], {"f.txt": "x"}),
        ("out-format-dup", [*run, "--format", "md,md,json", "--out", "{out}"], None),
        ("out-format-spaces", [*run, "--format", " md , html ", "--out", "{out}"], None),
        ("out-format-upper", [*run, "--format", "MD", "--out", "{out}"], None),
    ]:
        command(cid, c, argv, files=f)


# ------------------------------------------------------------------------------------------
# 14. run --uncertainty
# ------------------------------------------------------------------------------------------
def monte_carlo() -> None:
    c = "14-monte-carlo"
    unc = sub(SOLID, "  mass: 906 g", "  mass: 906 g +/- 2 g")

    def mc(cid, n, bat=unc, expect="either", extra=(), known="", desc=""):
        case(cid, c, desc or f"run --uncertainty {n}", "bat", bat, expect=expect, known=known,
             commands=[["run", "{f}", "-p", "ncaa-bbcor", *RIGID, "--uncertainty", n, "--json",
                        "--out", "{out}", *extra]])

    for cid, n in [("0", "0"), ("1", "1"), ("2", "2"), ("3", "3"), ("negative", "-5"),
                   ("over-max", "1000001"), ("huge", "9" * 30), ("exponent", "1e3"),
                   ("text", "many"), ("empty", ""), ("fraction", "2.5")]:
        mc(f"mc-n-{cid}", n, expect="valid" if cid in ("2", "3") else "either")
    mc("mc-seed-zero", "3", extra=("--seed", "0"), expect="valid")
    mc("mc-seed-negative", "3", extra=("--seed", "-1"))
    mc("mc-seed-over", "3", extra=("--seed", str(2**63)))
    mc("mc-seed-max", "3", extra=("--seed", str(2**63 - 1)), expect="valid")
    command("mc-seed-without-n", c, ["run", "ash-34", "-p", "ncaa-bbcor", *RIGID, "--seed", "1", "--no-reports"])
    mc("mc-no-uncertainties", "3", bat=SOLID, desc="--uncertainty on a bat that states none")
    odd = [
        ("cg", ("  cg: 429 mm", "  cg: 429 mm +/- 5 mm")),
        ("pivot", ("  pivot: 150 mm", "  pivot: 150 mm +/- 1 mm")),
        ("moi-wide", ("  moi: 0.209 kg*m^2", "  moi: 0.209 kg*m^2 +/- 0.5 kg*m^2")),
        ("moi-uniform-zero", ("  moi: 0.209 kg*m^2", "  moi: 0.209 kg*m^2 +/- 0 kg*m^2 (uniform)")),
        ("mass-percent", ("  mass: 906 g", "  mass: 906 g +/- 1 %")),
        ("mass-tiny", ("  mass: 906 g", "  mass: 906 g +/- 1e-300 g")),
        ("mass-huge", ("  mass: 906 g", "  mass: 906 g +/- 1e308 g")),
        ("mass-normal", ("  mass: 906 g", "  mass: 906 g +/- 1 g (normal)")),
        ("mass-triangular", ("  mass: 906 g", "  mass: 906 g +/- 1 g (triangular)")),
        ("mass-other-unit", ("  mass: 906 g", "  mass: 906 g +/- 0.1 oz")),
        ("mass-pm-spaced", ("  mass: 906 g", "  mass: 906 g + / - 1 g")),
        ("mass-minus-plus", ("  mass: 906 g", "  mass: 906 g -/+ 1 g")),
        ("profile-diameter", ("  - [28.0 in, 2.61 in]", "  - [28.0 in, 2.61 in +/- 0.01 in]")),
        ("knob", ("material: ash-bat", "material: ash-bat\nknob_mass: 10 g +/- 1 g")),
    ]
    for cid, edit in odd:
        mc(f"mc-bat-{cid}", "3", bat=sub(SOLID, *edit), desc=f"--uncertainty 3, bat {edit[1].strip()}")
    hollow = sub(sub(HOLLOW, "  mass: 863 g", "  mass: 863 g +/- 1 g"), "wall:\n  - [0 in, 1.8 mm]\n  - [11 in, 1.8 mm]\n  - [20 in, 2.2 mm]\n  - [22 in, 2.7 mm]\n  - [860 mm, 2.7 mm]", "wall: 2.5 mm +/- 0.1 mm (uniform)")
    mc("mc-hollow-wall-constant", "3", bat=hollow, desc="--uncertainty 3, a constant wall with a uniform uncertainty")
    mc("mc-hollow-hoop", "3", bat=sub(HOLLOW, "  moi: 0.198 kg*m^2", "  moi: 0.198 kg*m^2\n  hoop_frequency: 1800 Hz +/- 2000 Hz"), desc="--uncertainty 3, a hoop frequency uncertainty larger than the value")
    case("mc-ball-cor-near-one", c, "--uncertainty 3, ball COR 0.99 +/- 0.05", "ball",
         sub(BALL, "  - [85 ft/s, 0.546]", "  - [85 ft/s, 0.99 +/- 0.05]"), files={"proto.yaml": corpus.BALL_PROTO},
         commands=[["run", "ash-34", "-p", "{d}/proto.yaml", *RIGID, "--uncertainty", "3", "--json", "--out", "{out}"]])
    mc("mc-two-protocols", "3", desc="--uncertainty 3 under two protocols", extra=("-p", "ncaa-besr"))
    mc("mc-format-md", "3", desc="--uncertainty 3 with Markdown reports only", extra=("--format", "md"))


def build() -> None:
    lab()
    sweeps()
    scale()
    inject()
    outputs()
    monte_carlo()
