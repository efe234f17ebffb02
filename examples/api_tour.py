"""A tour of batcert as a library: a bat's predicted BBCOR, a sweep of the pitch speed, and a
comparison of wood and aluminium under the proposed method, through the API alone (docs/api.md).

Run it with ``python examples/api_tour.py`` (the rigid engine: a few seconds).
"""

from __future__ import annotations

import batcert


def main() -> None:
    ash = batcert.load_bat("ash-34")
    result = batcert.run(ash, "ncaa-bbcor", engine="rigid")
    print(f"{result.bat}: predicted BBCOR {result.value:.4f} against the limit {result.limit}, "
          f"{result.verdict} (model; {result.model_offset})")

    sweep = batcert.sweep("aluminium-34", "ncaa-bbcor", ["pitch_speed=50m/s:70m/s:3"],
                          engine="rigid")
    print("BBCOR over the pitch-speed sweep:")
    for speed, value in zip(sweep.values, sweep.series["value"], strict=True):
        print(f"  {speed:5.1f} m/s  {value:.4f}")

    comparison = batcert.compare(["ash-34", "aluminium-34"], ["proposed"], engine="rigid")
    for p in comparison.protocols:
        print(f"comparison under {p.protocol}:")
        for bat, value in p.aggregate_value.items():
            print(f"  {bat:32s} {value:.4f}")


if __name__ == "__main__":
    main()
