#!/usr/bin/env python3
"""Executes the notebooks of notebooks/ headless (nbclient) and checks that every cell runs.

    PYTHONPATH=build/python /usr/bin/python3 scripts/run_notebooks.py            # check (CTest `notebooks`)
    PYTHONPATH=build/python /usr/bin/python3 scripts/run_notebooks.py --save     # + save outputs, docs/img/*.png
    ... scripts/run_notebooks.py [--save] parabola wedge                          # only these notebooks

Each notebook asserts its key numbers (closed forms of docs/theory.md, the values of docs/tables.md),
so a wrong figure fails here, not only a crashing one. Without --save nothing in the source tree is
written: the executed notebooks are discarded and the figures go to a temporary directory. With
--save the executed notebooks (with their outputs) replace the committed ones and the figures the
README shows are written to docs/img/ (the notebooks write them to $RHABEL_FIGURE_DIR).

Exit codes: 0 all passed, 1 a notebook failed (its failing cell and error are printed),
77 the notebook packages (Debian: python3-nbclient python3-nbformat python3-ipykernel) are missing
(CTest reports the test as skipped).
"""
import argparse
import os
import pathlib
import sys
import tempfile
import time

SKIP = 77
root = pathlib.Path(__file__).resolve().parent.parent
notebook_dir = root / "notebooks"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--save", action="store_true", help="save outputs in place and figures to docs/img/")
    parser.add_argument("--timeout", type=int, default=300, help="seconds per cell (default 300)")
    parser.add_argument("names", nargs="*", help="notebook names without .ipynb (default: all)")
    args = parser.parse_args()

    try:
        import nbformat
        from nbclient import NotebookClient
        from nbclient.exceptions import CellExecutionError
        import ipykernel  # noqa: F401  (the kernel nbclient starts)
    except ImportError as e:
        print(f"SKIP: the notebook packages are missing ({e}); on Debian: "
              "apt-get install python3-nbclient python3-nbformat python3-ipykernel", file=sys.stderr)
        return SKIP
    try:
        import rhabel  # noqa: F401
    except ImportError as e:
        print(f"FAIL: cannot import rhabel ({e}): build it (cmake --build build --target rhabel_python) "
              "and set PYTHONPATH=build/python", file=sys.stderr)
        return 1

    paths = sorted(notebook_dir.glob("*.ipynb"))
    if args.names:
        wanted = {n.removesuffix(".ipynb") for n in args.names}
        paths = [p for p in paths if p.stem in wanted]
        missing = wanted - {p.stem for p in paths}
        if missing:
            print(f"FAIL: no such notebook: {', '.join(sorted(missing))}", file=sys.stderr)
            return 1

    # the kernel runs in notebooks/: make a relative PYTHONPATH (build/python) absolute
    os.environ["PYTHONPATH"] = os.pathsep.join(
        str(pathlib.Path(entry).resolve()) for entry in os.environ.get("PYTHONPATH", "").split(os.pathsep) if entry)
    with tempfile.TemporaryDirectory(prefix="rhabel-notebooks-") as scratch:
        figure_dir = root / "docs" / "img" if args.save else pathlib.Path(scratch)
        os.environ["RHABEL_FIGURE_DIR"] = str(figure_dir)
        os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
        os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # ipykernel debugger warning
        failed = []
        for path in paths:
            nb = nbformat.read(path, as_version=4)
            client = NotebookClient(nb, timeout=args.timeout, kernel_name="python3",
                                    resources={"metadata": {"path": str(notebook_dir)}})
            start = time.monotonic()
            try:
                client.execute()
            except CellExecutionError as e:
                print(f"FAIL {path.name} ({time.monotonic() - start:.1f} s):\n{e}", file=sys.stderr)
                failed.append(path.name)
                continue
            seconds = time.monotonic() - start
            print(f"ok   {path.name} ({seconds:.1f} s)")
            if args.save:
                _strip_volatile(nb)
                nbformat.write(nb, path)
        if failed:
            print(f"{len(failed)} of {len(paths)} notebooks failed: {', '.join(failed)}", file=sys.stderr)
            return 1
        if args.save:
            print(f"saved {len(paths)} notebooks with their outputs; figures in {figure_dir}")
    return 0


def _strip_volatile(nb):
    """Execution timestamps change on every run; drop them so that a rerun with unchanged
    results changes only what really changed (figures, timings printed by the notebook)."""
    for cell in nb.cells:
        cell.get("metadata", {}).pop("execution", None)


if __name__ == "__main__":
    sys.exit(main())
