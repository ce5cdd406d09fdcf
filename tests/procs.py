"""Processes as /proc shows them, for the tests that stop a command and
check that none of its processes is left."""
from pathlib import Path


def parents() -> dict:
    """pid -> parent pid of every process."""
    out = {}
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                out[int(d.name)] = int((d / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except OSError:
                continue
    return out


def children(pid) -> list:
    return [k for k, v in parents().items() if v == pid]


def descendants(pid) -> list:
    parent = parents()
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        kids = [k for k, v in parent.items() if v == p]
        out += kids
        todo += kids
    return out


def alive(pid) -> bool:
    """Running, not a zombie."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False
