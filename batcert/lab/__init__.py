"""Lab data: measured hits on a pivoted bat, reduced to certified values (docs/lab-reduction.md).

``session`` loads a session (its bat, ball lot, pivot and hits) and reduces every hit with
:func:`batcert.methods.reduction.reduce_hits`. The protocol's rule, uncertainty and decision
rules build on it (issue 12).
"""
