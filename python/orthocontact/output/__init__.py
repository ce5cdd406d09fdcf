"""What results are written as, and where: CSV and JSON (tables), PNG
figures (figures), the output folder (folder: checked, owned, staged and
committed whole) with its manifest (manifest), and the command's notes and
warnings on stderr (lines)."""
