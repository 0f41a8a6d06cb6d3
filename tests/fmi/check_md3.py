#!/usr/bin/env python3
"""check_md3.py - the rules of the FMI 3.0 schema and specification (modelica/fmi-standard
v3.0: schema/fmi3ModelDescription.xsd, fmi3Variable.xsd, fmi3InterfaceType.xsd,
fmi3BuildDescription.xsd; docs/2_4_common_schema.adoc) that an FMU written by
`scenec --fmu` (or a test FMU of tests/fmi/) must keep, checked on an unpacked FMU:

  root       fmiModelDescription with fmiVersion 3.x, modelName, instantiationToken
  order      ModelExchange? CoSimulation? ScheduledExecution? UnitDefinitions?
             TypeDefinitions? LogCategories? DefaultExperiment? ModelVariables
             ModelStructure Annotations?
  interface  modelIdentifier a C name, with binaries/x86_64-linux/<id>.so; boolean
             attributes true/false; fixedInternalStepSize > 0
  variables  unique names and value references; known types, causalities and
             variabilities; exactly one independent variable (Float64, no start, no
             initial); parameters fixed or tunable with a start; inputs with a start;
             calculated outputs without one; every unit declared in UnitDefinitions
  structure  Output* ContinuousStateDerivative* ClockedState* InitialUnknown*
             EventIndicator* in that order; the Outputs are exactly the outputs, in
             variable order; every reference names a variable
  experiment startTime < stopTime, stepSize > 0
  sources    buildDescription.xml (if any): fmiBuildDescription 3.0, the same
             modelIdentifier, every SourceFile present under sources/

Usage: check_md3.py FMU_DIR; prints one line per rule broken and exits 1, or "ok"."""
import os
import re
import sys
import xml.etree.ElementTree as ET

ORDER = ["ModelExchange", "CoSimulation", "ScheduledExecution", "UnitDefinitions",
         "TypeDefinitions", "LogCategories", "DefaultExperiment", "ModelVariables",
         "ModelStructure", "Annotations"]
STRUCT = ["Output", "ContinuousStateDerivative", "ClockedState", "InitialUnknown",
          "EventIndicator"]
TYPES = {"Float32", "Float64", "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32",
         "Int64", "UInt64", "Boolean", "String", "Binary", "Enumeration", "Clock"}
CAUSALITY = {"parameter", "calculatedParameter", "input", "output", "local", "independent",
             "structuralParameter"}
VARIABILITY = {"constant", "fixed", "tunable", "discrete", "continuous"}
BOOLS = ["needsExecutionTool", "canBeInstantiatedOnlyOncePerProcess", "canGetAndSetFMUState",
         "canSerializeFMUState", "providesDirectionalDerivatives",
         "providesAdjointDerivatives", "providesPerElementDependencies",
         "canHandleVariableCommunicationStepSize", "providesIntermediateUpdate",
         "mightReturnEarlyFromDoStep", "canReturnEarlyAfterIntermediateUpdate",
         "hasEventMode", "providesEvaluateDiscreteStates", "needsCompletedIntegratorStep"]


def check(d):
    errs = []
    root = ET.parse(os.path.join(d, "modelDescription.xml")).getroot()
    if root.tag != "fmiModelDescription":
        return ["root element is %s" % root.tag]
    if not root.get("fmiVersion", "").startswith("3."):
        errs.append("fmiVersion %r is not 3.x" % root.get("fmiVersion"))
    for a in ("modelName", "instantiationToken"):
        if not root.get(a):
            errs.append("fmiModelDescription lacks %s" % a)
    tags = [c.tag for c in root]
    idx = [ORDER.index(t) if t in ORDER else -1 for t in tags]
    if -1 in idx or idx != sorted(idx) or len(set(tags)) != len(tags):
        errs.append("elements out of the schema's order or unknown: %s" % tags)
    for t in ("ModelVariables", "ModelStructure"):
        if t not in tags:
            errs.append("no <%s>" % t)
    ifaces = [c for c in root if c.tag in ("ModelExchange", "CoSimulation", "ScheduledExecution")]
    if not ifaces:
        errs.append("no interface element")
    for i in ifaces:
        mid = i.get("modelIdentifier", "")
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", mid):
            errs.append("%s: modelIdentifier %r is not a C name" % (i.tag, mid))
        elif not os.path.exists(os.path.join(d, "binaries", "x86_64-linux", mid + ".so")) \
                and not os.path.isdir(os.path.join(d, "sources")):
            errs.append("%s: neither binaries/x86_64-linux/%s.so nor sources/" % (i.tag, mid))
        for b in BOOLS:
            if i.get(b) not in (None, "true", "false"):
                errs.append("%s: %s=%r is not a boolean" % (i.tag, b, i.get(b)))
        s = i.get("fixedInternalStepSize")
        if s is not None and not float(s) > 0:
            errs.append("fixedInternalStepSize %s is not > 0" % s)
    units = {u.get("name") for u in root.iter("Unit")}
    mv = root.find("ModelVariables")
    names, vrs, byvr, outputs, indep = set(), set(), {}, [], 0
    for v in (mv if mv is not None else []):
        n, c = v.get("name"), v.get("causality", "local")
        var = v.get("variability", "continuous" if v.tag in ("Float32", "Float64") else "discrete")
        where = "variable %r" % n
        if v.tag not in TYPES:
            errs.append("%s: unknown type <%s>" % (where, v.tag))
        if not n or n in names:
            errs.append("%s: missing or repeated name" % where)
        names.add(n)
        vr = v.get("valueReference")
        if vr is None or not vr.isdigit() or vr in vrs:
            errs.append("%s: missing or repeated valueReference %r" % (where, vr))
        vrs.add(vr)
        byvr[vr] = v
        if c not in CAUSALITY or var not in VARIABILITY:
            errs.append("%s: causality %r / variability %r unknown" % (where, c, var))
        init = v.get("initial")
        if c == "independent":
            indep += 1
            if v.tag not in ("Float32", "Float64") or v.get("start") or init:
                errs.append("%s: the independent variable must be a float without start or "
                            "initial" % where)
        if c in ("parameter", "structuralParameter") and (var not in ("fixed", "tunable")
                                                          or v.get("start") is None):
            errs.append("%s: a parameter must be fixed or tunable with a start" % where)
        if c == "input" and v.get("start") is None:
            errs.append("%s: an input needs a start" % where)
        if c == "output" and init in (None, "calculated") and v.get("start") is not None:
            errs.append("%s: a calculated output may not have a start" % where)
        if v.get("unit") and v.get("unit") not in units:
            errs.append("%s: unit %r not in UnitDefinitions" % (where, v.get("unit")))
        if c == "output":
            outputs.append(vr)
    if indep != 1:
        errs.append("%d independent variables (exactly one required)" % indep)
    ms = root.find("ModelStructure")
    kids = [c.tag for c in (ms if ms is not None else [])]
    k_idx = [STRUCT.index(t) if t in STRUCT else -1 for t in kids]
    if -1 in k_idx or k_idx != sorted(k_idx):
        errs.append("ModelStructure elements out of order or unknown")
    for c in (ms if ms is not None else []):
        if c.get("valueReference") not in byvr:
            errs.append("ModelStructure <%s valueReference=%r> names no variable"
                        % (c.tag, c.get("valueReference")))
    listed = [c.get("valueReference") for c in (ms if ms is not None else []) if c.tag == "Output"]
    if listed != outputs:
        errs.append("ModelStructure Outputs %s are not the outputs %s in order" % (listed, outputs))
    de = root.find("DefaultExperiment")
    if de is not None:
        t0, t1, h = (float(de.get(a, x)) for a, x in
                     (("startTime", "0"), ("stopTime", "inf"), ("stepSize", "1")))
        if not (t0 < t1 and h > 0):
            errs.append("DefaultExperiment: startTime %g, stopTime %g, stepSize %g" % (t0, t1, h))
    bd = os.path.join(d, "sources", "buildDescription.xml")
    if os.path.exists(bd):
        b = ET.parse(bd).getroot()
        if b.tag != "fmiBuildDescription" or not b.get("fmiVersion", "").startswith("3."):
            errs.append("buildDescription.xml: not an FMI 3.0 fmiBuildDescription")
        ids = {i.get("modelIdentifier") for i in ifaces}
        for bc in b.iter("BuildConfiguration"):
            if bc.get("modelIdentifier") not in ids:
                errs.append("buildDescription.xml: modelIdentifier %r of no interface"
                            % bc.get("modelIdentifier"))
        for sf in b.iter("SourceFile"):
            if not os.path.exists(os.path.join(d, "sources", sf.get("name", ""))):
                errs.append("buildDescription.xml: SourceFile %r missing" % sf.get("name"))
    return errs


def main():
    errs = check(sys.argv[1])
    for e in errs:
        print("check_md3: %s: %s" % (sys.argv[1], e))
    if not errs:
        print("check_md3: %s: ok" % sys.argv[1])
    return 1 if errs else 0


if __name__ == "__main__":
    sys.exit(main())
