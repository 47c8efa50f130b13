"""What a reader of a rendered report or the README's findings meets in prose: code names (snake_case
identifiers), config key paths and unrendered format templates.  Tables that list config keys are exempt when
they say so in a header cell ('config key'); code and preformatted blocks are exempt; the provenance section's
attribute names are shown as such."""

from __future__ import annotations

import html as _html
import re

#: Provenance attribute names every report shows in its provenance table, as names.
PROVENANCE = {"config_sha256", "git_commit", "linkwork_version", "paper_id", "config_json", "study"}
SNAKE = re.compile(r"(?<![\w./-])[a-z][a-z0-9]*_[a-z0-9_]*[a-z0-9](?![\w/-])")
KEY_PATH = re.compile(r"(?<![\w/])[a-z][a-z0-9_]*(?:\.[a-z][a-z0-9_]*)+(?![\w/])")
TEMPLATE = re.compile(r"\{[^{}\n]{0,80}(?:\.sel\(|:\.?\d*[fgeE%]\}|float\(|int\(|\[['\"])[^{}\n]{0,80}\}?")


def _marked_table(table_html: str) -> bool:
    head = re.search(r"<thead.*?</thead>", table_html, re.S | re.I)
    return bool(head and "config key" in head.group(0).lower())


def visible_text(page: str) -> str:
    """The text of an HTML page a reader sees as prose: without style, script, code, pre, embedded images and
    the tables marked as config-key listings."""
    page = re.sub(r"data:image[^\"')]+", "", page)
    page = re.sub(r"<(style|script|pre|code)\b.*?</\1>", " ", page, flags=re.S | re.I)
    page = re.sub(
        r"<table\b.*?</table>", lambda m: " " if _marked_table(m.group(0)) else m.group(0), page, flags=re.S | re.I
    )
    return _html.unescape(re.sub(r"<[^>]+>", " ", page))


def leaks(text: str) -> list[str]:
    """Code names, config key paths and unrendered templates in ``text`` (already plain prose)."""
    found = [m for m in SNAKE.findall(text) if m not in PROVENANCE]
    found += [
        m
        for m in KEY_PATH.findall(text)
        if "_" in m and not m.endswith((".nc", ".html", ".yaml", ".py", ".csv", ".json"))
    ]
    found += TEMPLATE.findall(text)
    return sorted(set(found))


def page_title(page: str) -> str:
    m = re.search(r"<title>(.*?)</title>", page, re.S | re.I)
    return _html.unescape(m.group(1)).strip() if m else ""
