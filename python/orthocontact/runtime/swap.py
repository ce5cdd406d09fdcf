"""A folder's content replaced in one step: the new content is built beside
it (hard links of what stays, the new files over them) and the two folders
are exchanged by one renameat2(RENAME_EXCHANGE), so that a reader, or a crash,
sees either the old folder or the new one, never a mix.  And the merge of
one folder's files into another, which both that build and the
file-by-file way where no exchange exists use."""
from __future__ import annotations

import errno
import os
import shutil
import stat
import sys
from pathlib import Path

RENAME_EXCHANGE = 2  # linux/fs.h
_AT_FDCWD = -100

# What a file system answers a hard link or an exchange it does not do:
# another file system below (a mount inside the folder), links not allowed
# (protected_hardlinks, a FAT disk), too many links, no RENAME_EXCHANGE.
UNSUPPORTED = (errno.EXDEV, errno.EPERM, errno.EMLINK, errno.ENOTSUP, errno.EOPNOTSUPP, errno.EINVAL,
               errno.ENOSYS)


def _renameat2():
    if not sys.platform.startswith("linux"):
        return None
    import ctypes
    fn = getattr(ctypes.CDLL(None, use_errno=True), "renameat2", None)   # glibc >= 2.28
    if fn is not None:
        fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    return fn


def exchange(a: Path, b: Path) -> None:
    """Swaps the folders `a` and `b` (same file system) atomically; OSError
    (ENOSYS where the system has no renameat2, EINVAL where the file system
    has no RENAME_EXCHANGE)."""
    fn = _renameat2()
    if fn is None:
        raise OSError(errno.ENOSYS, "no renameat2 on this system", str(b))
    import ctypes
    if fn(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), RENAME_EXCHANGE) != 0:
        e = ctypes.get_errno()
        raise OSError(e, os.strerror(e), str(b))


def can_exchange(folder: Path) -> bool:
    """Whether `folder` can be exchanged with a sibling built beside it: a
    real folder (not a symbolic link, whose target would stay as it is), not
    a mount point (which cannot be renamed), on a system with renameat2."""
    folder = Path(folder)
    return (_renameat2() is not None and folder.is_dir() and not folder.is_symlink()
            and not os.path.ismount(folder))


def link_tree(src: Path, dst: Path, skip=frozenset()) -> None:
    """`dst` (new) as a copy of the folder `src` made of hard links: its
    folders made anew with their modes, every other entry (a symbolic link
    as itself) linked, but for the paths (POSIX, relative to src) in
    `skip`.  OSError as the system refuses a link (UNSUPPORTED)."""
    src, dst = Path(src), Path(dst)
    dst.mkdir()
    os.chmod(dst, stat.S_IMODE(src.stat().st_mode))
    for root, dirs, files in os.walk(src):
        here = Path(root).relative_to(src)
        for d in list(dirs):
            if (src / here / d).is_symlink():   # linked as itself, not walked
                dirs.remove(d)
                files.append(d)
                continue
            (dst / here / d).mkdir()
            os.chmod(dst / here / d, stat.S_IMODE((src / here / d).stat().st_mode))
        for f in files:
            if (here / f).as_posix() not in skip:
                os.link(src / here / f, dst / here / f, follow_symlinks=False)


def merge_into(src: Path, dst: Path, place=os.replace) -> None:
    """Every file under `src` to the same place under `dst` by place(from,
    to) (os.replace: moved; os.link: linked), replacing only the files
    written: what else `dst` holds (and its subfolders, e.g. reproduce's
    <out>/<scenario>/) stays; a folder where `src` has a file goes."""
    dst.mkdir(exist_ok=True)
    for item in src.iterdir():
        target = dst / item.name
        if item.is_dir() and target.is_dir() and not target.is_symlink():
            merge_into(item, target, place)
            continue
        if target.is_dir() and not target.is_symlink():
            shutil.rmtree(target)  # a folder where this command writes a file
        elif place is not os.replace and (target.exists() or target.is_symlink()):
            if item.is_dir():      # as os.replace refuses it: a file is never replaced by a folder
                raise NotADirectoryError(errno.ENOTDIR, os.strerror(errno.ENOTDIR), str(target))
            target.unlink()        # a link replaces nothing: the name first
        if item.is_dir() and place is not os.replace:
            merge_into(item, target, place)
        else:
            place(item, target)


def prune_empty(root: Path, names) -> None:
    """Removes the folders under `root` left empty where the files `names`
    (POSIX, relative to root) were, up to the first that is not empty."""
    for name in names:
        for parent in (Path(root) / name).parents:
            if parent == Path(root):
                break
            try:
                parent.rmdir()   # only if empty
            except OSError:
                break
