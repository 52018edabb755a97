#!/usr/bin/env python3
"""Checks the Unity stand-ins (COMPILE CHECK ONLY) against Unity's published C# reference source.

Reads a bare clone of github.com/Unity-Technologies/UnityCsReference (branches 2022.3, 6000.x) and
  gen    writes */Generated.TypeNames.cs: an empty declaration for every public top-level type name
         Unity has in the namespaces the package can see (UnityEngine*, UnityEditor, Unity.Collections*,
         and every Unity namespace the package imports) that the hand-written stand-ins lack, so a
         Drape type that shadows a Unity type fails our compile check the way it would fail in Unity;
  check  verifies every public member the hand-written stand-ins declare against Unity's source in
         each branch: same name, static-ness, parameter types (ref/out/in, params), return or
         property type, accessors, and Obsolete state (the stand-in compiled with that branch's
         UNITY_* defines must be Obsolete where Unity's is, and an error where Unity's is).
Only names and signatures are read from Unity's source; nothing of it is copied here.

Usage: python3 unity_api.py GIT_DIR gen|check [--branches 2022.3,6000.0,6000.5] [--cache FILE (gen)]
The parser is a brace-level scanner, not a C# compiler: comments, strings and preprocessor lines
are dropped (both sides of an #if are kept), which is exact for declarations at type level.
"""
import json
import re
import subprocess
import sys
import threading
from collections import defaultdict
from pathlib import Path

HERE = Path(__file__).resolve().parent
PACKAGE = HERE.parents[2] / "unity-package"
BRANCHES = ["2022.3", "6000.0", "6000.3", "6000.5"]
# The stand-in flavours the compile checks build (see ../CompileCheck/UnityVersion.props): each
# branch is checked against the flavour whose defines it would set.
FLAVOUR_DEFINES = {
    "2022.3": {"UNITY_2022_3_OR_NEWER"},
    "6000.0": {"UNITY_2022_3_OR_NEWER", "UNITY_2023_1_OR_NEWER", "UNITY_6000_0_OR_NEWER"},
    "6000.3": {"UNITY_2022_3_OR_NEWER", "UNITY_2023_1_OR_NEWER", "UNITY_6000_0_OR_NEWER",
               "UNITY_6000_2_OR_NEWER"},
    "6000.5": {"UNITY_2022_3_OR_NEWER", "UNITY_2023_1_OR_NEWER", "UNITY_6000_0_OR_NEWER",
               "UNITY_6000_2_OR_NEWER", "UNITY_6000_4_OR_NEWER", "UNITY_6000_5_OR_NEWER"},
}
STANDINS = {
    "UnityEngine": HERE / "UnityEngine" / "UnityEngine.cs",
    "UnityEditor": HERE / "UnityEditor" / "UnityEditor.cs",
}
MODIFIERS = {"public", "private", "protected", "internal", "static", "extern", "virtual", "override",
             "abstract", "sealed", "new", "unsafe", "readonly", "partial", "async", "volatile", "const",
             "ref", "required", "file"}
TYPE_RE = re.compile(r"\b(class|struct|interface|enum|record)\s+(@?\w+)\s*(<[^{]*?>)?")
DELEGATE_RE = re.compile(r"\bdelegate\s+(.+?)\s+(\w+)\s*(<[^(]*>)?\s*\(")


# ----------------------------------------------------------------------------- scanning

def clean(text, defines=None):
    """Drops comments, string/char literal contents and preprocessor lines. With `defines`, #if
    blocks are evaluated (simple symbols, !, &&, ||); without, every branch is kept."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if c == "/" and text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif c == "/" and text.startswith("/*", i):
            j = text.find("*/", i + 2)
            i = n if j < 0 else j + 2
            out.append(" ")
        elif c == '"' or (c in "@$" and text[i + 1:i + 2] == '"') or text.startswith('$@"', i) or text.startswith('@$"', i):
            verbatim = "@" in text[i:i + 2]
            j = text.index('"', i) + 1
            while j < n:
                if text[j] == "\\" and not verbatim:
                    j += 2
                    continue
                if text[j] == '"':
                    if verbatim and text[j + 1:j + 2] == '"':
                        j += 2
                        continue
                    break
                j += 1
            out.append('""')
            i = j + 1
        elif c == "'":
            j = i + 1
            while j < n and text[j] != "'":
                j += 2 if text[j] == "\\" else 1
            out.append("'x'")
            i = j + 1
        else:
            out.append(c)
            i += 1
    lines, frames = [], []  # frames: [parent visible, a branch was taken, this branch visible]
    for line in "".join(out).split("\n"):
        s = line.strip()
        visible = frames[-1][2] if frames else True
        if s.startswith("#"):
            if defines is not None:
                word = s[1:].strip().split(None, 1)
                kw, rest = (word + [""])[:2] if word else ("", "")
                if kw == "if":
                    take = visible and evaluate(rest, defines)
                    frames.append([visible, take, take])
                elif kw == "elif" and frames:
                    f = frames[-1]
                    take = f[0] and not f[1] and evaluate(rest, defines)
                    f[1], f[2] = f[1] or take, take
                elif kw == "else" and frames:
                    f = frames[-1]
                    f[2] = f[0] and not f[1]
                    f[1] = True
                elif kw == "endif" and frames:
                    frames.pop()
            lines.append("")
            continue
        lines.append(line if defines is None or visible else "")
    return "\n".join(lines)


def evaluate(expr, defines):
    py = re.sub(r"\b[A-Za-z_]\w*\b", lambda m: "True" if m.group(0) in defines or m.group(0) == "true" else "False", expr)
    py = py.replace("&&", " and ").replace("||", " or ").replace("!", " not ")
    return bool(eval(py))  # noqa: S307 - our own preprocessor lines only


def strip_attributes(header):
    """Removes leading [Attribute(...)] groups; returns (attribute text, rest)."""
    h, attrs = header.strip(), []
    while h.startswith("["):
        depth = 0
        for k, ch in enumerate(h):
            depth += ch == "["
            depth -= ch == "]"
            if depth == 0:
                attrs.append(h[:k + 1])
                h = h[k + 1:].strip()
                break
        else:
            break
    return " ".join(attrs), h


def split_top(s, sep=","):
    parts, depth, cur = [], 0, []
    for ch in s:
        if ch in "<([{":
            depth += 1
        elif ch in ">)]}":
            depth -= 1
        if ch == sep and depth == 0:
            parts.append("".join(cur))
            cur = []
        else:
            cur.append(ch)
    if "".join(cur).strip():
        parts.append("".join(cur))
    return parts


def norm_type(t, generic_map=None):
    t = re.sub(r"\s+", " ", t.strip())
    t = re.sub(r"\b(global::)?([A-Za-z_]\w*\.)+(?=[A-Za-z_])", "", t)  # drop namespace/outer qualifiers
    t = t.replace(" ", "")
    if generic_map:
        t = re.sub(r"\b\w+\b", lambda m: generic_map.get(m.group(0), m.group(0)), t)
    return {"Boolean": "bool", "Single": "float", "Double": "double", "Int32": "int", "UInt32": "uint", "Int64": "long",
            "UInt64": "ulong", "Int16": "short", "UInt16": "ushort", "Byte": "byte", "SByte": "sbyte", "Char": "char",
            "String": "string", "Void": "void"}.get(t, t)


def parse_params(text, generic_map):
    out = []
    for p in split_top(text):
        _, p = strip_attributes(p)
        p = p.split("=")[0].strip()
        words = p.split()
        mods = [w for w in words[:-1] if w in ("ref", "out", "in", "params", "this")]
        typ = " ".join(w for w in words[:-1] if w not in ("ref", "out", "in", "params", "this", "scoped"))
        tag = "".join(m + " " for m in mods if m != "this")
        out.append(tag + norm_type(typ, generic_map))
    return tuple(out)


class Member:
    def __init__(self, kind, name, static, params, rtype, attrs, where):
        self.kind, self.name, self.static, self.params, self.rtype = kind, name, static, params, rtype
        self.accessors = set()
        self.obsolete = obsolete_state(attrs)
        self.where = where

    def key(self):
        return (self.kind, self.name, self.params)

    def __repr__(self):
        p = "(" + ", ".join(self.params) + ")" if self.kind in ("method", "ctor", "operator") else ""
        acc = " {" + " ".join(sorted(self.accessors)) + "}" if self.kind == "property" else ""
        return ("static " if self.static else "") + f"{self.rtype} {self.name}{p}{acc}"


def obsolete_state(attrs):
    m = re.search(r"\bObsolete(Attribute)?\b(\s*\(([^)]*)\))?", attrs)
    if not m:
        return None
    args = m.group(3) or ""
    return "error" if re.search(r"\btrue\b", args) else "warning"


class TypeInfo:
    def __init__(self, ns, name, arity, kind, public, static, bases):
        self.ns, self.name, self.arity, self.kind, self.public, self.static = ns, name, arity, kind, public, static
        self.bases = bases
        self.members = []
        self.files = set()


def scan(text, path, types, defines=None):
    """Adds the types and members declared in `text` to `types` ({(ns, name, arity): TypeInfo};
    nested types are keyed with their outer names joined by '+')."""
    text = clean(text, defines)
    # using aliases (using UnityObject = UnityEngine.Object;) read as the type they name
    aliases = {m.group(1): m.group(2).split(".")[-1] for m in re.finditer(r"^\s*using\s+(\w+)\s*=\s*([\w.]+)\s*;", text, re.M)}
    stack = []  # entries: ("ns", name) | ("type", TypeInfo, generic_map) | ("prop", Member) | ("block",)
    file_ns = None
    header = []
    for ch in text:
        if ch not in "{};":
            header.append(ch)
            continue
        h = "".join(header).strip()
        header = []
        top = stack[-1] if stack else ("ns", file_ns)
        if ch == "}":
            if stack:
                stack.pop()
            continue
        attrs, body = strip_attributes(h)
        if top[0] == "ns":
            m = re.match(r"^namespace\s+([\w.]+)$", body)
            if m:
                name = m.group(1)
                outer = top[1]
                full = outer + "." + name if outer else name
                if ch == "{":
                    stack.append(("ns", full))
                else:
                    file_ns = full
                continue
        if top[0] in ("ns", "type"):
            ns = top[1] if top[0] == "ns" else top[1].ns
            outer = "" if top[0] == "ns" else top[1].name + "+"
            words = body.replace("<", " <").split()
            mods = set()
            for w in words:
                if w in MODIFIERS:
                    mods.add(w)
                else:
                    break
            tm = TYPE_RE.search(body)
            if ch == "{" and tm and "(" not in body[:tm.start()] and "=" not in body[:tm.start()]:
                arity = 0 if not tm.group(3) else len(split_top(tm.group(3)[1:-1]))
                name = outer + tm.group(2)
                key = (ns, name, arity)
                bases = []
                rest = body[tm.end():]
                if ":" in rest:
                    bases = [norm_type(b.split("where")[0]) for b in split_top(rest.split(":", 1)[1].split(" where ")[0])]
                info = types.get(key)
                public = "public" in mods and (top[0] == "ns" or top[1].public)
                if info is None:
                    info = types[key] = TypeInfo(ns, name, arity, tm.group(1), public, "static" in mods, bases)
                else:
                    info.public = info.public or public
                    info.bases = info.bases or bases
                info.files.add(path)
                gm = dict(aliases)
                if tm.group(3):
                    for k, g in enumerate(split_top(tm.group(3)[1:-1])):
                        gm[g.strip().split()[-1]] = f"T{k}"
                if top[0] == "type":
                    gm = {**top[2], **gm}
                stack.append(("type", info, gm))
                continue
            dm = DELEGATE_RE.search(body)
            if ch == ";" and dm and "public" in mods:
                arity = 0 if not dm.group(3) else len(split_top(dm.group(3)[1:-1]))
                key = (ns, outer + dm.group(2), arity)
                if key not in types:
                    types[key] = TypeInfo(ns, outer + dm.group(2), arity, "delegate", top[0] == "ns" or top[1].public,
                                          False, [])
                types[key].files.add(path)
                continue
            if top[0] == "type":
                member = parse_member(body, attrs, mods, top[1], top[2], ch, path)
                if member is not None:
                    top[1].members.append(member)
                    if ch == "{":
                        stack.append(("prop", member) if member.kind in ("property", "event", "indexer") else ("block",))
                        continue
                if ch == "{":
                    stack.append(("block",))
                continue
            if ch == "{":
                stack.append(("block",))
            continue
        if top[0] == "prop":
            if ch == "{":
                stack.append(("block",))
            acc_attrs, acc = strip_attributes(body)
            acc_words = acc.split("=>")[0].split()
            if acc_words and acc_words[-1] in ("get", "set", "init", "add", "remove"):
                private = any(w in ("private", "internal", "protected") for w in acc_words[:-1])
                if not private:
                    top[1].accessors.add(acc_words[-1])
            continue
        if ch == "{":
            stack.append(("block",))
    return types


def parse_member(body, attrs, mods, owner, gmap, ch, path):
    if "public" not in mods and "protected" not in mods and owner.kind != "interface":
        return None  # protected members count: derived classes (our editors) call them
    b = body
    expr_bodied = "=>" in b
    sig = b.split("=>")[0] if expr_bodied else b
    static = "static" in mods or "const" in mods
    words_after = re.sub(r"^(\s*(" + "|".join(MODIFIERS) + r")\b)+", "", sig).strip()
    if words_after.startswith("event "):
        m = re.match(r"event\s+(.+?)\s+(\w+)\s*$", words_after.split("=")[0].strip())
        if not m:
            return None
        mem = Member("event", m.group(2), static, (), norm_type(m.group(1), gmap), attrs, path)
        mem.accessors.update({"add", "remove"})
        return mem
    if "operator" in words_after.split("(")[0]:
        m = re.match(r"(.*?)\boperator\s*(.+?)\s*\((.*)\)\s*$", words_after, re.S)
        if not m:
            return None
        rtype = m.group(1).strip()
        name = "operator " + m.group(2).strip()
        if rtype in ("implicit", "explicit"):
            name, rtype = rtype + " operator", m.group(2).strip()
        return Member("operator", name, True, parse_params(m.group(3), gmap), norm_type(rtype, gmap), attrs, path)
    paren = sig.find("(")
    eq = sig.find("=")
    if paren >= 0 and (eq < 0 or paren < eq):
        head = words_after[:words_after.find("(")].strip()
        close = matching_paren(words_after, words_after.find("("))
        params_text = words_after[words_after.find("(") + 1:close]
        hm = re.match(r"^(.*?)\s*([\w]+)\s*(<[^<>]*(<[^<>]*>[^<>]*)*>)?$", head)
        if not hm:
            return None
        rtype, name = hm.group(1).strip(), hm.group(2)
        local = dict(gmap)
        if hm.group(3):
            for k, g in enumerate(split_top(hm.group(3)[1:-1])):
                local[g.strip()] = f"M{k}"
            name += f"`{len(split_top(hm.group(3)[1:-1]))}"
        short = owner.name.split("+")[-1]
        if rtype == "" and name == short:
            return Member("ctor", ".ctor", static, parse_params(params_text, local), "", attrs, path)
        if rtype == "" or rtype == "this":
            return None
        return Member("method", name, static, parse_params(params_text, local), norm_type(rtype, local), attrs, path)
    decl = words_after.split("=")[0].strip() if not expr_bodied else words_after.strip()
    if "this[" in decl.replace(" ", ""):
        m = re.match(r"(.+?)\s*this\s*\[(.*)\]\s*$", decl)
        if not m:
            return None
        mem = Member("indexer", "this[]", False, parse_params(m.group(2), gmap), norm_type(m.group(1), gmap), attrs, path)
        if expr_bodied:
            mem.accessors.add("get")
        return mem
    parts = split_top(decl)
    first = parts[0].split()
    if len(first) < 2:
        return None
    rtype = norm_type(" ".join(first[:-1]), gmap)
    if ch == "{" and eq < 0:
        return Member("property", first[-1], static, (), rtype, attrs, path)
    if expr_bodied:
        mem = Member("property", first[-1], static, (), rtype, attrs, path)
        mem.accessors.add("get")
        return mem
    # fields (possibly several: "public float x, y;")
    mem = Member("field", first[-1], static, (), rtype, attrs, path)
    mem.readonly = "readonly" in mods or "const" in mods
    mem.extra = [p.strip().split("=")[0].strip() for p in parts[1:]]
    return mem


def matching_paren(s, i):
    depth = 0
    for k in range(i, len(s)):
        depth += s[k] == "("
        depth -= s[k] == ")"
        if depth == 0:
            return k
    return len(s)


# ----------------------------------------------------------------------------- Unity's source

def unity_types(git_dir, branch):
    files = subprocess.run(["git", f"--git-dir={git_dir}", "ls-tree", "-r", "--name-only", branch],
                           check=True, capture_output=True, text=True).stdout.split("\n")
    files = [f for f in files if f.endswith(".cs")]
    proc = subprocess.Popen(["git", f"--git-dir={git_dir}", "cat-file", "--batch"], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE)
    def feed():  # in a thread: cat-file's output would fill its pipe before all names are written
        proc.stdin.write("".join(f"{branch}:{f}\n" for f in files).encode())
        proc.stdin.close()
    threading.Thread(target=feed, daemon=True).start()
    types = {}
    for f in files:
        head = proc.stdout.readline().split()
        size = int(head[2])
        data = proc.stdout.read(size).decode("utf-8", "replace")
        proc.stdout.read(1)
        try:
            scan(data, f, types)
        except Exception as e:  # a file the scanner cannot follow: say so, never hide it
            print(f"warning: {branch}:{f}: not scanned ({e})", file=sys.stderr)
    proc.wait()
    return types


def visible_namespaces():
    ns = {"UnityEngine", "UnityEditor", "Unity.Collections"}
    for f in PACKAGE.rglob("*.cs"):
        for m in re.finditer(r"^\s*using\s+([\w.]+)\s*;", f.read_text(), re.M):
            if m.group(1).split(".")[0] in ("UnityEngine", "UnityEditor", "Unity", "AOT"):
                ns.add(m.group(1))
    return ns


def wanted(ns, visible):
    return ns in visible or ns.startswith("UnityEngine.") or ns.startswith("Unity.Collections.")


# ----------------------------------------------------------------------------- commands

def gen(git_dir, branches):
    visible = visible_namespaces()
    union = {}
    cache = Path(sys.argv[sys.argv.index("--cache") + 1]) if "--cache" in sys.argv else None
    if cache is not None and cache.exists():  # the names of an earlier run (same branches): re-emit quickly
        for ns, name, arity, kind, static in json.loads(cache.read_text()):
            union[(ns, name, arity)] = TypeInfo(ns, name, arity, kind, True, static, [])
    else:
        for br in branches:
            for key, t in unity_types(git_dir, br).items():
                if t.public and "+" not in t.name and wanted(t.ns, visible):
                    union.setdefault(key, t)
        if cache is not None:
            cache.write_text(json.dumps([[t.ns, t.name, t.arity, t.kind, t.static] for t in union.values()]))
    hand = {}
    for f in list(STANDINS.values()) + [HERE / "InputSystem" / "InputSystem.cs"]:
        scan(f.read_text(), str(f), hand)
    by_assembly = {"UnityEngine": defaultdict(list), "UnityEditor": defaultdict(list)}
    for (ns, name, arity), t in sorted(union.items()):
        if any(k[0] == ns and k[1] == name and k[2] == arity for k in hand):
            continue
        asm = "UnityEditor" if ns == "UnityEditor" or ns.startswith("UnityEditor.") else "UnityEngine"
        by_assembly[asm][ns].append(t)
    for asm, spaces in by_assembly.items():
        lines = ["// GENERATED by tests/dotnet/UnityStandIn/unity_api.py from Unity's C# reference source",
                 f"// (branches {', '.join(branches)}): every public top-level type name in the namespaces the",
                 "// package can see that the hand-written stand-in does not declare. Names only, no members:",
                 "// they exist so that a Drape type shadowing a Unity type fails the compile check.",
                 "// COMPILE CHECK ONLY. Regenerate, do not edit.",
                 "#pragma warning disable CS0108, CS0109",
                 ""]
        count = 0
        for ns in sorted(spaces):
            lines.append(f"namespace {ns}")
            lines.append("{")
            for t in sorted(spaces[ns], key=lambda t: (t.name, t.arity)):
                gen_args = "" if t.arity == 0 else "<" + ", ".join(f"T{k}" for k in range(t.arity)) + ">"
                if t.kind == "delegate":
                    lines.append(f"    public delegate void {t.name}{gen_args}();")
                elif t.kind == "record":
                    lines.append(f"    public class {t.name}{gen_args} {{ }}")
                else:
                    static = "static " if t.static and t.kind == "class" else ""
                    lines.append(f"    public {static}{t.kind} {t.name}{gen_args} {{ }}")
                count += 1
            lines.append("}")
            lines.append("")
        out = HERE / asm / "Generated.TypeNames.cs"
        out.write_text("\n".join(lines))
        print(f"{out.relative_to(HERE)}: {count} type names")


def check(git_dir, branches):
    problems = []
    evidence = []
    for br in branches:
        unity = unity_types(git_dir, br)
        defines = FLAVOUR_DEFINES[br]
        for asm, path in STANDINS.items():
            hand = scan(path.read_text(), path.name, {}, defines)
            for key, t in sorted(hand.items()):
                ns, name, arity = key
                if not t.public or ns in ("UnityEditor",) and name == "StandIn":
                    continue
                u = unity.get(key)
                if u is None or not u.public:
                    problems.append(f"{br}: type {ns}.{name}`{arity}: not a public type in Unity")
                    continue
                if t.kind != u.kind and not (t.kind == "class" and u.kind == "record"):
                    problems.append(f"{br}: {ns}.{name}: stand-in {t.kind}, Unity {u.kind}")
                if t.static != u.static:
                    problems.append(f"{br}: {ns}.{name}: static mismatch")
                if t.bases and t.bases[0] != "Attribute" and u.bases and t.bases[0] not in u.bases and u.kind == "class":
                    problems.append(f"{br}: {ns}.{name}: base {t.bases[0]}, Unity {u.bases}")
                for m in t.members:
                    names = [m.name] + getattr(m, "extra", [])
                    for nm in names:
                        found = find_member(unity, u, m, nm)
                        where = f"{ns}.{name}.{nm}"
                        if found is None:
                            problems.append(f"{br}: {where}: no public Unity member matches {m!r}")
                            continue
                        if found.static != m.static:
                            problems.append(f"{br}: {where}: static differs from Unity")
                        if m.kind != "ctor" and found.rtype != m.rtype:
                            problems.append(f"{br}: {where}: type {m.rtype}, Unity {found.rtype}")
                        if m.kind in ("property", "indexer", "event"):
                            extra = m.accessors - found.accessors
                            if extra:
                                problems.append(f"{br}: {where}: accessor(s) {sorted(extra)} not public in Unity")
                        if m.kind == "field" and found.kind == "field" and getattr(found, "readonly", False) != getattr(m, "readonly", False):
                            problems.append(f"{br}: {where}: readonly differs from Unity")
                        if m.kind == "field" and found.kind == "property":
                            problems.append(f"{br}: {where}: a field here, a property in Unity")
                        if found.obsolete != m.obsolete:
                            problems.append(f"{br}: {where}: Obsolete in Unity: {found.obsolete}, stand-in: {m.obsolete}")
                        evidence.append(f"{br}\t{where}\t{m!r}\t{found.where}")
    (HERE / "unity-api-evidence.tsv").write_text(
        "# branch\tmember\tstand-in signature\tUnity source file declaring it (UnityCsReference)\n"
        + "\n".join(sorted(set(evidence))) + "\n")
    for p in problems:
        print(p)
    print(f"{len(problems)} problem(s); {len(evidence)} member checks recorded in unity-api-evidence.tsv")
    return 1 if problems else 0


def find_member(unity, u, m, nm, seen=None):
    seen = seen or set()
    for cand in u.members:
        names = [cand.name] + getattr(cand, "extra", [])
        if nm not in names:
            continue
        if m.kind in ("method", "ctor", "operator", "indexer"):
            if cand.kind == m.kind and cand.params == m.params:
                return cand
        elif m.kind in ("property", "field"):
            if cand.kind in ("property", "field"):
                return cand
        elif cand.kind == m.kind:
            return cand
    if m.kind == "ctor":
        return None
    for b in u.bases:
        for key, t in unity.items():
            if key[1] == b and key not in seen and t.kind in ("class", "interface", "struct"):
                seen.add(key)
                r = find_member(unity, t, m, nm, seen)
                if r is not None:
                    return r
    return None


def main():
    git_dir, cmd = sys.argv[1], sys.argv[2]
    branches = BRANCHES
    if "--branches" in sys.argv:
        branches = sys.argv[sys.argv.index("--branches") + 1].split(",")
    if cmd == "gen":
        gen(git_dir, branches)
        return 0
    return check(git_dir, branches)


if __name__ == "__main__":
    sys.exit(main())
