"""Files the tools generate from the repository's sources
(tools/make_generated.py, tools/make_reference.py): each compared with the
copy under the root, as a short diff, or written there in one step (a
temporary file renamed over it: a reader never sees half of it)."""
from __future__ import annotations

import difflib
from pathlib import Path


def differs(root: Path, rel: str, text: str, lines: int) -> str:
    """"" if the file `rel` under `root` holds `text`, else the first `lines`
    lines of a unified diff from it (committed) to `text` (generated)."""
    path = root / rel
    old = path.read_text() if path.is_file() else ""
    if old == text:
        return ""
    diff = difflib.unified_diff(old.splitlines(), text.splitlines(), f"{rel} (committed)",
                                f"{rel} (generated)", lineterm="", n=0)
    return "\n".join(list(diff)[:lines])


def write(root: Path, rel: str, text: str) -> None:
    """`text` into the file `rel` under `root`, in one step; says so on stdout."""
    path = root / rel
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text)
    tmp.replace(path)
    print(f"wrote {rel}")
