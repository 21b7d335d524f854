"""A study's rows as a pandas DataFrame, and the file it is written to: CSV, or Parquet where an
engine for it is installed (Debian 12 packages none: pyarrow and fastparquet are PyPI's)."""

import json
import pathlib


def output_format(path):
    """"csv" or "parquet" for the path's suffix; raises ValueError before any run when the
    format cannot be written, so that a study is not run for nothing."""
    suffix = pathlib.Path(path).suffix.lower()
    if suffix == ".csv":
        return "csv"
    if suffix in (".parquet", ".pq"):
        try:
            import pyarrow  # noqa: F401
        except ImportError:
            try:
                import fastparquet  # noqa: F401
            except ImportError:
                raise ValueError(
                    f"{path}: Parquet needs pyarrow or fastparquet, and this Python has neither "
                    f"(Debian 12 packages neither); write CSV instead (a .csv path)") from None
        return "parquet"
    raise ValueError(f"{path}: the study writes .csv or .parquet files, not {suffix or 'no suffix'!r}")


def to_frame(rows, parameter_keys):
    """The rows (dicts) as a DataFrame in run order: run, the parameters, then the results.
    Lists (a vector parameter, contacts_per_frame) are cells holding lists; write() turns them
    into JSON arrays ("[0, 3, 12]"), which json.loads reads back from a CSV."""
    import pandas as pd

    frame = pd.DataFrame(sorted(rows, key=lambda r: r["run"]))
    first = ["run", *[k for k in parameter_keys if k in frame.columns], "status"]
    return frame[first + [c for c in frame.columns if c not in first]]


def write(frame, path):
    """Writes the study's DataFrame to path (CSV or Parquet, by its suffix)."""
    out = frame.copy()
    for column in out.columns:  # vectors and lists as JSON, readable back from CSV
        if out[column].map(lambda v: isinstance(v, (list, tuple, dict))).any():
            out[column] = out[column].map(lambda v: json.dumps(v) if v is not None else None)
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if output_format(path) == "csv":
        out.to_csv(path, index=False)
    else:
        out.to_parquet(path, index=False)
