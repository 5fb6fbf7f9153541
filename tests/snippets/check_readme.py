"""CTest snippets.readme: the README shows the examples of examples/snippets/ verbatim.

    python3 tests/snippets/check_readme.py SOURCE_DIR

The ```python block must equal examples/snippets/solve.py from `import rhabel` on, the ```cpp block
examples/snippets/solve.cpp from its first #include on, the block after "prints" solve.out, and the
```json block scene.json; so the README cannot drift from the files that CTest runs.
"""
import pathlib
import re
import sys

src = pathlib.Path(sys.argv[1])
readme = (src / "README.md").read_text()
snip = src / "examples" / "snippets"
blocks = re.findall(r"```(\w*)\n(.*?)```", readme, flags=re.S)


def block(lang, start):
    found = [b for l, b in blocks if l == lang and b.startswith(start)]
    assert len(found) == 1, f"README: expected one ```{lang} block starting with {start!r}, found {len(found)}"
    return found[0]


def tail(text, start):
    return text[text.index(start):]


failures = []
for lang, start, path in (("python", "import rhabel\n\nscene", "solve.py"),
                          ("cpp", '#include "rhabel/punch.hpp"', "solve.cpp"),
                          ("json", '{"description": "README example', "scene.json"),
                          ("", "beta = ", "solve.out")):
    shown = block(lang, start)
    want = tail((snip / path).read_text(), start)
    if shown != want:
        failures.append(f"README's {lang or 'output'} block differs from examples/snippets/{path}")
if failures:
    print("\n".join(failures))
    sys.exit(1)
print("README shows examples/snippets/{solve.py, solve.cpp, scene.json, solve.out} verbatim")
