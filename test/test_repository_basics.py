"""The repository's own papers: every Markdown document the tree cites exists, with the section it
is cited for."""
import re
import subprocess
from pathlib import Path

import pytest

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


def package_xml():
    import xml.etree.ElementTree as ET
    return ET.parse(ROOT / "package.xml").getroot()


def test_the_license_file_is_the_bsd_3_clause_license_package_xml_declares():
    assert package_xml().findtext("license") == "BSD-3-Clause"
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("BSD 3-Clause License\n")
    assert re.search(r"^Copyright \(c\) \d{4}, the drone_ros authors$", text, re.M)
    for clause in ("1. Redistributions of source code must retain", "2. Redistributions in binary form",
                   "3. Neither the name of the copyright holder", 'PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS "AS IS"'):
        assert clause in text


# Citation File Format 1.2.0, what this file uses of it (the full schema ships with cffconvert, whose
# jsonschema<4 pin would shadow Debian's jsonschema in .venv): the keys it allows at the top and in a
# reference, its required ones, a person or an entity as an author, and the DOI's form.
_PERSON = {"type": "object", "required": ["family-names", "given-names"], "additionalProperties": False,
           "properties": {k: {"type": "string"} for k in ("family-names", "given-names", "affiliation", "orcid", "email")}}
_ENTITY = {"type": "object", "required": ["name"], "additionalProperties": False,
           "properties": {k: {"type": "string"} for k in ("name", "city", "country", "address", "website", "date-start", "date-end")}}
_AUTHORS = {"type": "array", "minItems": 1, "items": {"oneOf": [_PERSON, _ENTITY]}}
_DOI = {"type": "string", "pattern": r"^10\.\d{4,9}(\.\d+)?/[A-Za-z0-9:/_;\-\.\(\)\[\]\\]+$"}
CFF_1_2_0 = {
    "type": "object",
    "required": ["cff-version", "message", "title", "authors"],
    "additionalProperties": False,
    "properties": {
        "cff-version": {"const": "1.2.0"}, "message": {"type": "string"}, "title": {"type": "string"},
        "authors": _AUTHORS, "abstract": {"type": "string"}, "type": {"enum": ["software", "dataset"]},
        "version": {"type": ["string", "number"]}, "license": {"type": "string"}, "doi": _DOI,
        "keywords": {"type": "array", "items": {"type": "string"}}, "date-released": {"type": "string"},
        "repository-code": {"type": "string"}, "url": {"type": "string"}, "commit": {"type": "string"},
        "preferred-citation": {
            "type": "object",
            "required": ["type", "authors", "title"],
            "additionalProperties": False,
            "properties": {
                "type": {"enum": ["article", "conference-paper", "proceedings", "thesis", "report", "software"]},
                "title": {"type": "string"}, "authors": _AUTHORS, "collection-title": {"type": "string"},
                "conference": _ENTITY, "publisher": _ENTITY, "year": {"type": "integer"},
                "start": {"type": ["integer", "string"]}, "end": {"type": ["integer", "string"]}, "doi": _DOI,
                "url": {"type": "string"}, "pages": {"type": ["integer", "string"]},
            },
        },
    },
}


def test_the_citation_file_cites_the_rtcsa_2016_paper_and_the_software_as_package_xml_has_it():
    import jsonschema
    import yaml
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    problems = ["%s: %s" % ("/".join(map(str, e.absolute_path)), e.message)
                for e in jsonschema.Draft7Validator(CFF_1_2_0).iter_errors(cff)]
    assert not problems
    assert cff["version"] == package_xml().findtext("version")
    assert cff["license"] == package_xml().findtext("license")
    paper = cff["preferred-citation"]
    assert paper["type"] == "conference-paper" and paper["year"] == 2016 and "(RTCSA)" in paper["collection-title"]
    assert paper["title"] == "A Simplex Architecture for Intelligent and Safe Unmanned Aerial Vehicles"
    # README names the architecture's authors in this order.
    assert [a["family-names"] for a in paper["authors"]] == ["Vivekanandan", "Garcia", "Yun", "Keshmiri"]
    assert "Vivekanandan, Garcia, Yun, Keshmiri, RTCSA 2016" in (ROOT / "README.md").read_text()


@pytest.mark.filterwarnings("ignore:nodes.Node.traverse:PendingDeprecationWarning")  # catkin_pkg's own
def test_the_changelog_is_one_catkin_prepare_release_can_release():
    from catkin_pkg.changelog import populate_changelog_from_rst, Changelog
    from catkin_pkg.package_version import get_forthcoming_label, rename_section
    rst = (ROOT / "CHANGELOG.rst").read_text()
    assert get_forthcoming_label(rst) == "Forthcoming"
    # What catkin_prepare_release does at the first release: the section becomes the version's.
    version = package_xml().findtext("version")
    released = populate_changelog_from_rst(Changelog("drone_ros"), rename_section(rst, "Forthcoming", "%s (2026-11-26)" % version))
    entries = [(v, list(c)) for v, _, c in released.foreach_version()]
    assert [v for v, _ in entries] == [version]
    (bullets,) = entries[0][1]
    assert len(bullets.bullets) >= 8  # one per issue or feature
