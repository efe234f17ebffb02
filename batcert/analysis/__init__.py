"""Analyses over run results: bat comparison, study claims, league rules (pure: results in,
results out; no I/O)."""
