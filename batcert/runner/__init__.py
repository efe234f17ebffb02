"""Protocol runner: conditions, impact-location rules, sweet-spot search, metrics and verdicts."""
