"""The output folder, its logic in one place: where the results go, checked
before any work (check_output_folder, check_output_file); whose it is
(owner_of, check_owner: --force for another command's folder or one holding
what the command reads, which is never removed); the staging folder,
committed whole once everything is written (staged_output, commit_run,
swap_in); the files edited since their run (outdated: kept, never
overwritten without --force).  The manifest, its record, and outputs read
back as their run wrote them (written_by, one_run): output.manifest."""
from __future__ import annotations

import contextlib
import dataclasses
import errno
import os
import shutil
import tempfile
import zipfile
from pathlib import Path

from ..errors import InputError
from ..runtime import (
    UNSUPPORTED,
    can_exchange,
    exchange,
    hold_interrupts,
    interrupted,
    link_tree,
    locked_folder,
    merge_into,
    prune_empty,
    results_written,
    signals_held,
)
from ..textfiles import paths_being_read
from .lines import note, warn
from .manifest import MANIFEST, Manifest, file_names, file_sha256, new_manifest, read_manifest, write_manifest

# What the system answers a write it refuses: permission, a read-only file
# system, a full disk or quota, an I/O error.
REFUSALS = (errno.EACCES, errno.EPERM, errno.EROFS, errno.ENOSPC, errno.EDQUOT, errno.EIO)


def check_output_folder(out: Path, option: str = "--out") -> None:
    """Raises InputError, naming the user's path, unless `out` is (or can be
    created as) a writable folder; OSError naming the folder where the system
    refuses the write (REFUSALS: the command's exit 74).  Leaves nothing behind."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputError(f"{option} {out}: is a file; expected a folder to write the results into")
    probe = out
    while not probe.exists():
        if probe.parent == probe:
            break
        probe = probe.parent
    if probe != out and not probe.is_dir():
        raise InputError(f"{option} {out}: {probe} is a file, so no folder can be made under it")
    try_writing(probe, option, out)
    if out.is_dir():
        read_manifest(out)   # its list decides what the run removes: a bad one is refused now


def check_owner(out: Path, command: str | None, force: bool = False, reads=(), option: str = "--out",
                writes=()) -> None:
    """Refuses (InputError, one line naming the owner and --force) to write
    the results of `orthocontact COMMAND` into `out` unless it is new, empty
    (but for a killed run's scratch folders) or holds an earlier run of the
    same command: not a folder of another command's run, nor one holding
    files no orthocontact run wrote, nor one holding a file or folder of
    `reads` (what the command reads); nor, once the run is done, its own
    earlier run's folder where a file that run wrote has changed since (the
    user's edit) and `writes` (the new run's files) would overwrite it.
    `force` lets each through: the commit then replaces the other run's
    files and keeps what is read."""
    out = Path(out)
    inside = [r for r in (Path(r) for r in reads) if _holds(out, r)]
    owner = owner_of(out)
    mine = owner is not None and owner[1].command == command and owner[0] == out.absolute()
    if mine and writes and not force:
        edited = [n for n in outdated(out, owner[1], keep=())[1] if n in writes]
        if edited:
            raise InputError(f"{option} {out}: {', '.join(edited)} changed since {owner[1].describe()} "
                             "wrote it (an edit of yours?), and this run would write it again: move it "
                             f"out of {out} to keep it, or pass --force to replace it; nothing written")
    if force or (mine and not inside):
        return
    by = f"`orthocontact {command}`" if command else "this command"
    if inside:
        what = f"holds {inside[0]}, which {by} reads"
        if owner is not None:
            what += f" (the folder holds the outputs of {owner[1].describe()})"
        remedy = "pass --force to write there all the same (it never removes what it reads)"
    elif owner is not None:
        what = f"holds the outputs of {owner[1].describe()}"
        remedy = f"pass --force to replace them ({_count(owner, out)})"
    else:
        strangers = _entries(out)
        if not strangers:
            return
        what = (f"holds {len(strangers)} file(s) or folder(s) no orthocontact run wrote "
                f"({', '.join(sorted(strangers)[:3])}{', ...' if len(strangers) > 3 else ''})")
        remedy = "pass --force to write beside them (only files named as its outputs are replaced)"
    raise InputError(f"{option} {out}: {what}; {by} writes into a new or empty folder or one of its own "
                     f"earlier runs: choose another {option}, or {remedy}")


def _holds(out: Path, path: Path) -> bool:
    """Whether `path` is `out` or lies under it (both resolved: links too)."""
    out, path = out.resolve(), path.resolve()
    return path == out or out in path.parents


def _entries(out: Path) -> list[str]:
    """The names in `out` but for killed runs' scratch folders (removed by
    the next run) and the command's own probe: what makes it not empty."""
    if not out.is_dir():
        return []
    scratch = (f".{out.name}.partial-", ".orthocontact-probe-")
    return [p.name for p in out.iterdir() if not p.name.startswith(scratch)]


def _count(owner: tuple[Path, Manifest], out: Path) -> str:
    home, m = owner
    prefix = _prefix(home, out)
    n = sum(1 for name in m.files if name.startswith(prefix))
    return f"{n} file(s)"


def _prefix(home: Path, out: Path) -> str:
    """The path of `out` under the manifest's folder `home`, as a prefix of its list's names."""
    rel = Path(out).absolute().relative_to(Path(home).absolute()).as_posix()
    return "" if rel == "." else rel + "/"


def check_output_file(out: Path, option: str = "--out", reads=(), force: bool = False,
                      kind: str = "an SSP package", marker: str = "SystemStructure.ssd") -> None:
    """Raises InputError, naming the user's path, unless a file can be written
    at `out` (in an existing, writable folder): not a file the command reads
    (`reads`, --force or not), nor an existing file other than `kind` (a zip
    holding `marker`) unless `force`; OSError as check_output_folder."""
    out = Path(out)
    if out.is_dir():
        raise InputError(f"{option} {out}: is a folder; expected a file name")
    if any(out.resolve() == Path(r).resolve() for r in reads):
        raise InputError(f"{option} {out}: is a file this command reads; choose another {option}")
    if out.exists() and not force and not _is_zip_with(out, marker):
        raise InputError(f"{option} {out}: exists and is not {kind}; choose another {option}, or pass "
                         "--force to replace it")
    if not out.parent.is_dir():
        raise InputError(f"{option} {out}: the folder {out.parent} does not exist")
    try_writing(out.parent, option, out)


def try_writing(probe: Path, option: str, out: Path) -> None:
    """Makes and removes a folder in `probe` (access() says yes to root
    everywhere, /proc included: try instead): InputError naming the user's
    `option` and `out` where it cannot, OSError naming `probe` where the
    system refuses the write (REFUSALS: the command's exit 74)."""
    try:
        tempfile.TemporaryDirectory(prefix=".orthocontact-probe-", dir=probe).cleanup()
    except OSError as e:
        if e.errno in REFUSALS:   # the system's refusal: its own exit status (cli.main)
            raise OSError(e.errno, e.strerror, str(probe)) from None
        raise InputError(f"{option} {out}: {probe} is not writable ({e.strerror})") from None


def _is_zip_with(path: Path, member: str) -> bool:
    try:
        with zipfile.ZipFile(path) as z:
            return member in z.namelist()
    except (OSError, zipfile.BadZipFile):
        return False


@contextlib.contextmanager
def staged_output(out: Path, command: str | None = None, force: bool = False):
    """A scratch folder beside `out`; its files move into `out` only if the
    block completes, so a failure or an interrupt leaves nothing behind: not
    the scratch folder, nor parent folders made for it, nor a half-written `out`.
    On success `out` is this run's (commit_run): the files an earlier run's
    manifest lists are replaced or removed, the user's own stay.  The owner
    of `out` is checked (check_owner) against every file the command has
    read by now (textfiles.paths_being_read) before the block and again
    before the commit."""
    out = Path(out)
    check_owner(out, command, force, paths_being_read())
    made = []
    for parent in reversed(out.parents):
        if not parent.exists():
            parent.mkdir()
            made.append(parent.absolute())
    # Beside `out`, or in it where `out` is a file system of its own (a
    # mount point, a container's volume): a file moves by renaming only
    # within one file system.
    inside = out.is_dir() and out.stat().st_dev != out.parent.stat().st_dev
    # A locked folder (runtime.folders): this run's while it lives; one a killed
    # run left there (SIGKILL cleans nothing) goes with the next run into `out`.
    held = None
    try:
        with signals_held():   # made and kept in `held` as one step: an interrupt comes after
            held = locked_folder(out if inside else out.parent, f".{out.name}.partial-")
        stage = held.path / "files"
        stage.mkdir()
        yield stage
        hold_interrupts()  # one arriving during the commit must not cut it in half
        # An interrupt that a finalizer swallowed ("Exception ignored in
        # __del__") still means the user asked to stop: commit nothing.
        if interrupted():
            raise KeyboardInterrupt
    except BaseException:
        if held is not None:
            held.remove()
        _unmake(made)
        raise
    try:
        reads = paths_being_read()
        # another command may have written there meanwhile; an edited earlier output is refused
        check_owner(out, command, force, reads, writes=set(file_names(stage)))
        commit_run(stage, out, command, reads)
    except BaseException:   # a commit the system refused (disk full) leaves nothing either
        held.remove()
        _unmake(made)
        raise
    held.remove()
    results_written(out)


def _unmake(made) -> None:
    """Removes the folders made for the output, if they are still empty."""
    for parent in reversed(made):
        with contextlib.suppress(OSError):
            parent.rmdir()


def commit_run(stage: Path, out: Path, command: str | None, reads=()) -> None:
    """Makes `out` this run's: the run's files from `stage`, its manifest,
    the files of the folder's earlier run (owner_of) removed but for those
    this run writes again, those changed since and what the command read
    (`reads`); the user's own stay.  Says so in one line.  `out` takes its
    new content in one step, manifest included (swap_in); where that cannot
    be done, file by file with the manifest last (a reader that finds it
    finds its files)."""
    from ..version import __version__
    out = Path(out)
    owner = owner_of(out)
    run = new_manifest(stage, command, __version__)
    strangers = sorted(set(_entries(out)) - {MANIFEST}) if owner is None else []
    replaced = sorted(n for n in run.files if (out / n).exists()) if strangers else []
    clash = [n for n in run.files if any(Path(r).resolve() == (out / n).resolve() for r in reads)]
    if clash:   # --force or not: what the command read is never replaced
        raise InputError(f"--out {out}: {clash[0]} is a file this command read and would write; "
                         "choose another --out")
    gone, changed, prefix = [], [], ""
    if owner is not None:
        home, earlier = owner
        prefix = _prefix(home, out)
        kept_read = {n for n in earlier.files if any(_holds(Path(r), home / n) for r in reads)}
        theirs = dataclasses.replace(earlier, files={k: v for k, v in earlier.files.items()
                                                     if k.startswith(prefix)})
        keep = {prefix + n for n in run.files} | kept_read
        gone, changed = outdated(home, theirs, keep)
    swapped = swap_in(stage, out, run, [n[len(prefix):] for n in gone])
    if not swapped:
        merge_into(stage, out)
    if owner is not None:
        if not swapped:
            changed = remove_earlier(home, theirs, keep)
        if prefix:   # a folder inside another run's: that run's list no longer names it
            write_manifest(home, dataclasses.replace(earlier, files={
                k: v for k, v in earlier.files.items() if not k.startswith(prefix)}))
        if changed:
            warn(f"{out}: kept {', '.join(changed)} of {earlier.describe()}: changed since that run "
                 "wrote them, so they are taken as yours; they are not this run's outputs")
        said = f"replaced {earlier.describe()} ({len(theirs.files)} file(s)"
        read_here = sorted(kept_read & set(theirs.files))
        if read_here:
            said += f"; kept {', '.join(read_here)}, read by this command"
        said += ")"
        note(f"{out}: {said}" if earlier.command == command and not prefix else f"--force: {out}: {said}")
    elif strangers:
        note(f"--force: {out}: wrote beside {len(strangers)} file(s) or folder(s) no orthocontact run "
             f"wrote" + (f"; replaced {', '.join(replaced)}" if replaced else "; none replaced"))
    if not swapped:
        write_manifest(out, run)


def swap_in(stage: Path, out: Path, run: Manifest, gone) -> bool:
    """`out` with its new content in one step, the manifest `run` in it
    before it takes the name: a new `out` is `stage`, renamed; an existing
    one is exchanged (runtime.swap) with a folder built beside `stage` of
    hard links: every file of `out` that stays (the user's own, what the
    command read, an earlier run's files it keeps; not `gone`, the earlier
    run's files this run removes, nor the old manifest) and the run's files
    over them.  The old content is then in the locked folder and goes with
    it.  A crash at any step leaves `out` as it was or complete.  False,
    `out` untouched, where this cannot be done: no renameat2 (not Linux),
    `out` a symbolic link or a mount point (the staging folder is then
    inside it), a file system without hard links or RENAME_EXCHANGE; the
    caller then moves the files one by one (merge_into), manifest last."""
    if not out.exists() and not out.is_symlink():
        write_manifest(stage, run)
        os.rename(stage, out)
        return True
    if not can_exchange(out) or out.absolute() in stage.absolute().parents:
        return False
    nxt = stage.with_name("next")
    try:
        link_tree(out, nxt, skip=set(gone) | {MANIFEST})
        merge_into(stage, nxt, os.link)
        prune_empty(nxt, gone)
        write_manifest(nxt, run)
        exchange(nxt, out)
    except OSError as e:
        shutil.rmtree(nxt, ignore_errors=True)   # links and this run's files only: `out` is as it was
        if e.errno in UNSUPPORTED:
            return False
        raise
    return True


def owner_of(folder: Path) -> tuple[Path, Manifest] | None:
    """The run whose outputs `folder` holds, with the folder of its manifest:
    the folder's own manifest, else the nearest enclosing folder's whose
    list names a file under `folder` (reproduce's <out>/<scenario>/ is
    reproduce's); None if no run wrote there.  InputError as read_manifest."""
    folder = Path(folder).absolute()
    m = read_manifest(folder) if folder.is_dir() else None
    if m is not None:
        return folder, m
    for parent in folder.parents:
        if not (parent / MANIFEST).is_file():
            continue
        m = read_manifest(parent)
        under = folder.relative_to(parent).as_posix() + "/"
        if any(name.startswith(under) for name in m.files):
            return parent, m
    return None


def outdated(folder: Path, old: Manifest, keep) -> tuple[list[str], list[str]]:
    """What a new run does with the files `old` lists in `folder` that are
    not in `keep` (the new run's paths): (those it removes, still as `old`
    recorded them; those it leaves because they changed since, the user's
    now).  Files that are gone, not regular, outside the folder or behind a
    symbolic link are in neither."""
    folder = Path(folder)
    root = folder.resolve()
    gone, changed = [], []
    for name, sha in sorted(old.files.items()):
        if name in keep:
            continue
        p = folder / name
        if p.is_symlink() or not p.is_file() or root not in p.resolve().parents:
            continue
        (gone if file_sha256(p) == sha else changed).append(name)
    return gone, changed


def remove_earlier(folder: Path, old: Manifest, keep) -> list[str]:
    """Removes from `folder` the files `old` lists that are not in `keep`
    (the new run's paths) and are still as `old` recorded them, and the
    subfolders this empties; returns the listed files left because they
    changed since (the user's now).  Nothing else is touched, and nothing
    through a symbolic link."""
    folder = Path(folder)
    gone, changed = outdated(folder, old, keep)
    for name in gone:
        (folder / name).unlink()
    prune_empty(folder, gone)
    return changed
