"""The repository's own papers: every Markdown document the tree cites exists, with the section it
is cited for."""
import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# A Markdown file named in the tree (README.md, hil/HIL_INTERFACES.md, link/README.md, ...),
# optionally with the section it is cited for ("HIL_INTERFACES.md section 3").
CITATION = re.compile(r"(?<![\w./-])([\w./-]*[A-Za-z0-9_]\.md)\b(?: section (\d+))?")


def tracked():
    out = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True)
    return out.stdout.split()


def citations():
    for name in tracked():
        path = ROOT / name
        if path.suffix not in (".py", ".md", ".txt", ".launch", ".h", ".c", ".cpp", ".sh", ".mk", ".cmake", ".yaml", ".xml", ".cff") \
                and path.name not in ("Makefile", "CMakeLists.txt"):
            continue
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            for match in CITATION.finditer(line):
                if "://" in line[max(0, match.start() - 60):match.start()]:
                    continue  # a web address
                yield "%s:%d" % (name, number), match.group(1), match.group(2)


def is_document(cited, top_level):
    """A document rather than an output a tool writes (report/table.md, sweep.md): an upper-case
    name (README.md, HIL_INTERFACES.md) or a path from a folder of the repository's root."""
    return re.fullmatch(r"[A-Z_]+\.md", cited.rsplit("/", 1)[-1]) is not None or \
        cited.lstrip("./").split("/", 1)[0] in top_level


def resolve(cited, documents):
    """The tracked document a citation names: a path ending in what is cited."""
    cited = cited.lstrip("./")
    return [d for d in documents if d == cited or d.endswith("/" + cited)]


def test_every_cited_markdown_document_exists_with_its_section():
    documents = [t for t in tracked() if t.endswith(".md")]
    top_level = {t.split("/", 1)[0] for t in tracked() if "/" in t}
    missing, no_section, seen = [], [], 0
    for where, cited, section in citations():
        if not is_document(cited, top_level):
            continue
        seen += 1
        found = resolve(cited, documents)
        if not found:
            missing.append("%s: %s" % (where, cited))
            continue
        if section is not None:
            heading = re.compile(r"^#+ %s\. " % section, re.M)
            if not any(heading.search((ROOT / d).read_text()) for d in found):
                no_section.append("%s: %s section %s" % (where, cited, section))
    assert seen > 20  # the scan sees the tree's citations
    assert not missing, "cited but not in the tree:\n" + "\n".join(missing)
    assert not no_section, "cited sections without a heading '## N. ':\n" + "\n".join(no_section)
