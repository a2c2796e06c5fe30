#!/usr/bin/env python3
"""What the Markdown tools count as prose: scripts/check_links.py's outside_fences(), which
comment_answers.py also reads Markdown by (a fence closes only on its own character, at least as
long; CommonMark), and how check_links.py counts a table row's cells (GFM). Expected values by
hand."""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
from check_links import outside_fences, table_cells  # noqa: E402
import comment_answers  # noqa: E402


def prose(text):
    return [line for _, line in outside_fences(text.split("\n"))]


class TableCells(unittest.TestCase):
    def test_a_row_and_its_delimiter(self):
        self.assertEqual(table_cells("| a | `b` | c |"), 3)
        self.assertEqual(table_cells("|---|---|---|"), 3)

    def test_a_pipe_in_a_code_span_splits_the_cell(self):
        self.assertEqual(table_cells("| point | `d = |position - P|` |"), 4)

    def test_an_escaped_pipe_does_not(self):
        self.assertEqual(table_cells("| point | `d = \\|position - P\\|` |"), 2)


class OutsideFences(unittest.TestCase):
    def test_a_block_of_backticks(self):
        self.assertEqual(prose("a\n```sh\nb\n```\nc"), ["a", "c"])

    def test_a_shorter_fence_inside_does_not_close_a_longer_one(self):
        self.assertEqual(prose("a\n````\n```\nb\n```\n````\nc"), ["a", "c"])

    def test_tildes_do_not_close_backticks(self):
        self.assertEqual(prose("a\n```\n~~~\nb\n```\nc\n~~~\nd\n~~~\ne"), ["a", "c", "e"])

    def test_four_spaces_are_not_a_fence(self):
        self.assertEqual(prose("a\n    ```\nb"), ["a", "    ```", "b"])

    def test_an_unclosed_block_runs_to_the_end(self):
        self.assertEqual(prose("a\n```\nb\nc"), ["a"])

    def test_line_numbers_count_every_line(self):
        self.assertEqual(list(outside_fences(["x", "```", "y", "```", "z"])), [(1, "x"), (5, "z")])


class CommentAnswersReadsMarkdownSo(unittest.TestCase):
    def test_prose_of_a_markdown_file(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "README.md")
            with open(path, "w") as f:
                f.write("intro\n````md\n```\nvkCmdDraw(...)\n```\n````\nafter\n")
            code, text = comment_answers.split_code(path)
            self.assertEqual(code, "")
            self.assertEqual(text, [(1, "intro"), (7, "after"), (8, "")])


if __name__ == "__main__":
    unittest.main(verbosity=1)
