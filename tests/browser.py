"""Open rendered reports in headless Chromium (Debian's chromium, driven by playwright): does the page load,
does every image decode, is there a console error?  Used by tests/test_workflow.py; `python tests/browser.py
results/reports` checks a folder by hand and writes the screenshots beside the pages' folder."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync"]


def chromium() -> str:
    """The system Chromium (apt-get install chromium)."""
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    if path is None:
        raise RuntimeError("Chromium is not installed: `apt-get install chromium` (make test installs it where it can)")
    return path


def check_pages(pages: list[Path], screenshots: Path) -> dict[str, dict]:
    """Per page: console errors, page errors, images that did not decode, and a full-page screenshot."""
    from playwright.sync_api import sync_playwright

    screenshots.mkdir(parents=True, exist_ok=True)
    out = {}
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium(), args=CHROMIUM_ARGS)
        for page_path in pages:
            page = browser.new_page(viewport={"width": 1280, "height": 900})
            errors: list[str] = []
            page.on("console", lambda msg, errors=errors: errors.append(msg.text) if msg.type == "error" else None)
            page.on("pageerror", lambda exc, errors=errors: errors.append(str(exc)))
            page.on("requestfailed", lambda req, errors=errors: errors.append(f"request failed: {req.url[:120]}"))
            response = page.goto(page_path.resolve().as_uri(), wait_until="load")
            images = page.evaluate(
                "Array.from(document.images).map(i => [i.complete && i.naturalWidth > 0, i.naturalWidth,"
                " i.naturalHeight])"
            )
            page.screenshot(path=str(screenshots / f"{page_path.stem}.png"), full_page=True)
            out[page_path.name] = {
                "loaded": response is not None and response.ok,
                "errors": errors,
                "images": len(images),
                "broken_images": sum(1 for ok, *_ in images if not ok),
                "text": page.inner_text("body")[:200],
            }
            page.close()
        browser.close()
    return out


if __name__ == "__main__":
    folder = Path(sys.argv[1])
    for name, result in check_pages(sorted(folder.glob("*.html")), folder.parent / "screenshots").items():
        print(name, {k: v for k, v in result.items() if k != "text"})
