"""Checks of the reproduction report's HTML (index.html), with Python's html.parser."""
import html.parser
import os
import re

VOID_ELEMENTS = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "wbr"}


class PageParser(html.parser.HTMLParser):
    """Collects tag-nesting problems, the tables' rows (cell texts), the images and the runs' figures."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.open_tags = []
        self.problems = []
        self.tables = []        # each a list of rows, each a list of (tag, text, row id)
        self.images = []        # src of every <img>
        self.run_figures = {}   # h3 id -> number of <img> after it
        self.row = None
        self.cell = None
        self.run = None
        self.figures = []       # each {"img": src or None, "caption": text or None}
        self.figure = None
        self.caption = None

    def handle_starttag(self, tag, attrs):
        attributes = dict(attrs)
        if tag not in VOID_ELEMENTS:
            self.open_tags.append(tag)
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self.row = {"id": attributes.get("id"), "cells": []}
        elif tag in ("td", "th"):
            self.cell = {"tag": tag, "text": ""}
        elif tag == "br" and self.cell is not None:
            self.cell["text"] += "\n"
        elif tag == "figure":
            self.figure = {"img": None, "caption": None}
        elif tag == "figcaption" and self.figure is not None:
            self.caption = ""
        elif tag == "img":
            if self.figure is not None:
                self.figure["img"] = attributes.get("src")
            else:
                self.problems.append(f"line {self.getpos()[0]}: <img> outside a <figure> (no caption)")
            self.images.append(attributes.get("src"))
            if self.run is not None:
                self.run_figures[self.run] += 1
        elif tag == "h3":
            self.run = attributes.get("id")
            self.run_figures[self.run] = 0

    def handle_endtag(self, tag):
        if tag in VOID_ELEMENTS:
            return
        if not self.open_tags or self.open_tags[-1] != tag:
            self.problems.append(f"line {self.getpos()[0]}: </{tag}> closes {self.open_tags[-1:] or 'nothing'}")
            if tag in self.open_tags:
                del self.open_tags[len(self.open_tags) - 1 - self.open_tags[::-1].index(tag):]
            return
        self.open_tags.pop()
        if tag == "figcaption" and self.figure is not None:
            self.figure["caption"] = self.caption
            self.caption = None
        elif tag == "figure" and self.figure is not None:
            self.figures.append(self.figure)
            self.figure = None
        elif tag in ("td", "th") and self.row is not None:
            self.row["cells"].append(self.cell)
            self.cell = None
        elif tag == "tr" and self.tables:
            self.tables[-1].append(self.row)
            self.row = None

    def handle_data(self, data):
        if self.caption is not None:
            self.caption += data
        if self.cell is not None:
            self.cell["text"] += data


def parse_page(path):
    parser = PageParser()
    with open(path, encoding="utf-8") as f:
        parser.feed(f.read())
    parser.close()
    if parser.open_tags:
        parser.problems.append(f"unclosed at the end: {parser.open_tags}")
    return parser


def has_number(text):
    return re.search(r"\d", text) is not None and re.search(r"\bnan\b|no result", text) is None


def table_problems(page):
    """Every table: a header with an Ours column, and every row a number in it."""
    problems = []
    for index, table in enumerate(page.tables):
        header = [c["text"] for c in table[0]["cells"]] if table else []
        if "Ours" not in header:
            problems.append(f"table {index + 1}: no Ours column in the header {header}")
            continue
        ours = header.index("Ours")
        if len(table) < 2:
            problems.append(f"table {index + 1}: no rows")
        for row in table[1:]:
            cells = row["cells"]
            if len(cells) != len(header):
                problems.append(f"row {row['id']}: {len(cells)} cells, the header has {len(header)}")
            elif not has_number(cells[ours]["text"]):
                problems.append(f"row {row['id']}: no number in Ours: {cells[ours]['text']!r}")
            elif "Verdict (tolerance)" in header:
                verdict = cells[header.index("Verdict (tolerance)")]["text"].split("\n")
                if verdict[0] not in ("reproduced", "differs") or len(verdict) < 2 or not verdict[1].strip():
                    problems.append(f"row {row['id']}: verdict {verdict!r}, not reproduced/differs and a tolerance")
        if "Verdict (tolerance)" not in header:
            problems.append(f"table {index + 1}: no Verdict (tolerance) column in the header {header}")
    return problems


def figure_problems(page):
    """Every figure a caption naming at least one unit in brackets ("[rad]")."""
    return [f"figure {f['img']!r}: caption {f['caption']!r} names no unit in brackets"
            for f in page.figures if not f["caption"] or not re.search(r"\[[^\]]+\]", f["caption"])]


def image_problems(page, page_dir):
    return [f"<img src={src!r}>: no such file" for src in page.images
            if not src or not os.path.isfile(os.path.join(page_dir, src))]


def page_problems(path):
    """Every problem of the page at `path`: nesting, tables (a number and a verdict in every row),
    figures (each captioned with units), images."""
    page = parse_page(path)
    return page.problems + table_problems(page) + figure_problems(page) + image_problems(page, os.path.dirname(path))


def table_rows(path):
    """{row id: [cell texts]} of every table row of the page."""
    return {row["id"]: [c["text"] for c in row["cells"]]
            for table in parse_page(path).tables for row in table[1:]}
