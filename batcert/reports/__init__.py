"""Reports: certificates, comparisons and league evaluations as Markdown, HTML and JSON.

Each report has one view (``run_view``, ``compare_view``, ``league_view``) that formats the
result into tables and text (:mod:`batcert.reports.format`, :mod:`batcert.reports.table`); the
Markdown and HTML renderers only lay the view out through their templates, and
:mod:`batcert.reports.write` writes a report's files together, atomically. Reports only read a
result, never compute physics, so they can be regenerated from a saved results JSON.
"""
