"""Physics: pure functions and dataclasses on SI floats and numpy arrays. No I/O, no units."""
