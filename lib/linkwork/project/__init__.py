"""The layer that knows the project's papers: the whole config and the published numbers validated before any job
(``validate``, ``published``) and the README's findings (``readme``).  It imports the papers and the toolkit below
them (``linkwork.pipeline``), and nothing imports it but the workflow (the Snakefile, the rules' studies) and the tests:
every import in the library points downward (tests/test_imports.py)."""
