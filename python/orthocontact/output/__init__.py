"""What results are written as, and where: CSV and JSON (tables), PNG
figures (figures), the output folder (folder: checked, owned, staged and
committed whole) with its manifest (manifest), and the command's notes and
warnings on stderr (lines)."""
from .figures import FigureDrawer, curve_style, draw_here, finish, label, pyplot, save, swept_label
from .folder import check_output_file, check_output_folder, check_owner, staged_output
from .lines import forget_warnings, note, warn, warnings_said
from .manifest import MANIFEST, one_run, written_by
from .tables import write_csv, write_json

__all__ = ["FigureDrawer", "curve_style", "draw_here", "finish", "label", "pyplot", "save", "swept_label",
           "check_output_file", "check_output_folder", "check_owner", "staged_output", "forget_warnings",
           "note", "warn", "warnings_said", "MANIFEST", "one_run", "written_by", "write_csv", "write_json"]
