"""Checks every Catch2 test name under tests/ against the naming scheme
(docs/architecture.md, "How tests are named"): "<thing>: <what is checked>",
and no ';'. ctest's test discovery cuts a name at ';' into entries that run
no test and still pass, so a ';' would hide a test. Prints one line per bad
name and exits 1 if there is any.
usage: check_test_names.py TESTS_DIR"""
import pathlib
import re
import sys

LITERAL = re.compile(r'\s*"((?:[^"\\]|\\.)*)"')


def test_names(path):
    text = path.read_text(errors="replace")
    for match in re.finditer(r"\bTEST_CASE\s*\(", text):
        # The name may be split over adjacent string literals.
        position, parts = match.end(), []
        while (literal := LITERAL.match(text, position)) is not None:
            parts.append(literal.group(1))
            position = literal.end()
        if parts:
            yield text.count("\n", 0, match.start()) + 1, "".join(parts)


def main():
    root = pathlib.Path(sys.argv[1])
    count, bad = 0, []
    for path in sorted(root.rglob("*.cpp")):
        for line, name in test_names(path):
            count += 1
            where = f"{path.relative_to(root)}:{line}"
            if ";" in name:
                bad.append(f"{where}: ';' in the test name '{name}'")
            if not re.match(r"^[^:]+: \S", name):
                bad.append(f"{where}: '{name}' is not '<thing>: <what is checked>'")
    print("\n".join(bad) if bad else f"{count} test names follow the scheme")
    return 1 if bad or count == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
