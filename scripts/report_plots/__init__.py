"""The parts of scripts/plot_report.py: data (reading the report's files),
figures (matplotlib) and summary (summary.md's prose)."""
