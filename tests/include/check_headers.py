#!/usr/bin/env python3
"""Checks tessera's GLES/gl.h, GLES/glext.h and EGL/egl.h against Khronos'.

For every GL_*/EGL_* macro defined in both, the values must agree; every
OpenGL ES 1.1 enum and entry point (float and fixed point) of the Khronos
GLES/gl.h, and every EGL 1.0-1.4 enum and entry point of the Khronos
EGL/egl.h, must be in ours; every macro of ours must be known to Khronos
(which catches misspelt names); and prototypes present in both must have the
same return and parameter types. Our GLES/glext.h, which declares only the
extensions the driver implements, is held to the same values, names and
prototypes, with nothing required.

Only the subset of C that these headers use is understood: object-like
macros, #include of headers under the same root, and one-line-or-more
prototypes ending in ');'.
"""

import argparse
import os
import re
import sys

# Khronos' headers wrap each API version and extension in
# `#ifndef NAME / #define NAME 1 ... #endif`; NAME tells what is required.
GL_CORE_BLOCK = "GL_VERSION_ES_CM_1_0"
EGL_REQUIRED_BLOCKS = {f"EGL_VERSION_1_{minor}" for minor in range(5)}
EXTENSION_SUFFIX = re.compile(r"_?(OES|EXT|KHR|ARB|NV|AMD|IMG|QCOM|ARM|APPLE|ANGLE|MESA|INTEL)$")
TYPE_QUALIFIERS = {"const", "volatile", "struct", "unsigned", "signed"}
API_PREFIXES = ("GL_", "EGL_")
# Linkage, not API values: each implementation defines them its own way.
LINKAGE_MACROS = {"GL_API", "GL_APIENTRY", "GL_APIENTRYP"}
PROTOTYPE = re.compile(r"\b(?:GL_API|EGLAPI)\s+([^;]*?)\s*\b(?:GL_APIENTRY|EGLAPIENTRY)\s+(\w+)\s*\(([^;]*?)\)\s*;")


class Header:
    """The macros and prototypes that one header and its includes declare."""

    def __init__(self):
        self.macros = {}  # name -> raw value text
        self.macro_block = {}  # name -> enclosing feature block (or None)
        self.functions = {}  # name -> (return type, [parameter types])
        self.function_block = {}


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def parse(path, root, header=None, seen=None):
    header = header if header is not None else Header()
    seen = seen if seen is not None else set()
    if path in seen:
        return header
    seen.add(path)
    with open(path, encoding="utf-8") as f:
        text = strip_comments(f.read()).replace("\\\n", " ")

    block = None
    pending_guard = None
    # Prototypes never span a directive, so the code between two directives
    # is searched as one piece, belonging to the block it is in.
    segments = [([], block)]
    for line in text.splitlines():
        directive = re.match(r"\s*#\s*(\w+)\s*(.*)", line)
        if not directive:
            segments[-1][0].append(line)
            continue
        kind, rest = directive.groups()
        if kind == "include":
            target = re.match(r"[<\"]([^>\"]+)[>\"]", rest)
            if target:
                included = os.path.join(root, target.group(1))
                if os.path.isfile(included):
                    parse(included, root, header, seen)
        elif kind == "ifndef":
            pending_guard = rest.split()[0]
        elif kind == "define":
            name, params, value = re.match(r"(\w+)(\([^)]*\))?\s*(.*)", rest).groups()
            if name == pending_guard and value.strip() == "1" and name.startswith(API_PREFIXES):
                block = name
            if params is None and name.startswith(API_PREFIXES) and name not in LINKAGE_MACROS:
                header.macros[name] = value.strip()
                header.macro_block[name] = block
        if kind != "ifndef":
            pending_guard = None
        segments.append(([], block))

    for lines, segment_block in segments:
        for match in PROTOTYPE.finditer(" ".join(lines)):
            return_type, name, params = match.groups()
            header.functions[name] = (normalise_type(return_type), [parameter_type(p) for p in split_params(params)])
            header.function_block[name] = segment_block
    return header


def tokens(text):
    return re.findall(r"\w+|\*", text)


def normalise_type(text):
    return " ".join(tokens(text))


def split_params(text):
    text = text.strip()
    return [] if text in ("", "void") else [p.strip() for p in text.split(",")]


def parameter_type(param):
    parts = tokens(param)
    type_words = [t for t in parts[:-1] if t != "*" and t not in TYPE_QUALIFIERS]
    if parts and re.match(r"\w+$", parts[-1]) and type_words:
        parts = parts[:-1]  # the parameter's name
    return " ".join(parts)


def evaluate(name, macros, depth=0):
    """The value of a macro as an int when it is a number, else normalised text."""
    value = macros.get(name, "")
    if value in macros and depth < 10:
        return evaluate(value, macros, depth + 1)
    text = re.sub(r"\s+", "", value)
    number = re.fullmatch(r"\(?(-?(?:0[xX][0-9a-fA-F]+|\d+))[uUlL]*\)?", text)
    if number:
        return int(number.group(1), 0)
    cast = re.fullmatch(r"EGL_CAST\((\w+),\(?(-?\w+)\)?\)", text)
    if cast:
        return f"({cast.group(1)}){int(cast.group(2), 0)}"
    return text


def is_extension(name):
    return bool(EXTENSION_SUFFIX.search(name))


def check(khronos, ours, prefix, required, errors):
    khronos_names = {n for n in khronos.macros if n.startswith(prefix)}
    our_names = {n for n in ours.macros if n.startswith(prefix)}

    for name in sorted(khronos_names & our_names):
        theirs, mine = evaluate(name, khronos.macros), evaluate(name, ours.macros)
        if theirs != mine:
            errors.append(
                f"{name}: ours is {ours.macros[name]!r} = {mine!r}, Khronos' is {khronos.macros[name]!r} = {theirs!r}"
            )

    for name in sorted(our_names - khronos_names):
        errors.append(f"{name}: defined by ours but unknown to the Khronos header (misspelt?)")

    for name in sorted(khronos_names - our_names):
        if required(khronos.macro_block.get(name)) and not is_extension(name):
            errors.append(f"{name}: missing from ours")

    fn_prefix = prefix.lower().rstrip("_")
    for name, signature in sorted(khronos.functions.items()):
        if not name.startswith(fn_prefix):
            continue
        if name not in ours.functions:
            if required(khronos.function_block.get(name)) and not is_extension(name):
                errors.append(f"{name}: function missing from ours")
            continue
        if ours.functions[name] != signature:
            errors.append(
                f"{name}: ours is {format_signature(ours.functions[name])}, Khronos' is {format_signature(signature)}"
            )

    for name in sorted(set(ours.functions) - set(khronos.functions)):
        if name.startswith(fn_prefix):
            errors.append(f"{name}: declared by ours but unknown to the Khronos header")


def format_signature(signature):
    return f"{signature[0]} ({', '.join(signature[1]) or 'void'})"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--khronos", default="/usr/include", help="root of the Khronos headers")
    parser.add_argument("--ours", required=True, help="root of tessera's headers (sw_driver/include)")
    args = parser.parse_args()

    errors = []
    counts = []
    # Our glext.h declares only extensions, none of them required; Khronos
    # keeps ES 1.1's required ones in gl.h, so it is compared with both.
    for api, prefix, required, khronos_apis in (
        ("GLES/gl.h", "GL_", lambda block: block == GL_CORE_BLOCK, ["GLES/gl.h"]),
        ("GLES/glext.h", "GL_", lambda block: False, ["GLES/gl.h", "GLES/glext.h"]),
        ("EGL/egl.h", "EGL_", lambda block: block in EGL_REQUIRED_BLOCKS, ["EGL/egl.h"]),
    ):
        khronos_path = os.path.join(args.khronos, api)
        our_path = os.path.join(args.ours, api)
        if not os.path.isfile(khronos_path):
            print(f"SKIP: {khronos_path} is not installed")
            return 77
        khronos = Header()
        for khronos_api in khronos_apis:
            parse(os.path.join(args.khronos, khronos_api), args.khronos, khronos)
        ours = parse(our_path, args.ours)
        if not khronos.functions or not khronos.macros:
            errors.append(f"{khronos_path}: parsed no macros or prototypes; the parser needs updating")
        shared = len(set(khronos.functions) & set(ours.functions))
        counts.append(
            f"{api}: {len(ours.macros)} macros, {len(ours.functions)} functions ({shared} compared with Khronos')"
        )
        check(khronos, ours, prefix, required, errors)

    for line in counts:
        print(line)
    for error in errors:
        print("FAIL:", error)
    print(f"{len(errors)} problem(s)")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
