"""The contact-law registry (batcert.physics.balls.LAWS): every law provides the interface
(batcert.physics.balls.law.ContactLaw) and the registry says what the callers need to know of
it, so that no caller names a law's class."""

from __future__ import annotations


def test_every_contact_law_provides_the_interface_and_its_registry_flags():
    # the engines, the runner and the uncertainty ask the registry (closed_form_cor,
    # cor_parameters) and the law's methods, never its class
    from batcert.physics.balls import LAWS
    from batcert.physics.balls.law import ContactLaw

    wanted = [n for n in dir(ContactLaw) if not n.startswith("_")]
    for name, entry in LAWS.items():
        assert entry.law.name == name
        for method in wanted:
            assert hasattr(entry.law, method), (name, method)
        if entry.closed_form_cor:
            assert hasattr(entry.law, "cor_at"), name
