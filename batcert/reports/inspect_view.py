"""What ``batcert inspect`` shows of a bat or a ball, as blocks for the terminal: each a title
with either key-value rows or a :class:`~batcert.reports.table.Table` (the console prints
them, :func:`batcert.console.blocks`)."""

from __future__ import annotations

from typing import Any

from batcert.reports.format import flatten
from batcert.reports.table import Table
from batcert.units import show

# a titled block: key-value rows, or a table
Block = tuple[str, "list[tuple[str, Any]] | Table"]


def bat_view(info: dict) -> list[Block]:
    """``inspect``'s view of a bat (:func:`batcert.commands.inspect.inspect_bat`'s dict)."""
    out: list[Block] = []
    g = info["geometry"]
    out.append((f"{info['name']}  ({info['construction']}, {info['material']})", [
        ("length", str(show(info["length"], "length"))),
        ("pivot (from knob)", str(show(info["pivot"], "length"))),
        ("mass", f"{show(info['mass'], 'mass')}   geometry {show(g['mass'], 'mass')}"),
        ("CG (from pivot)", f"{show(info['cg'], 'length')}   geometry {show(g['cg'], 'length')}"),
        ("MOI about pivot", f"{show(info['moi_pivot'], 'moi', 4)}   geometry "
                            f"{show(g['moi_pivot'], 'moi', 4)}"),
        ("COP (from pivot)", str(show(info["cop"], "length"))),
        ("barrel diameter", str(show(info["barrel_diameter"], "length", 4))),
        ("reconciliation", info["reconciliation"]["description"]),
    ]))
    if info.get("modes_hz"):
        rows = []
        for j, f in enumerate(info["modes_hz"][:6]):
            nodes = info["mode_nodes"][j] if j < len(info["mode_nodes"]) else []
            rows.append([str(j + 1), f"{f:.0f}", ", ".join(f"{z * 100:.1f}" for z in nodes)])
        out.append(("free-free bending modes",
                    Table(["mode", "frequency [Hz]", "nodes [cm from knob]"], rows,
                          [False, True, True])))
    if info.get("layup"):
        out.append(("layup (walls innermost first, plies inside out)", _layup(info["layup"])))
    if info.get("barrel"):
        out.append(("barrel (shell of revolution)", barrel_rows(info["barrel"])))
    return out


def _hz(x: Any) -> str:
    return "\u2014" if x is None else f"{x:.0f} Hz"


# the barrel block's rows: its key in inspect's JSON, the label, how the value reads
_BARREL = (
    ("start", "starts (from knob)", lambda x: str(show(x, "length"))),
    ("end", "ends (from knob)", lambda x: str(show(x, "length"))),
    ("tip_end", "tip end", str),
    ("outer_diameter", "outer diameter", lambda x: str(show(x, "length", 4))),
    ("wall", "wall thickness", lambda x: f"{x * 1e3:.2f} mm ({x / 0.0254:.4f} in)"),
    ("hoop_frequency_hz", "hoop frequency", _hz),
    ("measured_hoop_frequency_hz", "hoop frequency, measured", _hz),
    ("ring_frequency_hz", "ring frequency", _hz),
    ("stiffness_scale", "stiffness scale", lambda x: f"x{x:.3f}"),
    ("mass_scale", "mass scale", lambda x: f"x{x:.3f}"),
    ("calibrated", "calibrated by a measurement", lambda x: "yes" if x else "no"),
)


def barrel_rows(barrel: dict[str, Any]) -> list[tuple[str, Any]]:
    """The barrel block: each value labelled with its unit (``inspect --json`` keeps SI);
    the shell's modes by circumferential order; a key not listed here as it is."""
    known = {key for key, _, _ in _BARREL} | {"modes_hz"}
    rows = [(label, read(barrel[key])) for key, label, read in _BARREL if key in barrel]
    for order, freqs in (barrel.get("modes_hz") or {}).items():
        rows.append((f"shell modes {order.replace('n=', 'n = ')}",
                     ", ".join(f"{f:.0f}" for f in freqs) + " Hz"))
    rows += [(k, v) for k, v in flatten({k: v for k, v in barrel.items() if k not in known})]
    return rows


def _layup(spans: list[dict]) -> Table:
    """One row per span: where, its walls' plies, thickness, mass per area, and the hoop and
    axial stiffnesses that matter most (``D22`` bends the barrel oval, ``A11`` stretches it
    along the bat)."""
    rows = []
    for s in spans:
        walls = " | ".join(", ".join(
            f"{p['material']} {'±' if p['balanced'] else ''}{p['angle_deg']:g}° "
            f"{p['thickness'] * 1e3:g}" for p in wall) for wall in s["walls"])
        rows.append([f"{s['start'] * 100:.1f}-{s['end'] * 100:.1f}", walls,
                     f"{s['thickness'] * 1e3:.2f}", f"{s['areal_density']:.2f}",
                     f"{s['d'][1][1]:.3g}", f"{s['a'][0][0]:.3g}"])
    return Table(["span [cm]", "walls: plies (mm)", "t [mm]", "kg/m²", "D22 [N m]",
                  "A11 [N/m]"], rows, [False, False, True, True, True, True])


_TEST_UNITS = {"cor": ("", 1.0, "{:.3f}"), "cylinder_cor": ("", 1.0, "{:.3f}"),
               "peak_force": ("kN", 1e-3, "{:.2f}"), "collision_time": ("ms", 1e3, "{:.3f}"),
               "contact_time": ("ms", 1e3, "{:.3f}"), "compression": ("N", 1.0, "{:.0f}")}


def ball_view(info: dict) -> list[Block]:
    """``inspect``'s view of a ball (:func:`batcert.commands.inspect.inspect_ball`'s dict)."""
    out: list[Block] = []
    rows = [("mass", str(show(info["mass"], "mass", 4))),
            ("radius", f"{info['radius'] * 1e3:.1f} mm"), ("contact law", info["law"]["summary"])]
    fit = info.get("fit")
    if fit:
        u, held = fit["parameter_uncertainty"], fit.get("held", [])
        shown = [f"u(a) = {u['exponent']:.2g}" if "exponent" not in held else "",
                 f"u(tau) = {u['relaxation_time'] * 1e6:.2g} us"
                 if "relaxation_time" not in held else "",
                 f"u(tau_f) = {u['fast_relaxation_time'] * 1e6:.2g} us"
                 if "fast_relaxation_time" in u and "fast_relaxation_time" not in held else ""]
        text = (f"chi-square {fit['chi2']:.2f} for {fit['dof']} degrees of freedom"
                + "".join(f"; {x}" for x in shown if x))
        if held:
            text += f"; held as given: {', '.join(h.replace('_', ' ') for h in held)}"
        rows.append(("fitted to the tests", text))
    lot = info.get("lot_calibration")
    if lot:
        rows.append(("lot CALIBRATED on a reference bat",
                     f"{lot['bat']} under {lot['protocol']}: measured {lot['value']:.3f} +/- "
                     f"{lot['uncertainty']:.3f}, the model {lot['model_value']:.4f} with every COR "
                     f"test moved by {lot['shift']:+.2f} +/- {lot['u_shift']:.2f} of its standard "
                     "uncertainties; the law above and every run use this lot, and the "
                     "reference bat is no longer a validation"))
    out.append((info["name"], rows))
    if info["tests"]:
        table = []
        for t in info["tests"]:
            unit, factor, f = _TEST_UNITS[t["test"]]
            cond = (f"{t['condition'] * 1e3:.2f} mm" if t["test"] == "compression"
                    else f"{t['condition']:g} m/s")
            if t["surface_diameter"]:
                cond += f", {t['surface_diameter'] * 1e3:.1f} mm cylinder"
            measured = f.format(t["value"] * factor)
            if t["uncertainty"]:
                measured += " +/- " + f.format(t["uncertainty"] * factor)
            table.append([t["test"].replace("_", " "), cond, f"{measured} {unit}".strip(),
                          f"{f.format(t['model'] * factor)} {unit}".strip(),
                          "" if t["residual"] is None else f"{t['residual']:+.2f}"])
        out.append(("ball tests (the uncertainty is one standard uncertainty)",
                    Table(["test", "condition", "measured", "law", "(law - measured) / u"],
                          table, [False, False, True, True, True])))
    out += _speed_tables(info, lot)
    return out


def _speed_tables(info: dict, lot: dict | None) -> list[Block]:
    """The ball against a rigid flat wall (the tested balls' COR beside a calibrated lot's) and
    a rigid cylinder, against impact speed."""
    out: list[Block] = []
    # the 99 %-impulse times are in the JSON (and the tests' table): 80 columns
    rows = [[f"{v:g}", f"{e:.3f}", f"{ct * 1e3:.2f}", f"{u * 1e3:.1f}", f"{us * 1e3:.1f}",
             f"{f / 1e3:.1f}"]
            for v, e, ct, u, us, f in zip(info["speeds"], info["cor"], info["contact_time"],
                                          info["max_compression"],
                                          info["separation_compression"], info["peak_force"],
                                          strict=True)]
    head = ["v [m/s]", "COR", "contact [ms]", "squeeze [mm]", "left [mm]", "F max [kN]"]
    if lot:  # the tested balls' COR beside the lot's
        head.insert(2, "tested COR")
        for row, e in zip(rows, lot["tested_cor"], strict=True):
            row.insert(2, f"{e:.3f}")
    out.append(("against a rigid flat wall" + (" (the calibrated lot)" if lot else ""),
                Table(head, rows, [True] * len(head))))
    cyl = info.get("cylinder")
    if cyl:
        rows = [[f"{v:g}", f"{e:.3f}", f"{ct * 1e3:.2f}", f"{u * 1e3:.1f}", f"{f / 1e3:.1f}"]
                for v, e, ct, u, f in zip(info["speeds"], cyl["cor"], cyl["contact_time"],
                                          cyl["max_compression"], cyl["peak_force"], strict=True)]
        out.append((f"against a rigid cylinder {cyl['diameter'] * 1e3:.1f} mm across "
                    "(a 2 5/8 in barrel, fixed)" + (", the calibrated lot" if lot else ""),
                    Table(["v [m/s]", "COR", "contact [ms]", "squeeze [mm]", "F max [kN]"],
                          rows, [True] * 5)))
    return out
