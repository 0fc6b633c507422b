#!/usr/bin/env python3
"""Offline link check of a built HTML site: every relative href and src of every page must name
a file of the site (and an anchor of it, when it names one). Remote links are not followed.
Usage: check_links.py HTML_DIR"""
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit


class Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.links, self.ids = [], set()

    def handle_starttag(self, tag, attrs):
        for name, value in attrs:
            if name == "id" and value:
                self.ids.add(value)
            if name in ("href", "src") and value:
                self.links.append(value)


def main():
    site = Path(sys.argv[1]).resolve()
    pages = {}
    for page in site.rglob("*.html"):
        parser = Links()
        parser.feed(page.read_text(encoding="utf-8"))
        pages[page] = parser
    broken = []
    for page, parser in sorted(pages.items()):
        for link in parser.links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc or link.startswith(("mailto:", "javascript:")):
                continue
            target = (page.parent / unquote(parts.path)).resolve() if parts.path else page
            if not target.exists():
                broken.append(f"{page.relative_to(site)}: {link} (no such file)")
            elif parts.fragment and target in pages and parts.fragment not in pages[target].ids:
                broken.append(f"{page.relative_to(site)}: {link} (no such anchor)")
    for b in broken:
        print("broken link:", b, file=sys.stderr)
    if broken:
        sys.exit(1)
    print(f"[flexgait] links: {sum(len(p.links) for p in pages.values())} checked in {len(pages)} pages, none broken")


if __name__ == "__main__":
    main()
