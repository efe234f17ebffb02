"""Design studies: a protocol run on variants of a bat or a test (docs/sweeps.md).

``variants`` (the registry of parameters), ``sweep`` (plans, chunks and rows), ``execute`` (where
chunks run, and the journal for resuming), ``design`` (the parameter value that meets a limit)
and ``study_figures`` (a study file's figures).
"""
