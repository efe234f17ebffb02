"""batcert: bat certification from YAML specs with a reduced-order ball-bat impact engine."""

__version__ = "0.2.0"
