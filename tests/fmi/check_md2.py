#!/usr/bin/env python3
"""check_md2.py - the rules of the FMI 2.0 schema and specification (modelica/fmi-standard
v2.0.5: schema/fmi2ModelDescription.xsd, fmi2ScalarVariable.xsd, fmi2Unit.xsd,
fmi2VariableDependency.xsd; docs/2_2_common_schema.adoc, docs/4_3_co-simulation_schema.adoc)
that an FMU written by `scenec --fmu --fmi-version 2` must keep, checked on an unpacked FMU:

  root       fmiModelDescription with fmiVersion "2.0", modelName, guid
  order      ModelExchange? CoSimulation? UnitDefinitions? TypeDefinitions? LogCategories?
             DefaultExperiment? VendorAnnotations? ModelVariables ModelStructure
  interface  modelIdentifier a C name, with binaries/linux64/<id>.so or sources/; boolean
             attributes true/false; every SourceFiles/File present under sources/
  units      UnitDefinitions, LogCategories, SourceFiles and the ModelStructure lists hold
             at least one child when present (the schema's minOccurs)
  variables  ScalarVariable with exactly one of Real, Integer, Boolean, String,
             Enumeration; unique names and value references; known causalities,
             variabilities and initials; exactly one independent variable (Real, no
             start, no initial); parameters fixed or tunable with a start and initial
             exact; inputs with a start; calculated outputs without one; every unit
             declared in UnitDefinitions
  structure  Outputs? Derivatives? InitialUnknowns? in that order; Outputs are exactly the
             outputs (1-based indices, ascending); InitialUnknowns hold every output whose
             initial is calculated or approx, ascending
  experiment startTime < stopTime, stepSize > 0

Usage: check_md2.py FMU_DIR; prints one line per rule broken and exits 1, or "ok"."""
import os
import re
import sys
import xml.etree.ElementTree as ET

ORDER = ["ModelExchange", "CoSimulation", "UnitDefinitions", "TypeDefinitions",
         "LogCategories", "DefaultExperiment", "VendorAnnotations", "ModelVariables",
         "ModelStructure"]
STRUCT = ["Outputs", "Derivatives", "InitialUnknowns"]
TYPES = {"Real", "Integer", "Boolean", "String", "Enumeration"}
CAUSALITY = {"parameter", "calculatedParameter", "input", "output", "local", "independent"}
VARIABILITY = {"constant", "fixed", "tunable", "discrete", "continuous"}
INITIAL = {"exact", "approx", "calculated"}
BOOLS = ["needsExecutionTool", "canHandleVariableCommunicationStepSize",
         "canInterpolateInputs", "canRunAsynchronuously",
         "canBeInstantiatedOnlyOncePerProcess", "canNotUseMemoryManagementFunctions",
         "canGetAndSetFMUstate", "canSerializeFMUstate", "providesDirectionalDerivative",
         "completedIntegratorStepNotNeeded"]


def initial_of(c, v):
    """the initial a variable has when it gives none (2_2_common_schema, the table of
    causality, variability and initial)"""
    if c in ("parameter",):
        return "exact"
    if c in ("calculatedParameter", "output", "local"):
        return "calculated" if v != "constant" else "exact"
    return None


def check_interface(d, root, errs):
    ifaces = [c for c in root if c.tag in ("ModelExchange", "CoSimulation")]
    if not ifaces:
        errs.append("no interface element")
    for i in ifaces:
        mid = i.get("modelIdentifier", "")
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", mid):
            errs.append("%s: modelIdentifier %r is not a C name" % (i.tag, mid))
        elif not os.path.exists(os.path.join(d, "binaries", "linux64", mid + ".so")) \
                and not os.path.isdir(os.path.join(d, "sources")):
            errs.append("%s: neither binaries/linux64/%s.so nor sources/" % (i.tag, mid))
        for b in BOOLS:
            if i.get(b) not in (None, "true", "false"):
                errs.append("%s: %s=%r is not a boolean" % (i.tag, b, i.get(b)))
        sf = i.find("SourceFiles")
        if sf is not None and len(sf) == 0:
            errs.append("%s: an empty SourceFiles" % i.tag)
        for f in (sf if sf is not None else []):
            if f.tag != "File" or not os.path.exists(os.path.join(d, "sources", f.get("name", ""))):
                errs.append("%s: SourceFiles <%s name=%r> missing under sources/"
                            % (i.tag, f.tag, f.get("name")))


def check_variables(root, errs):
    """the variables by 1-based index: (name, causality, initial) and the errors"""
    units = {u.get("name") for u in root.iter("Unit")}
    mv = root.find("ModelVariables")
    names, vrs, byidx, indep = set(), set(), {}, 0
    for k, sv in enumerate(mv if mv is not None else [], 1):
        n = sv.get("name")
        where = "variable %d %r" % (k, n)
        if sv.tag != "ScalarVariable":
            errs.append("%s: <%s> in ModelVariables" % (where, sv.tag))
            continue
        kids = [t for t in sv if t.tag in TYPES]
        if len(kids) != 1:
            errs.append("%s: %d type elements (exactly one of %s)" % (where, len(kids), TYPES))
            continue
        t = kids[0]
        c = sv.get("causality", "local")
        v = sv.get("variability", "continuous" if t.tag == "Real" else "discrete")
        init = sv.get("initial")
        if not n or n in names:
            errs.append("%s: missing or repeated name" % where)
        names.add(n)
        vr = sv.get("valueReference")
        if vr is None or not vr.isdigit() or (t.tag, vr) in vrs:
            errs.append("%s: missing or repeated valueReference %r" % (where, vr))
        vrs.add((t.tag, vr))
        if c not in CAUSALITY or v not in VARIABILITY or (init and init not in INITIAL):
            errs.append("%s: causality %r / variability %r / initial %r unknown"
                        % (where, c, v, init))
        start = t.get("start")
        if c == "independent":
            indep += 1
            if t.tag != "Real" or start is not None or init:
                errs.append("%s: the independent variable must be Real without start or "
                            "initial" % where)
        if c == "parameter" and (v not in ("fixed", "tunable") or start is None
                                 or (init or "exact") != "exact"):
            errs.append("%s: a parameter must be fixed or tunable, exact, with a start" % where)
        if c == "input" and start is None:
            errs.append("%s: an input needs a start" % where)
        eff = init or initial_of(c, v)
        if eff == "calculated" and start is not None:
            errs.append("%s: a calculated variable may not have a start" % where)
        if t.get("unit") and t.get("unit") not in units:
            errs.append("%s: unit %r not in UnitDefinitions" % (where, t.get("unit")))
        byidx[k] = (n, c, eff)
    if indep != 1:
        errs.append("%d independent variables (exactly one required)" % indep)
    return byidx


def check_structure(root, byidx, errs):
    ms = root.find("ModelStructure")
    if ms is None:
        errs.append("no <ModelStructure>")
        return
    kids = [c.tag for c in ms]
    k_idx = [STRUCT.index(t) if t in STRUCT else -1 for t in kids]
    if -1 in k_idx or k_idx != sorted(k_idx) or len(set(kids)) != len(kids):
        errs.append("ModelStructure elements out of order, repeated or unknown: %s" % kids)
    lists = {}
    for lst in ms:
        if len(lst) == 0:
            errs.append("ModelStructure: an empty <%s>" % lst.tag)
        idx = []
        for u in lst:
            i = u.get("index", "")
            if u.tag != "Unknown" or not i.isdigit() or int(i) not in byidx:
                errs.append("ModelStructure/%s: <%s index=%r> names no variable"
                            % (lst.tag, u.tag, i))
            else:
                idx.append(int(i))
        if idx != sorted(set(idx)):
            errs.append("ModelStructure/%s: indices not ascending and unique" % lst.tag)
        lists[lst.tag] = idx
    outputs = [k for k, (n, c, e) in sorted(byidx.items()) if c == "output"]
    if lists.get("Outputs", []) != outputs:
        errs.append("ModelStructure Outputs %s are not the outputs %s"
                    % (lists.get("Outputs", []), outputs))
    need = [k for k in outputs if byidx[k][2] in ("calculated", "approx")]
    missing = [k for k in need if k not in lists.get("InitialUnknowns", [])]
    if missing:
        errs.append("ModelStructure InitialUnknowns lack the outputs %s" % missing)


def check(d):
    errs = []
    root = ET.parse(os.path.join(d, "modelDescription.xml")).getroot()
    if root.tag != "fmiModelDescription":
        return ["root element is %s" % root.tag]
    if root.get("fmiVersion") != "2.0":
        errs.append("fmiVersion %r is not 2.0" % root.get("fmiVersion"))
    for a in ("modelName", "guid"):
        if not root.get(a):
            errs.append("fmiModelDescription lacks %s" % a)
    tags = [c.tag for c in root]
    idx = [ORDER.index(t) if t in ORDER else -1 for t in tags]
    if -1 in idx or idx != sorted(idx) or len(set(tags)) != len(tags):
        errs.append("elements out of the schema's order or unknown: %s" % tags)
    for t in ("ModelVariables", "ModelStructure"):
        if t not in tags:
            errs.append("no <%s>" % t)
    for t, child in (("UnitDefinitions", "Unit"), ("LogCategories", "Category")):
        e = root.find(t)
        if e is not None and (len(e) == 0 or any(c.tag != child for c in e)):
            errs.append("<%s> must hold one or more <%s>" % (t, child))
    check_interface(d, root, errs)
    byidx = check_variables(root, errs)
    check_structure(root, byidx, errs)
    de = root.find("DefaultExperiment")
    if de is not None:
        t0, t1, h = (float(de.get(a, x)) for a, x in
                     (("startTime", "0"), ("stopTime", "inf"), ("stepSize", "1")))
        if not (t0 < t1 and h > 0):
            errs.append("DefaultExperiment: startTime %g, stopTime %g, stepSize %g" % (t0, t1, h))
    return errs


def main():
    errs = check(sys.argv[1])
    for e in errs:
        print("check_md2: %s: %s" % (sys.argv[1], e))
    if not errs:
        print("check_md2: %s: ok" % sys.argv[1])
    return 1 if errs else 0


if __name__ == "__main__":
    sys.exit(main())
