"""The core's size is counted in code lines (issue 25): comments, ACSL contracts and blank lines
do not count, code does, even code that looks like a comment inside a string."""
import importlib.util
import os

from stack_tools.paths import ROOT

spec = importlib.util.spec_from_file_location(
    "code_lines", os.path.join(ROOT, "arduino_ha", "tools", "code_lines.py"))
code_lines = importlib.util.module_from_spec(spec)
spec.loader.exec_module(code_lines)


def test_comments_contracts_and_blank_lines_are_not_code():
    text = ("/* a header\n * comment */\n\n#include <stdint.h>\n"
            "/*@ requires \\valid(p);\n  @ ensures \\result >= 0; */\n"
            "int f(int *p) {  // why, not what\n  return *p; /* inline */\n}\n")
    assert code_lines.code_lines(text) == 4


def test_code_after_a_comment_on_its_line_counts_and_a_comment_in_a_string_opens_none():
    text = 'x = 1; /* set */ y = 2;\n/* gone */ z = 3;\nconst char *s = "/* not a comment";\nw = 4;\n'
    assert code_lines.code_lines(text) == 4


def test_the_last_line_without_a_newline_counts():
    assert code_lines.code_lines("a = 1;\nb = 2;") == 2
