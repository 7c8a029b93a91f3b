#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Write the FMU's documentation/index.html and sources/buildDescription.xml.

Usage: package_extras.py FMI_VERSION MODEL STAGE_DIR DOC_TEMPLATE SOURCE_FILE...
The documentation is the model's hand-written page with a table of every variable (name,
causality, type, unit, start, description) taken from the staged modelDescription.xml, so it
never disagrees with the interface, and the licence. The page is written for FMI 2.0; for an
FMI 3.0 FMU its FMI function names become FMI 3.0's and a section says what FMI 3.0 changes.
buildDescription.xml (FMI 3.0 format, read by tools that rebuild from sources) lists the same
source files as <SourceFiles> in an FMI 2.0 modelDescription.xml.
"""
import html
import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

# The FMI 2.0 names the pages use and their FMI 3.0 counterparts.
FMI3_NAMES = {
    "DoStep": "DoStep", "OK": "OK", "Warning": "Warning", "Error": "Error",
    "ExitInitializationMode": "ExitInitializationMode",
    "EnterInitializationMode": "EnterInitializationMode",
    "SetupExperiment": "EnterInitializationMode", "SetReal": "SetFloat64",
    "GetReal": "GetFloat64", "SetInteger": "SetInt32", "GetInteger": "GetInt32",
    "GetFMUstate": "GetFMUState", "SetFMUstate": "SetFMUState",
    "SerializeFMUstate": "SerializeFMUState", "DeSerializeFMUstate": "DeserializeFMUState",
    "Reset": "Reset", "Terminate": "Terminate", "Instantiate": "InstantiateCoSimulation",
    "FreeInstance": "FreeInstance",
}

FMI3_SECTION = """<h2>FMI 3.0</h2>
<ul>
<li>This FMU is built from the same model source as the FMI 2.0 one and computes the same
  values bit for bit; its serialised FMU states are interchangeable with the FMI 2.0 FMU's of
  the same build.</li>
<li>Reals are <code>Float64</code>, the choices <code>Int32</code> codes with min and max.
  Per-axis variables are arrays of fixed size (their value reference is their first
  element's), with the elements the FMI 2.0 FMU names <code>name[i]</code>.</li>
<li><code>time</code> is the independent variable (read only): the communication point
  reached. <code>fixedInternalStepSize</code> is the default of <code>Ts</code>; the ticks follow
  the <code>Ts</code> set.</li>
<li>No event mode, clocks, intermediate update or structural parameters: instantiate with
  <code>eventModeUsed = false</code>; the functions for them return <code>fmi3Error</code> with a
  logged message.</li>
</ul>
"""

LICENSE_SECTION = """<h2>Licence</h2>
<p>smoothshaper is licensed under the Apache License, Version 2.0
(SPDX-License-Identifier: Apache-2.0); the full text is in
<a href="licenses/LICENSE.txt">licenses/LICENSE.txt</a>. The sources in <code>sources/</code>
are under the same licence.</p>
"""


def variable_table(md: Path) -> str:
    root = ET.parse(md).getroot()
    rows = ["<table><tr><th>name</th><th>causality</th><th>type</th><th>unit</th><th>start</th>"
            "<th>value reference</th><th>description</th></tr>"]
    if root.get("fmiVersion") == "2.0":
        for sv in root.iter("ScalarVariable"):
            t = next(iter(sv))
            rows.append(_row(sv.get("name"), sv.get("causality"), t.get("declaredType") or t.tag,
                             t.get("unit", ""), t.get("start", ""), sv.get("valueReference"),
                             sv.get("description")))
    else:
        for v in root.find("ModelVariables"):
            dims = [d.get("start") for d in v.iter("Dimension")]
            typ = v.tag + "".join(f"[{d}]" for d in dims)
            rows.append(_row(v.get("name"), v.get("causality"), typ, v.get("unit", ""),
                             v.get("start", ""), v.get("valueReference"), v.get("description")))
    rows.append("</table>")
    return "\n".join(rows)


def _row(*cells) -> str:
    return "<tr>" + "".join(f"<td>{html.escape(str(x or ''))}</td>" for x in cells) + "</tr>"


def for_fmi3(page: str) -> str:
    """The FMI 2.0 page with FMI 3.0's function names and the FMI 3.0 section."""
    def rename(match: re.Match) -> str:
        name = match.group(1)
        if name not in FMI3_NAMES:
            raise SystemExit(f"package_extras.py: no FMI 3.0 name for fmi2{name} (add it to "
                             "FMI3_NAMES)")
        return "fmi3" + FMI3_NAMES[name]
    page = re.sub(r"\bfmi2([A-Za-z]+)", rename, page).replace("FMI 2.0", "FMI 3.0")
    return page.replace("<!--VARIABLES-->", FMI3_SECTION + "<!--VARIABLES-->")


def build_description(model: str, sources: list[str]) -> str:
    files = "\n".join(f'      <SourceFile name="{s}"/>' for s in sources)
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n<fmiBuildDescription fmiVersion="3.0">\n'
            f'  <BuildConfiguration modelIdentifier="{model}">\n'
            f'    <SourceFileSet language="C99">\n{files}\n'
            f'      <IncludeDirectory name="."/>\n    </SourceFileSet>\n'
            f'  </BuildConfiguration>\n</fmiBuildDescription>\n')


def main(argv):
    version, model, stage, template = argv[1], argv[2], Path(argv[3]), Path(argv[4])
    sources = argv[5:]
    page = template.read_text()
    if version == "3":
        page = for_fmi3(page)
    table = variable_table(stage / "modelDescription.xml")
    page = page.replace("<!--VARIABLES-->", table + "\n" + LICENSE_SECTION)
    (stage / "documentation" / "index.html").write_text(page)
    (stage / "sources" / "buildDescription.xml").write_text(build_description(model, sources))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
