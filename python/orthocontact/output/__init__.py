"""What results are written as: CSV and JSON (tables), PNG figures
(figures)."""
