"""json_difference.py: where two JSON values first differ (the scripts that compare runs)."""


def first_difference(a, b, where: str = "", labels: tuple = ("before", "after")) -> str:
    """The path of the first difference between a and b and both values there ("" if equal);
    labels name the two sides in the message."""
    first, second = labels
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                return f"{where}.{key} only {second if key not in a else first}"
            found = first_difference(a[key], b[key], f"{where}.{key}", labels)
            if found:
                return found
        return ""
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{where}: {len(a)} items {first}, {len(b)} {second}"
        for i, (x, y) in enumerate(zip(a, b)):
            found = first_difference(x, y, f"{where}[{i}]", labels)
            if found:
                return found
        return ""
    return "" if a == b else f"{where}: {a!r} {first}, {b!r} {second}"
