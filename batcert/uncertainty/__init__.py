"""Predicted verdicts with uncertainty: the stated uncertainties of a bat's and a ball's inputs
propagated through the engine by Monte Carlo (``batcert run --uncertainty N``)."""
