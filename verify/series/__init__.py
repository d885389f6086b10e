"""A run's time series: its columns with units (:mod:`.columns`), the files people keep (:mod:`.files`:
CSV, JSON, NPZ) and the picture of a run (:mod:`.plot`)."""
from .columns import FORMAT, RunColumns, run_columns
from .files import EXTENSIONS, RunFileError, output_path, read_run, write_run

__all__ = ["EXTENSIONS", "FORMAT", "RunColumns", "RunFileError", "output_path", "read_run", "run_columns", "write_run"]
