"""batcert's release number (one home: the package, the wheel's metadata and every result's
``batcert_version`` read it here)."""

__version__ = "0.2.0"
