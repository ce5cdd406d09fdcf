"""One name for the angle the sweeps turn the mat by: "mat angle" (symbol a,
degrees; the data files' column mat_angle_deg).  It had three (mat angle,
orientation angle, swept angle a) across the help texts, figures, messages
and documents; the others must not come back."""
import re

from paths import DOCS, PKG, ROOT, SCENARIOS

OTHER_NAMES = re.compile(r"orientation angle|swept angles?|\borientations?\b", re.IGNORECASE)


def user_facing_files():
    yield from PKG.rglob("*.py")
    yield ROOT / "README.md"
    yield from DOCS.rglob("*.md")
    yield from SCENARIOS.rglob("*.md")
    yield from SCENARIOS.rglob("*.toml")   # a scenario's title and description


# Lines being rewritten by the plausibility gate's work when
# the name was unified: each must still be there (else drop it here), and
# nothing else may use another name.
PENDING: set = set()   # (file, text) of a rename still to come; empty: none


def test_the_swept_angle_has_one_name_everywhere():
    files = list(user_facing_files())
    assert len(files) > 50
    hits, pending = [], set()
    for f in files:
        rel = str(f.relative_to(ROOT))
        for n, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
            if not OTHER_NAMES.search(line):
                continue
            known = {(p, s) for p, s in PENDING if p == rel and s in line}
            pending |= known
            if not known:
                hits.append(f"{rel}:{n}: {line.strip()}")
    assert not hits, "use \"mat angle\":\n" + "\n".join(hits)
    assert pending == PENDING, f"renamed since: drop {PENDING - pending} from PENDING"


def test_the_check_sees_each_other_name():
    for text in ("the orientation angle [deg]", "Swept angle a: α = a", "at two orientations",
                 "over the swept angles"):
        assert OTHER_NAMES.search(text), text
    for text in ("mat angle a [deg]", "RADIAN_ORIENTATIONS", "mat_angle_deg"):
        assert not OTHER_NAMES.search(text), text
