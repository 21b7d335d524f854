"""examples/impact_speed_study.py runs (two speeds, a few frames) and writes its PNG and CSV."""

import pandas as pd
import pytest

pytest.importorskip("distributed", reason="python3-distributed (Dask) is not installed")

import impact_speed_study  # noqa: E402 (from examples/, put on sys.path by conftest.py)


def test_impact_speed_study_writes_a_png_and_rows(separate_cluster, tmp_path, capsys):
    png, csv = tmp_path / "study.png", tmp_path / "rows.csv"
    status = impact_speed_study.main([str(png), "--speeds", "1,4", "--frames", "3",
                                      "--scheduler", separate_cluster.address, "--csv", str(csv)])
    out = capsys.readouterr().out
    assert status == 0, out
    rows = pd.read_csv(csv)
    assert list(rows["bodies.armadillo.velocity.0"]) == [1.0, 4.0]
    assert (rows["status"] == "ok").all() and (rows["frames"] == 3).all()
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
