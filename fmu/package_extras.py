#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Write the FMU's documentation/index.html and sources/buildDescription.xml.

Usage: package_extras.py MODEL STAGE_DIR DOC_TEMPLATE SOURCE_FILE...
The documentation is the model's hand-written page with a table of every variable (name,
causality, unit, start, description) taken from the staged modelDescription.xml, so it never
disagrees with the interface. buildDescription.xml (FMI 3.0 format, read by tools that rebuild
from sources) lists the same source files as <SourceFiles> in modelDescription.xml.
"""
import html
import sys
import xml.etree.ElementTree as ET
from pathlib import Path


def variable_table(md: Path) -> str:
    root = ET.parse(md).getroot()
    rows = ["<table><tr><th>name</th><th>causality</th><th>type</th><th>unit</th><th>start</th>"
            "<th>value reference</th><th>description</th></tr>"]
    for sv in root.iter("ScalarVariable"):
        t = next(iter(sv))
        typ = t.get("declaredType") or t.tag
        rows.append("<tr>" + "".join(f"<td>{html.escape(str(x))}</td>" for x in (
            sv.get("name"), sv.get("causality"), typ, t.get("unit", ""), t.get("start", ""),
            sv.get("valueReference"), sv.get("description"))) + "</tr>")
    rows.append("</table>")
    enums = []
    for st in root.iter("SimpleType"):
        items = ", ".join(f"{html.escape(i.get('name'))} = {i.get('value')}" for i in st.iter("Item"))
        enums.append(f"<li><b>{html.escape(st.get('name'))}</b>: {items}</li>")
    if not enums:   # choices are Integer codes, listed in the variables' descriptions
        return "\n".join(rows)
    return "\n".join(rows) + "\n<h2>Enumerations</h2>\n<ul>" + "\n".join(enums) + "</ul>"


def build_description(model: str, sources: list[str]) -> str:
    files = "\n".join(f'      <SourceFile name="{s}"/>' for s in sources)
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n<fmiBuildDescription fmiVersion="3.0">\n'
            f'  <BuildConfiguration modelIdentifier="{model}">\n'
            f'    <SourceFileSet language="C99">\n{files}\n'
            f'      <IncludeDirectory name="."/>\n    </SourceFileSet>\n'
            f'  </BuildConfiguration>\n</fmiBuildDescription>\n')


def main(argv):
    model, stage, template, sources = argv[1], Path(argv[2]), Path(argv[3]), argv[4:]
    page = template.read_text().replace("<!--VARIABLES-->", variable_table(stage / "modelDescription.xml"))
    (stage / "documentation" / "index.html").write_text(page)
    (stage / "sources" / "buildDescription.xml").write_text(build_description(model, sources))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
