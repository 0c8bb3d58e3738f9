#!/usr/bin/python3
"""The ParaView plugin's lighting properties say what the scene language says (issue 33).

paraview/plugin/CloudRepresentation.xml spells the lighting models, the phase functions, the
multiple-scattering methods and the light transmittances again as enumerations, and the lighting
parameters' defaults and ranges as numbers, for ParaView's panel. The scene schema is their one
home (`cloudvis schema` prints it: filters/CloudLightingParameters.h's tables, the keys of
app/scene/SceneSchema.cxx). This check reads both and fails naming every property that differs:
an enumeration's names, their order (the XML's values are the enumeration's, 0, 1, ...) or its
default; a number's default; a range the XML allows beyond the schema's.

    ParaViewXmlCheck.py --cloudvis build/bin/cloudvis --xml paraview/plugin/CloudRepresentation.xml
"""
import argparse
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

# XML property -> (schema table, key). The representation's own settings (sampling, accumulation,
# memory, the exchange) have no scene key of the same meaning and are not listed.
PROPERTIES = {
    "CloudLighting": ("render", "lighting"),
    "CloudDerivativeDistance": ("render.lighting", "derivative.distance"),
    "CloudLightSteps": ("render.lighting", "march.light_steps"),
    "CloudTransmittance": ("render.lighting", "march.transmittance"),
    "CloudPhaseG1": ("render.lighting", "march.g1"),
    "CloudPhaseG2": ("render.lighting", "march.g2"),
    "CloudPhaseLobeWeight": ("render.lighting", "march.lobe_weight"),
    "CloudPhase": ("render.lighting", "march.phase"),
    "CloudDropletEffectiveRadius": ("render.lighting", "march.effective_radius"),
    "CloudDropletEffectiveVariance": ("render.lighting", "march.effective_variance"),
    "CloudMultipleScattering": ("render.lighting", "march.multiple_scattering"),
    "CloudOctaves": ("render.lighting", "march.octaves"),
}

# Defaults the representation chooses on purpose, with the reason.
OWN_DEFAULTS = {
    # A cloud added in ParaView is lit: its users expect a shaded volume, not emission alone.
    "CloudLighting": "march",
    # The droplets' radius defaults to the field's r_e in a scene; ParaView has no field units.
    "CloudDropletEffectiveRadius": 10.0,
}


def schema_tables(cloudvis):
    """{table: {key: (default, allowed)}} from `cloudvis schema`."""
    text = subprocess.run([cloudvis, "schema"], check=True, capture_output=True,
                          text=True).stdout
    tables = {}
    for name, body in re.findall(r"<!-- schema:(\S+) -->\n(.*?)<!-- /schema -->", text, re.S):
        rows = {}
        for line in body.splitlines():
            cells = line.strip().strip("|").split("|", 3)
            if len(cells) == 4 and cells[0].strip().startswith("`"):
                rows[cells[0].strip().strip("`")] = (cells[2].strip(), cells[3].strip())
        tables[name] = rows
    return tables


def without_parentheses(text):
    """The text with every (balanced) parenthesized part removed: the names' descriptions."""
    out, depth = [], 0
    for c in text:
        depth += c == "("
        if depth == 0:
            out.append(c)
        depth -= c == ")" and depth > 0
    return "".join(out)


def choice_names(allowed):
    """The names of a choice's allowed column: `"a"` (...), `"b"` (...) or `"a"` or `"b"`; ..."""
    return re.findall(r'`"([a-z_]+)"`', without_parentheses(allowed).split(";")[0])


def number_range(allowed):
    """(low, high, low closed, high closed) of an allowed column: [a, b], (a, b), >= a, > a."""
    head = allowed.split(";")[0].strip()
    m = re.match(r"([\[(])\s*(-?[\d.e+-]+),\s*(-?[\d.e+-]+)\s*([\])])", head)
    if m:
        return float(m[2]), float(m[3]), m[1] == "[", m[4] == "]"
    m = re.match(r"(>=|>)\s*(-?[\d.e+-]+)", head)
    if m:
        return float(m[2]), float("inf"), m[1] == ">=", False
    return None


def check_choice(name, prop, default, allowed, problems):
    names = choice_names(allowed)
    entries = [(int(e.get("value")), e.get("text")) for e in prop.iter("Entry")]
    if [t for _, t in entries] != names or [v for v, _ in entries] != list(range(len(names))):
        problems.append(f"{name}: entries {entries}, but the schema's names are {names} "
                        f"(values 0 to {len(names) - 1} in that order)")
        return
    expected = OWN_DEFAULTS.get(name, default.strip('`"'))
    got = names[int(prop.get("default_values"))] if entries else None
    if got != expected:
        problems.append(f"{name}: default {got!r}, the schema's is {expected!r}")


def check_number(name, prop, default, allowed, problems):
    got = float(prop.get("default_values"))
    expected = OWN_DEFAULTS.get(name)
    if expected is None:
        m = re.fullmatch(r"`(-?[\d.e+-]+)`", default)
        if not m:
            problems.append(f"{name}: the schema's default {default!r} is not a number")
            return
        expected = float(m[1])
    if got != expected:
        problems.append(f"{name}: default {got:g}, the schema's is {expected:g}")
    schema = number_range(allowed)
    domain = next((d for d in prop if d.tag in ("IntRangeDomain", "DoubleRangeDomain")), None)
    if schema is None or domain is None:
        if schema is not None and schema[:2] != (float("-inf"), float("inf")):
            problems.append(f"{name}: no range domain, the schema allows only {allowed.split(';')[0]}")
        return
    low = float(domain.get("min", "-inf"))
    high = float(domain.get("max", "inf"))
    s_low, s_high, low_closed, high_closed = schema
    if low < s_low or (low == s_low and not low_closed) or high > s_high or (
            high == s_high and not high_closed and high != float("inf")):
        problems.append(f"{name}: range [{low:g}, {high:g}] goes beyond the schema's "
                        f"{allowed.split(';')[0]}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cloudvis", required=True)
    parser.add_argument("--xml", required=True)
    args = parser.parse_args()
    tables = schema_tables(args.cloudvis)
    properties = {p.get("name"): p for p in ET.parse(args.xml).getroot().iter()
                  if p.tag.endswith("VectorProperty") and p.get("name") in PROPERTIES}
    problems = []
    for name, (table, key) in PROPERTIES.items():
        if name not in properties:
            problems.append(f"{name}: not in {args.xml}")
            continue
        if key not in tables.get(table, {}):
            problems.append(f"{name}: the schema has no key {key} in {table}")
            continue
        default, allowed = tables[table][key]
        prop = properties[name]
        if prop.find(".//EnumerationDomain") is not None:
            check_choice(name, prop, default, allowed, problems)
        else:
            check_number(name, prop, default, allowed, problems)
    for problem in problems:
        print(f"ParaViewXmlCheck: {args.xml}: {problem}")
    if problems:
        sys.exit(1)
    print(f"ParaViewXmlCheck: {len(PROPERTIES)} properties agree with the scene schema")


if __name__ == "__main__":
    main()
