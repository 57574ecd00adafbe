"""The X-macro tables (`*.def`) as the Python scripts read them.

A row is one line `MACRO(field, field, ...)`; fields are split on commas
outside double quotes, which are removed (as a C string's would be).
Used by scripts/update_docs.py (the generated tables) and
scripts/check_add_backend.py (the back-end table's columns).

    def_table.row('TESSERA_BACKEND(arm, "arm", 16, 8, "software")', "TESSERA_BACKEND")
        -> ['arm', 'arm', '16', '8', 'software']
    def_table.rows(path, "TESSERA_BACKEND")   # every row of a file
"""

import csv
import pathlib
import re


def row(line, macro):
    """The fields of `line` if it is a `macro(...)` line, else None."""
    match = re.match(r"^" + re.escape(macro) + r"\((.*)\)\s*$", line)
    if not match:
        return None
    fields = next(csv.reader([match.group(1)], skipinitialspace=True))
    return [field.strip() for field in fields]


def rows(path, macro):
    """The fields of every `macro(...)` line of the file `path`."""
    found = (row(line, macro) for line in pathlib.Path(path).read_text().splitlines())
    return [fields for fields in found if fields is not None]
