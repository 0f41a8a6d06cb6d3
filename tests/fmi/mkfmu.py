#!/usr/bin/env python3
"""mkfmu.py - builds a test FMU (tests/fmi/) from one model description: tests/fmi/models/
<m>.json gives the variables, mkfmu writes model_gen.h for the C code, compiles the model
with the FMI glue (tests/fmi/fmi_glue.c) into binaries/<platform>/<m>.so, writes
modelDescription.xml for FMI 2.0 or 3.0 as the specification lays it out, and zips the
whole. Options damage the result for the bad-FMU corpus (tests/fmi/bad.sh)."""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from xml.sax.saxutils import quoteattr

HERE = os.path.dirname(os.path.abspath(__file__))


def gen_header(d, token):
    nv = max(v["vr"] for v in d["vars"]) + 1
    states = [v for v in d["vars"] if v.get("state")]
    ders = [v for v in d["vars"] if "derivative" in v]
    # states in the order of their derivatives (the model structure's order)
    order = [next(s for s in states if s["vr"] == dv["derivative"]) for dv in ders]
    start = ["0"] * nv
    for v in d["vars"]:
        if "start" in v:
            start[v["vr"]] = repr(float(v["start"]))
    lines = [
        "/* model_gen.h - written by tests/fmi/mkfmu.py from models/%s.json */" % d["name"],
        "#define MODEL_NV %d" % nv,
        "#define MODEL_NX %d" % len(ders),
        "#define MODEL_NZ %d" % d["nz"],
        "#define MODEL_TOKEN %s" % json.dumps(token),
        "static const double model_start[%d] = {%s};" % (nv, ", ".join(start)),
        "static const unsigned model_state[%d] = {%s};" % (len(order) + 1,
                                                           ", ".join(str(s["vr"]) for s in order) or "0"),
        "static const unsigned model_der[%d] = {%s};" % (len(ders) + 1,
                                                         ", ".join(str(v["vr"]) for v in ders) or "0"),
    ]
    if d.get("needs_step"):  # the model's model_completed_step (fmi_model.h)
        lines.append("#define MODEL_NEEDS_STEP 1")
    late = [v["vr"] for v in d["vars"] if v.get("late")]
    if late:  # the glue counts there evaluations past nextEventTime (fmi_glue.c)
        lines.append("#define MODEL_LATE %d" % late[0])
    wrong = [v["vr"] for v in d["vars"] if v.get("wrong")]
    if wrong:  # the glue counts there values FMI lets change in event mode only, set in
        # continuous-time mode: discrete inputs and tunable parameters (fmi_glue.c)
        only = ["0"] * nv
        for v in d["vars"]:
            if (v["causality"] == "input" and v["variability"] != "continuous") or \
               (v["causality"] == "parameter" and v["variability"] == "tunable"):
                only[v["vr"]] = "1"
        lines.append("#define MODEL_WRONG %d" % wrong[0])
        lines.append("static const unsigned char model_event_only[%d] = {%s};" % (nv, ", ".join(only)))
    return "\n".join(lines) + "\n"


def units_xml(d):
    units = sorted({v["unit"] for v in d["vars"] if v.get("unit")})
    if not units:
        return ""
    return "  <UnitDefinitions>\n%s  </UnitDefinitions>\n" % "".join(
        "    <Unit name=%s/>\n" % quoteattr(u) for u in units)


def var_attrs(v):
    a = 'name=%s valueReference="%d" causality="%s" variability="%s"' % (
        quoteattr(v["name"]), v["vr"], v["causality"], v["variability"])
    if "initial" in v and v["causality"] != "input":
        a += ' initial="%s"' % v["initial"]
    return a


def md2(d, token, ident):
    idx = {v["vr"]: i + 1 for i, v in enumerate(d["vars"])}
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<fmiModelDescription fmiVersion="2.0" modelName="%s" guid=%s '
           'numberOfEventIndicators="%d" generationTool="modrt tests/fmi/mkfmu.py" '
           'description=%s>' % (d["name"], quoteattr(token), d["nz"], quoteattr(d["doc"])),
           '  <ModelExchange modelIdentifier="%s" completedIntegratorStepNotNeeded="%s" '
           'canGetAndSetFMUstate="true" canSerializeFMUstate="true"/>' % (
               ident, "false" if d.get("needs_step") else "true")]
    out.append(units_xml(d).rstrip("\n")) if units_xml(d) else None
    out.append("  <ModelVariables>")
    for v in d["vars"]:
        real = ""
        if "start" in v:
            real += ' start="%r"' % float(v["start"])
        if v.get("unit"):
            real += " unit=%s" % quoteattr(v["unit"])
        if "derivative" in v:
            real += ' derivative="%d"' % idx[v["derivative"]]
        out.append("    <ScalarVariable %s>\n      <Real%s/>\n    </ScalarVariable>" % (var_attrs(v), real))
    out.append("  </ModelVariables>\n  <ModelStructure>\n    <Outputs>")
    for o in d["outputs"]:
        out.append('      <Unknown index="%d" dependencies="%s"/>' % (
            idx[o["vr"]], " ".join(str(idx[x]) for x in o["deps"])))
    out.append("    </Outputs>\n    <Derivatives>")
    for v in d["vars"]:
        if "derivative" in v:
            out.append('      <Unknown index="%d"/>' % idx[v["vr"]])
    out.append("    </Derivatives>\n    <InitialUnknowns>")
    for v in d["vars"]:
        if v.get("initial") == "calculated" and (v["causality"] == "output" or "derivative" in v):
            out.append('      <Unknown index="%d"/>' % idx[v["vr"]])
    out.append("    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n")
    return "\n".join(out)


def md3(d, token, ident):
    nv = max(v["vr"] for v in d["vars"]) + 1
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<fmiModelDescription fmiVersion="3.0" modelName="%s" instantiationToken=%s '
           'generationTool="modrt tests/fmi/mkfmu.py" description=%s>' % (
               d["name"], quoteattr(token), quoteattr(d["doc"])),
           '  <ModelExchange modelIdentifier="%s"%s canGetAndSetFMUState="true" '
           'canSerializeFMUState="true"/>' % (
               ident, ' needsCompletedIntegratorStep="true"' if d.get("needs_step") else "")]
    out.append(units_xml(d).rstrip("\n")) if units_xml(d) else None
    out.append("  <ModelVariables>")
    out.append('    <Float64 name="time" valueReference="%d" causality="independent" '
               'variability="continuous"/>' % nv)
    for v in d["vars"]:
        a = var_attrs(v)
        if "start" in v:
            a += ' start="%r"' % float(v["start"])
        if v.get("unit"):
            a += " unit=%s" % quoteattr(v["unit"])
        if "derivative" in v:
            a += ' derivative="%d"' % v["derivative"]
        out.append("    <Float64 %s/>" % a)
    out.append("  </ModelVariables>\n  <ModelStructure>")
    for o in d["outputs"]:
        out.append('    <Output valueReference="%d" dependencies="%s"/>' % (
            o["vr"], " ".join(str(x) for x in o["deps"])))
    for v in d["vars"]:
        if "derivative" in v:
            out.append('    <ContinuousStateDerivative valueReference="%d"/>' % v["vr"])
    for v in d["vars"]:
        if v.get("initial") == "calculated" and (v["causality"] == "output" or "derivative" in v):
            out.append('    <InitialUnknown valueReference="%d"/>' % v["vr"])
    ind = [v["vr"] for v in d["vars"] if v.get("indicator")]
    ind += [ind[0] if ind else 0] * (d["nz"] - len(ind))  # --md-nz: more than the binary's
    for vr in ind:
        out.append('    <EventIndicator valueReference="%d"/>' % vr)
    out.append("  </ModelStructure>\n</fmiModelDescription>\n")
    return "\n".join(out)


def build_description(ident, cfiles):
    return ('<?xml version="1.0" encoding="UTF-8"?>\n<fmiBuildDescription fmiVersion="3.0">\n'
            '  <BuildConfiguration modelIdentifier="%s">\n    <SourceFileSet language="C11">\n'
            '%s      <PreprocessorDefinition name="FMI_VERSION" value="3"/>\n'
            '      <IncludeDirectory name="."/>\n    </SourceFileSet>\n'
            '    <Library name="m"/>\n  </BuildConfiguration>\n</fmiBuildDescription>\n'
            % (ident, "".join('      <SourceFile name="%s"/>\n' % f for f in cfiles)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cc", default="gcc")
    ap.add_argument("--cflags", default="")
    ap.add_argument("--version", type=int, choices=(2, 3), required=True)
    ap.add_argument("--model", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--define", action="append", default=[], help="-D for the model build")
    ap.add_argument("--md-token", help="a token in modelDescription.xml other than the binary's")
    ap.add_argument("--md-nz", type=int, help="numberOfEventIndicators other than the binary's")
    ap.add_argument("--no-md", action="store_true", help="leave modelDescription.xml out")
    ap.add_argument("--extra", action="append", default=[], help="NAME: one more entry")
    ap.add_argument("--platform", help="binaries/<platform>/ other than this one's")
    ap.add_argument("--int-input", help="one more input, an integer, in modelDescription.xml")
    ap.add_argument("--source-only", action="store_true",
                    help="a source FMU: sources/ (and buildDescription.xml for 3.0), no binary")
    ap.add_argument("--break-source", action="store_true", help="a source file cut short")
    ap.add_argument("--source-name", help="the name buildDescription.xml gives the glue")
    ap.add_argument("--truncate", type=int, help="keep only this many bytes of the archive")
    ap.add_argument("--no-state", action="store_true",
                    help="the description does not say it can get, set and serialize its state")
    a = ap.parse_args()
    d = json.load(open(os.path.join(HERE, "models", a.model + ".json")))
    token = d["token"]
    ident = d["name"]
    tmp = tempfile.mkdtemp(prefix="mkfmu")
    try:
        with open(os.path.join(tmp, "model_gen.h"), "w") as f:
            f.write(gen_header(d, token))
        plat = a.platform or ("linux64" if a.version == 2 else "x86_64-linux")
        so = os.path.join(tmp, "binaries", plat, ident + ".so")
        os.makedirs(os.path.dirname(so))
        cmd = ([a.cc] + a.cflags.split() + ["-ffp-contract=off", "-fvisibility=hidden",
               "-DFMI_VERSION=%d" % a.version, "-I" + tmp] + ["-D" + x for x in a.define] +
               [os.path.join(HERE, "fmi_glue.c"), os.path.join(HERE, "models", a.model + ".c"),
                "-o", so, "-lm"])
        subprocess.run(cmd, check=True)
        if a.md_token:
            token = a.md_token
        if a.md_nz is not None:
            d["nz"] = a.md_nz
        xml = (md2 if a.version == 2 else md3)(d, token, ident)
        srcs = [os.path.join(HERE, "fmi_glue.c"), os.path.join(HERE, "models", a.model + ".c"),
                os.path.join(HERE, "fmi_model.h"), os.path.join(tmp, "model_gen.h"),
                os.path.join(HERE, "..", "..", "tools", "fmi", "fmi_api.h")]
        cfiles = ["fmi_glue.c", a.model + ".c"]
        if a.source_only and a.version == 2:
            xml = re.sub(r'(canSerializeFMUstate="true")/>',
                         r'\1>\n    <SourceFiles>\n%s    </SourceFiles>\n  </ModelExchange>' %
                         "".join('      <File name="%s"/>\n' % f for f in cfiles), xml)
        if a.no_state:
            xml = xml.replace(' canGetAndSetFMUstate="true" canSerializeFMUstate="true"', '')
            xml = xml.replace(' canGetAndSetFMUState="true" canSerializeFMUState="true"', '')
        if a.int_input:
            vr = max(v["vr"] for v in d["vars"]) + 10
            var = ('    <ScalarVariable name="%s" valueReference="%d" causality="input">\n'
                   '      <Integer start="0"/>\n    </ScalarVariable>\n' if a.version == 2 else
                   '    <Int32 name="%s" valueReference="%d" causality="input" start="0"/>\n')
            xml = xml.replace("  </ModelVariables>", var % (a.int_input, vr) + "  </ModelVariables>")
        tmpzip = a.out + ".tmp"
        with zipfile.ZipFile(tmpzip, "w", zipfile.ZIP_DEFLATED) as z:
            if not a.no_md:
                z.writestr("modelDescription.xml", xml)
            if a.source_only:
                for f in srcs:
                    data = open(f).read()
                    if a.break_source and f.endswith("fmi_glue.c"):
                        data = data[:len(data) // 2]
                    z.writestr("sources/" + os.path.basename(f), data)
                if a.version == 3:
                    if a.source_name:
                        cfiles[0] = a.source_name
                    z.writestr("sources/buildDescription.xml", build_description(ident, cfiles))
            else:
                z.write(so, "binaries/%s/%s.so" % (plat, ident))
            for e in a.extra:
                z.writestr(e, "an entry of the bad-FMU corpus\n")
        if a.truncate:
            with open(tmpzip, "r+b") as f:
                f.truncate(a.truncate)
        os.replace(tmpzip, a.out)
    finally:
        shutil.rmtree(tmp)


if __name__ == "__main__":
    sys.exit(main())
