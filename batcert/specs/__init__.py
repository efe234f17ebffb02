"""Input specifications: YAML files parsed, unit-converted to SI and validated."""
