"""From a bat spec to the reconciled bat model the engines read (geometry, reconciliation,
calibration), and what the model shows about itself (mass properties, modes)."""
