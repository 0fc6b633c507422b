"""python/report.py on tiny hand-made run trees: values from JSON and CSV, escaping, failures.

Run from tests/report with FLEXGAIT_SOURCE set to the source tree (ctest does both).
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

import yaml

import page_check

SOURCE = os.environ.get("FLEXGAIT_SOURCE", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
REPORT = os.path.join(SOURCE, "python", "report.py")
sys.path.insert(0, os.path.join(SOURCE, "python"))
import report  # noqa: E402

REFERENCES = {
    "sections": [{"id": "demo", "title": "Demo study", "reference_header": "Paper"}],
    "rows": [
        {
            "id": "scalar",
            "section": "demo",
            "run": "run-a",
            "values": {
                "k": {"file": "summary.json", "key": "/k_fit"},
                "steps": {"file": "summary.json", "key": "/nested/steps", "type": "integer"},
                "name": {"file": "summary.json", "key": "/name", "type": "text"},
            },
            "label": "Fit over {{ steps }} steps",
            "ours": "{{ k|fmt('.2f') }} Nm/rad ({{ name }})",
            "reference": "≈ 1000 Nm/rad",
            "source": "thesis Fig. 12",
            "verdict": {"reproduced": "(k - 1000)|abs <= 100", "tolerance": "±10 % of 1000 Nm/rad"},
        },
        {
            "id": "table",
            "section": "demo",
            "run": "run-b",
            "values": {
                "points": {"file": "points.csv",
                           "columns": {"mu": "number", "gait": "text", "stable": "bool", "lam": "optional-number"}},
            },
            "label": "Points ({{ points|selectattr('stable')|list|length }} stable)",
            "ours": "{% for p in points %}{% if not loop.first %}<br>{% endif %}μ = {{ p.mu|fmt('.2f') }}: "
                    "{{ p.gait }}, |λ| {{ p.lam|fmt('.3f') }}{% endfor %}",
            "reference": "four behaviours",
            "source": "paper, abstract",
            "verdict": {"reproduced": "points|selectattr('stable')|list|length == 4", "tolerance": "four stable"},
        },
    ],
    "figures": {"plot.png": "what the plot shows [rad]"},
}

SUMMARY = {"k_fit": 999.5, "nested": {"steps": 12}, "name": "bench"}
POINTS_CSV = 'mu,gait,stable,lam\n0.1,"slip, then stick",true,0.9\n0.6,stick,false,\n'


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


class RunTree:
    """A run root with reproduce.json, run-a/summary.json, run-b/points.csv and a references file."""

    def __init__(self, root, references=None, summary=None, points_csv=POINTS_CSV, exit_codes=None):
        self.root = root
        self.references = os.path.join(root, "references.yaml")
        exit_codes = exit_codes or {}
        runs = [{"dir": d, "title": f"Run <{d}>", "command": f"flexgait {d}", "exit_code": exit_codes.get(d, 0)}
                for d in ("run-a", "run-b")]
        write(os.path.join(root, "reproduce.json"), json.dumps({"quick": True, "runs": runs}))
        write(self.references, yaml.safe_dump(references or REFERENCES, allow_unicode=True))
        if summary is not None or "run-a" not in exit_codes:
            write(os.path.join(root, "run-a", "summary.json"), json.dumps(SUMMARY if summary is None else summary))
        write(os.path.join(root, "run-b", "points.csv"), points_csv)
        write(os.path.join(root, "run-b", "plot.png"), "not really a PNG")

    def render(self):
        return subprocess.run([sys.executable, REPORT, self.root, "--references", self.references],
                              capture_output=True, text=True)

    @property
    def page(self):
        return os.path.join(self.root, "index.html")

    def page_text(self):
        with open(self.page, encoding="utf-8") as f:
            return f.read()


class RenderTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def test_values_from_json_and_csv_with_quoted_fields(self):
        tree = RunTree(self.tmp.name)
        result = tree.render()
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(page_check.page_problems(tree.page), [])
        rows = page_check.table_rows(tree.page)
        self.assertEqual(rows["scalar"][:2], ["Fit over 12 steps", "999.50 Nm/rad (bench)"])
        self.assertEqual(rows["table"][0], "Points (1 stable)")
        self.assertEqual(rows["table"][1], "μ = 0.10: slip, then stick, |λ| 0.900\nμ = 0.60: stick, |λ| n/a")
        self.assertIn('<img src="run-b/plot.png"', tree.page_text())
        self.assertFalse([f for f in os.listdir(tree.root) if f.startswith(".index.html")], "temporary file left")

    def test_every_row_has_a_verdict_with_its_tolerance_and_every_figure_a_caption(self):
        # scalar: |999.5 - 1000| <= 100 holds; table: 1 of 2 points stable, not 4.
        tree = RunTree(self.tmp.name)
        result = tree.render()
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(page_check.page_problems(tree.page), [])
        rows = page_check.table_rows(tree.page)
        self.assertEqual(rows["scalar"][3], "reproduced\n±10 % of 1000 Nm/rad")
        self.assertEqual(rows["table"][3], "differs\nfour stable")
        self.assertIn("<figcaption>plot.png: what the plot shows [rad]</figcaption>", tree.page_text())

    def test_a_figure_without_a_caption_or_a_verdict_that_is_not_a_boolean_fails(self):
        references = dict(REFERENCES, figures={"other.png": "x [m]"})
        tree = RunTree(self.tmp.name, references=references)
        result = tree.render()
        self.assertEqual(result.returncode, 1)
        self.assertIn("run-b/plot.png: no caption", result.stderr)
        rows = [dict(REFERENCES["rows"][0], verdict={"reproduced": "k", "tolerance": "t"}), REFERENCES["rows"][1]]
        tree = RunTree(self.tmp.name, references=dict(REFERENCES, rows=rows))
        result = tree.render()
        self.assertEqual(result.returncode, 1)
        self.assertIn("row scalar (run-a): verdict: 999.5 is not true or false", result.stderr)
        rows = [dict(REFERENCES["rows"][0], verdict={"reproduced": "k > 1"}), REFERENCES["rows"][1]]
        self.assertIn("row scalar: verdict needs exactly", "".join(report.check_references(dict(REFERENCES, rows=rows))))

    def test_every_file_written_is_world_readable(self):
        # index.html and every figure go through atomic_write.temporary_beside, whose mkstemp makes
        # 0600 files: a report copied to a web server must be readable by it, so 0644 exactly
        # (the C++ side's atomic files are 0644 too), whatever the umask.
        sys.path.insert(0, os.path.join(SOURCE, "python"))
        import atomic_write
        old = os.umask(0o077)
        try:
            with atomic_write.temporary_beside(self.tmp.name, "figure.png") as tmp:
                with open(tmp, "wb") as f:
                    f.write(b"png")
        finally:
            os.umask(old)
        self.assertEqual(os.stat(os.path.join(self.tmp.name, "figure.png")).st_mode & 0o777, 0o644)
        tree = RunTree(self.tmp.name)
        result = tree.render()
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(os.stat(tree.page).st_mode & 0o777, 0o644)

    def test_contents_link_every_section_and_run_and_rows_link_their_run(self):
        tree = RunTree(self.tmp.name)
        result = tree.render()
        self.assertEqual(result.returncode, 0, result.stderr)
        page = tree.page_text()
        contents = page[page.index('<nav id="contents">'):page.index("</nav>")]
        for target in ("demo", "runs", "run-a", "run-b"):
            self.assertIn(f'href="#{target}"', contents)
            self.assertIn(f'id="{target}"', page)
        # A row links its run's entry on the page (command and figures), not a directory listing.
        self.assertIn('<a href="#run-a">run-a</a>', page)
        self.assertNotIn('href="run-a/"', page)

    def test_a_rendered_walk_shows_its_video_not_its_frames(self):
        tree = RunTree(self.tmp.name)
        write(os.path.join(tree.root, "run-b", "video.mp4"), "not really an MP4")
        write(os.path.join(tree.root, "run-b", "frames", "frame_00000.png"), "not really a PNG")
        result = tree.render()
        self.assertEqual(result.returncode, 0, result.stderr)
        text = tree.page_text()
        self.assertIn('<video src="run-b/video.mp4" controls', text)
        self.assertNotIn("frame_00000.png", text)
        self.assertEqual(page_check.page_problems(tree.page), [])

    def test_a_run_with_a_replay_links_it(self):
        tree = RunTree(self.tmp.name)
        write(os.path.join(tree.root, "run-b", "replay.html"), "<!doctype html><title>replay</title>")
        result = tree.render()
        self.assertEqual(result.returncode, 0, result.stderr)
        text = tree.page_text()
        self.assertIn('<a href="run-b/replay.html">', text)
        self.assertNotIn("run-a/replay.html", text)
        self.assertEqual(page_check.page_problems(tree.page), [])

    def test_the_first_replay_of_each_study_is_embedded_the_others_linked(self):
        tree = RunTree(self.tmp.name)
        for run in ("run-a", "run-b"):
            write(os.path.join(tree.root, run, "replay.html"), "<!doctype html><title>replay</title>")
        result = tree.render()
        self.assertEqual(result.returncode, 0, result.stderr)
        text = tree.page_text()
        self.assertEqual(text.count("<iframe "), 1)  # run-a and run-b are one study ("run")
        self.assertIn('<iframe src="run-a/replay.html"', text)
        self.assertIn('<a href="run-b/replay.html">', text)
        self.assertEqual(page_check.page_problems(tree.page), [])

    def test_values_and_titles_are_escaped(self):
        summary = dict(SUMMARY, name="<script>alert(1)</script>")
        points = 'mu,gait,stable,lam\n0.1,"<script>x</script> & ""quoted""",true,0.9\n'
        tree = RunTree(self.tmp.name, summary=summary, points_csv=points)
        result = tree.render()
        self.assertEqual(result.returncode, 0, result.stderr)
        text = tree.page_text()
        self.assertNotIn("<script", text)
        self.assertIn("&lt;script&gt;alert(1)&lt;/script&gt;", text)
        self.assertIn("&lt;script&gt;x&lt;/script&gt; &amp; &#34;quoted&#34;", text)
        self.assertIn("Run &lt;run-a&gt;", text)
        self.assertEqual(page_check.page_problems(tree.page), [])

    def test_missing_key_fails_naming_run_file_and_key(self):
        summary = {k: v for k, v in SUMMARY.items() if k != "k_fit"}
        tree = RunTree(self.tmp.name, summary=summary)
        write(tree.page, "the previous report")
        result = tree.render()
        self.assertEqual(result.returncode, 1)
        self.assertIn("run-a/summary.json: no key /k_fit", result.stderr)
        self.assertIn("row scalar", result.stderr)
        self.assertEqual(tree.page_text(), "the previous report")

    def test_missing_column_fails_naming_it(self):
        tree = RunTree(self.tmp.name, points_csv="mu,gait,lam\n0.1,slip,0.9\n")
        result = tree.render()
        self.assertEqual(result.returncode, 1)
        self.assertIn("run-b/points.csv: no column stable", result.stderr)
        self.assertFalse(os.path.exists(tree.page))

    def test_value_of_the_wrong_type_fails(self):
        tree = RunTree(self.tmp.name, summary=dict(SUMMARY, k_fit="fast"))
        result = tree.render()
        self.assertEqual(result.returncode, 1)
        self.assertIn("run-a/summary.json key /k_fit: 'fast' is not number", result.stderr)

    def test_empty_number_cell_fails(self):
        tree = RunTree(self.tmp.name, points_csv="mu,gait,stable,lam\n,slip,true,0.9\n")
        result = tree.render()
        self.assertEqual(result.returncode, 1)
        self.assertIn("run-b/points.csv, row 1, column mu", result.stderr)

    def test_every_problem_is_reported_at_once(self):
        tree = RunTree(self.tmp.name, summary={}, points_csv="mu\n")
        result = tree.render()
        self.assertEqual(result.returncode, 1)
        self.assertIn("row scalar", result.stderr)
        self.assertIn("row table", result.stderr)

    def test_row_of_a_failed_run_says_no_result(self):
        tree = RunTree(self.tmp.name, exit_codes={"run-a": 1})
        result = tree.render()
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = page_check.table_rows(tree.page)
        self.assertEqual(rows["scalar"][1], "no result: the run exited with 1")
        self.assertIn("exit code 1", tree.page_text())

    def test_template_using_an_undeclared_value_fails(self):
        references = yaml.safe_load(yaml.safe_dump(REFERENCES))
        references["rows"][0]["ours"] = "{{ k|fmt('.2f') }} (R² {{ r_squared|fmt('.3f') }})"
        tree = RunTree(self.tmp.name, references=references)
        result = tree.render()
        self.assertEqual(result.returncode, 1)
        self.assertIn("row scalar (run-a): 'r_squared' is undefined", result.stderr)

    def test_yaml_boolean_value_name_is_rejected(self):
        references = yaml.safe_load(yaml.safe_dump(REFERENCES))
        references["rows"][0]["values"][True] = {"file": "summary.json", "key": "/k_fit"}
        tree = RunTree(self.tmp.name, references=references)
        result = tree.render()
        self.assertEqual(result.returncode, 1)
        self.assertIn("is not an identifier", result.stderr)


class ReferencesFileTest(unittest.TestCase):
    """The shipped data/report/references.yaml."""

    def setUp(self):
        self.path = os.path.join(SOURCE, "data", "report", "references.yaml")

    def test_structure_is_valid(self):
        with open(self.path, encoding="utf-8") as f:
            self.assertEqual(report.check_references(yaml.safe_load(f)), [])

    def test_every_row_names_its_source_and_reads_only_files_the_commands_write(self):
        written_by_plot_scripts = (".png", ".txt")
        for row in report.load_references(self.path)["rows"]:
            self.assertTrue(row["source"].strip(), row["id"])
            self.assertTrue(row["reference"].strip(), row["id"])
            # The papers are cited, not files or tickets a reader of the report does not have.
            for text in (row["source"], row["reference"], row["verdict"]["tolerance"]):
                self.assertNotRegex(text, r"spec [a-z]+\.md|issue [0-9]+|seeds/", row["id"])
            for spec in row["values"].values():
                self.assertFalse(spec["file"].endswith(written_by_plot_scripts), row["id"])
                self.assertTrue(spec["file"].endswith((".json", ".csv")), row["id"])


    def test_every_figure_a_plotting_script_saves_has_a_caption_with_units(self):
        # The names the plot scripts save (save_atomic(fig, DIR, "NAME.png"); plot_campaign's
        # campaign*.png per run), each matched by a caption that names a unit in brackets.
        import glob
        import re
        references = report.load_references(self.path)
        captions = references["figures"]
        for text in captions.values():
            self.assertRegex(text, r"\[[^\]]+\]")
        names = set()
        for script in glob.glob(os.path.join(SOURCE, "python", "plot_*.py")):
            with open(script, encoding="utf-8") as f:
                names |= set(re.findall(r'save_atomic\(fig, \w+, "([\w.-]+\.png)"\)', f.read()))
        names.discard("sweep.png")  # renamed to gait-vs-friction.png by plot_analysis.py
        names.add("gait-vs-friction.png")
        runs = {row["run"] for row in references["rows"]}
        for name in sorted(names):
            self.assertTrue(any(report.caption(captions, run, name) for run in runs) or
                            report.caption(captions, "x", name), name)
        for run in ("humanoid-envelope", "humanoid-push-recovery"):
            self.assertIsNotNone(report.caption(captions, run, "campaign_balance.mode=pd.png"
                                                if run == "humanoid-push-recovery" else "campaign.png"), run)


class CampaignRowTest(unittest.TestCase):
    """A row over a campaign.csv (dotted axis columns) and a run's caption, as the walking envelope has."""

    def test_where_filter_and_caption(self):
        with tempfile.TemporaryDirectory() as tmp:
            references = {
                "sections": REFERENCES["sections"],
                "rows": [{
                    "id": "envelope", "section": "demo", "run": "run-b",
                    "values": {"points": {"file": "campaign.csv",
                                          "columns": {"control.compensation": "text", "fell": "bool"}}},
                    "label": "Envelope",
                    "ours": "{% for m in ['off', 'both'] %}{{ m }}: "
                            "{{ points|where('control.compensation', m)|selectattr('fell')|list|length }} of "
                            "{{ points|where('control.compensation', m)|length }} fell; {% endfor %}",
                    "reference": "—", "source": "spec",
                    "verdict": {"reproduced": "true", "tolerance": "none"}}],
                "figures": REFERENCES["figures"],
            }
            tree = RunTree(tmp, references=references)
            write(os.path.join(tmp, "run-b", "campaign.csv"),
                  "index,control.compensation,fell\n0,off,true\n1,both,false\n2,off,false\n3,both,false\n")
            with open(os.path.join(tmp, "reproduce.json"), encoding="utf-8") as f:
                manifest = json.load(f)
            manifest["runs"][1]["caption"] = "Each cell <one> walk."
            write(os.path.join(tmp, "reproduce.json"), json.dumps(manifest))
            result = tree.render()
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertEqual(page_check.table_rows(tree.page)["envelope"][1], "off: 1 of 2 fell; both: 0 of 2 fell; ")
            self.assertIn("<p>Each cell &lt;one&gt; walk.</p>", tree.page_text())
            self.assertEqual(page_check.page_problems(tree.page), [])


class JsonPointerTest(unittest.TestCase):
    def test_pointer_resolution(self):
        document = {"a": {"b/c": [10, 20]}, "m~n": 1}
        self.assertEqual(report.json_pointer(document, "/a/b~1c/1", "f"), 20)
        self.assertEqual(report.json_pointer(document, "/m~0n", "f"), 1)
        with self.assertRaisesRegex(report.ReportError, "f: no key /a/x"):
            report.json_pointer(document, "/a/x", "f")
        with self.assertRaisesRegex(report.ReportError, "no key /a/b~1c/2"):
            report.json_pointer(document, "/a/b~1c/2", "f")


if __name__ == "__main__":
    unittest.main()
