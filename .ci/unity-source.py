#!/usr/bin/env python3
"""Writes the Unity source plug-in: the native library as one self-contained C++ file.

IL2CPP compiles C/C++ files placed in a package (enabled per platform in their .meta) together
with its generated code; it gives them no include path of ours, and .hpp/.inl files are not
among the extensions it picks up. So the library's sources, its own headers, the generated
shader header and the glm and Eigen headers it uses are inlined into one translation unit, in the order
and with the definitions CMake uses for the `drape` target (read from the manifest that
plugin-native/cmake/source-manifest.cmake writes at configure time). System and platform
headers (<vector>, <EGL/egl.h>, <arm_neon.h>, ...) stay #includes.

Usage: unity-source.py <manifest> <output.cpp>
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
PRAGMA_ONCE = re.compile(r'^\s*#\s*pragma\s+once\b')
IF = re.compile(r'^\s*#\s*if(n?def)?\b')
ENDIF = re.compile(r'^\s*#\s*endif\b')
IFNDEF = re.compile(r'^\s*#\s*ifndef\s+(\w+)')
DEFINE = re.compile(r'^\s*#\s*define\s+(\w+)')
UNDEF = re.compile(r'^\s*#\s*undef\s+(\w+)', re.M)
# Header-only libraries inlined from their include directory (everything else in <> stays).
THIRD_PARTY = ("glm/", "Eigen/")


def read_manifest(path):
    m = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            key, _, value = line.rstrip("\n").partition("=")
            m[key] = [v for v in value.split(";") if v]
    return m


def classic_guard(lines):
    """Name of an #ifndef/#define include guard opening the file, or None."""
    directives = []
    in_comment = False
    for line in lines:
        t = line.strip()
        if in_comment:
            in_comment = "*/" not in t
            continue
        if not t or t.startswith("//"):
            continue
        if t.startswith("/*"):
            in_comment = "*/" not in t
            continue
        directives.append(t)
        if len(directives) == 2:
            break
    if len(directives) == 2:
        a, b = IFNDEF.match(directives[0]), DEFINE.match(directives[1])
        if a and b and a.group(1) == b.group(1):
            return a.group(1)
    return None


class Amalgamator:
    """Inlines quoted includes and third-party headers. A header that is included once only (it
    has #pragma once, or an include guard nobody #undefs) is inlined at its first include that no
    #if encloses, and skipped after that; an include inside an #if block is inlined there (its
    guard, or the guard that replaces #pragma once, keeps the compiler from reading it twice), so
    a header first reached in one platform's branch is still there for another's."""

    def __init__(self, root, include_dirs, dep_dirs):
        self.root = root
        self.include_dirs = include_dirs
        self.dep_dirs = dep_dirs
        self.done = set()
        self.out = []
        self.undefined = set()  # macros some inlined file #undefs (not usable as once-guards)
        self.active = set()  # files being inlined (include stack)

    def label(self, path):
        """Stable name for #line: repository-relative, <library>/..., or generated/..."""
        for d in self.dep_dirs:
            rel = os.path.relpath(path, d)
            if not rel.startswith("..") and rel.startswith(THIRD_PARTY):
                return rel
        rel = os.path.relpath(path, self.root)
        if rel.startswith(".."):
            return "generated/" + os.path.basename(path)
        if rel.startswith("build/"):  # generated into a build tree
            return "generated/" + rel.split("/generated/", 1)[-1]
        return rel

    def resolve(self, kind, name, including_dir):
        if kind == '"':
            for d in [including_dir] + self.include_dirs + self.dep_dirs:
                p = os.path.normpath(os.path.join(d, name))
                if os.path.isfile(p):
                    return p
            return None
        if name.startswith(THIRD_PARTY):
            for d in self.dep_dirs:
                p = os.path.normpath(os.path.join(d, name))
                if os.path.isfile(p):
                    return p
            raise SystemExit(f"unity-source: <{name}> not found in {self.dep_dirs}")
        return None  # system / platform header: stays an #include

    def inline(self, path, conditional=False):
        path = os.path.normpath(path)
        if path in self.done or path in self.active:  # an include cycle: its guard stops it
            return
        self.active.add(path)
        try:
            self._inline(path, conditional)
        finally:
            self.active.discard(path)

    def _inline(self, path, conditional):
        label = self.label(path)
        with open(path, encoding="utf-8") as f:
            lines = f.readlines()
        text = "".join(lines)
        self.undefined.update(UNDEF.findall(text))
        once = any(PRAGMA_ONCE.match(l) for l in lines)
        guard = classic_guard(lines)
        if not conditional and (once or (guard and guard not in self.undefined)):
            self.done.add(path)
        synthetic = "DRAPE_ONCE_" + re.sub(r"\W", "_", label).upper()
        self.out.append(f'#line 1 "{label}"\n')
        depth = 0          # #if nesting in this file, its include guard not counted
        guard_open = None  # depth of the include guard's #ifndef while it is open
        for n, line in enumerate(lines, 1):
            if PRAGMA_ONCE.match(line):
                self.out.append(f"#ifndef {synthetic}\n#define {synthetic}\n")
                continue
            if IF.match(line):
                m = IFNDEF.match(line)
                if guard and guard_open is None and depth == 0 and m and m.group(1) == guard:
                    guard_open = depth
                else:
                    depth += 1
            elif ENDIF.match(line):
                if depth == 0 and guard_open is not None:
                    guard_open = None
                else:
                    depth -= 1
            m = INCLUDE.match(line)
            target = m and self.resolve(m.group(1), m.group(2), os.path.dirname(path))
            if not target:
                if m and m.group(1) == '"' and not (conditional or depth > 0):
                    raise SystemExit(f"unity-source: {label}:{n}: \"{m.group(2)}\" not found")
                self.out.append(line if line.endswith("\n") else line + "\n")
                continue
            self.out.append(f"// {line.strip()}\n")
            self.inline(target, conditional or depth > 0)
            self.out.append(f'#line {n + 1} "{label}"\n')
        if once:
            self.out.append(f"\n#endif  // {synthetic}\n")


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    manifest = read_manifest(sys.argv[1])
    root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    sources = manifest["sources"]
    gles_dir = os.path.join(root, "plugin-native", "src", "backend", "gles") + os.sep
    plain = [s for s in sources if not s.startswith(gles_dir)]
    gles = [s for s in sources if s.startswith(gles_dir)]
    # Quoted includes resolve in the library's own directories only (not the system's).
    own = [d for d in manifest["include_dirs"] if (os.path.normpath(d) + os.sep).startswith(root + os.sep)]
    a = Amalgamator(root, own, manifest["dep_include_dirs"])

    version = "?"
    defines = []
    for d in manifest["definitions"]:
        name, _, value = d.partition("=")
        if name == "DRAPE_WITH_GLES":
            continue  # decided per platform below
        if name == "DRAPE_VERSION":
            version = value.strip('"')
        defines.append(f"#define {name} {value or 1}\n")

    glm_license = open(os.path.join(root, "plugin-native", "cmake", "glm-license.txt"), encoding="utf-8").read()
    head = [
        "// Drape native library as one C++17 translation unit: the Unity source plug-in for IL2CPP\n",
        "// players (Android, iOS), called through [DllImport(\"__Internal\")].\n",
        "// GENERATED by `bash .ci/unity-source.sh sync` from plugin-native/ (sources, headers, shaders)\n",
        "// and the glm and Eigen headers the library uses. Do not edit; `npm test` fails when it is stale.\n",
        f"// Drape {version}, MIT License (see LICENSE in the package).\n",
        "//\n",
        "// glm (OpenGL Mathematics, https://github.com/g-truc/glm), inlined below, is under the MIT\n",
        "// (Expat) license:\n",
    ] + ["// " + l if l.strip() else "//\n" for l in glm_license.splitlines(True)] + [
        "//\n",
        "// Eigen (https://eigen.tuxfamily.org), inlined below, is under the Mozilla Public License 2.0\n",
        "// (https://mozilla.org/MPL/2.0/): its files keep their notices; its source is this file's text.\n",
        "\n",
        "#if !(__cplusplus >= 201703L || (defined(_MSVC_LANG) && _MSVC_LANG >= 201703L))\n",
        "#error \"Drape needs C++17. Unity: PlayerSettings.SetAdditionalIl2CppArgs(\\\"--compiler-flags=-std=c++17\\\")\"\n",
        "#endif\n",
        # What CMake passes as options (-ffp-contract=off: the same bits on x86-64 and arm64).
        "#if defined(__clang__)\n#pragma STDC FP_CONTRACT OFF\n",
        "#elif defined(__GNUC__)\n#pragma GCC optimize(\"fp-contract=off\")\n#endif\n",
        # Statically linked into the player: Unity calls no UnityPluginLoad there, and other
        # static plug-ins may define the same names.
        "#define UnityPluginLoad DrapeUnityPluginLoad\n#define UnityPluginUnload DrapeUnityPluginUnload\n",
        # GLES backend where the player can run it: Android (entry points loaded at run time).
        "#if defined(__ANDROID__) && !defined(DRAPE_WITH_GLES)\n#define DRAPE_WITH_GLES 1\n#endif\n",
    ] + defines
    a.out.extend(head)
    for s in plain:
        a.inline(s)
    if gles:
        a.out.append("\n#if defined(DRAPE_WITH_GLES)\n")
        for s in gles:
            a.inline(s)
        a.out.append("\n#endif  // DRAPE_WITH_GLES\n")

    text = "".join(a.out)
    with open(sys.argv[2], "w", encoding="utf-8", newline="\n") as f:
        f.write(text)


if __name__ == "__main__":
    main()
