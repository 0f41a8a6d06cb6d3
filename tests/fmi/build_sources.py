#!/usr/bin/env python3
"""build_sources.py - builds a source FMU's binary as an importer would, from nothing but
its sources/buildDescription.xml (FMI 3.0, also in FMI 2.0.4 FMUs): every SourceFile,
PreprocessorDefinition, IncludeDirectory and Library of its first BuildConfiguration,
compiled with $CC (else cc) in sources/ into OUT.so. It defines
FMI2_OVERRIDE_FUNCTION_PREFIX or FMI3_OVERRIDE_FUNCTION_PREFIX, as the standard tells an
importer building a shared object to (the functions keep their plain names). Usage: build_sources.py FMU_DIR OUT.so"""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET


def main():
    d, out = sys.argv[1], os.path.abspath(sys.argv[2])
    src = os.path.join(d, "sources")
    bc = ET.parse(os.path.join(src, "buildDescription.xml")).getroot().find("BuildConfiguration")
    cmd = [os.environ.get("CC") or "cc", "-shared", "-fPIC", "-O2", "-w"]
    md = ET.parse(os.path.join(d, "modelDescription.xml")).getroot()
    cmd.append("-DFMI%s_OVERRIDE_FUNCTION_PREFIX" % md.get("fmiVersion")[0])
    for s in bc.iter("SourceFileSet"):
        cmd += (s.get("compilerOptions") or "").split()
        cmd += ["-std=c11"] if s.get("language") == "C11" else []
        cmd += ["-I" + i.get("name") for i in s.iter("IncludeDirectory")]
        cmd += ["-D%s=%s" % (p.get("name"), p.get("value")) if p.get("value") is not None
                else "-D" + p.get("name") for p in s.iter("PreprocessorDefinition")]
        cmd += [f.get("name") for f in s.iter("SourceFile")]
    cmd += ["-o", out] + ["-l" + lib.get("name") for lib in bc.iter("Library")]
    return subprocess.run(cmd, cwd=src).returncode


if __name__ == "__main__":
    sys.exit(main())
