"""examples/compare_broadphases.py runs (small), finds the methods agreeing, writes a PNG."""

import matplotlib

matplotlib.use("Agg")

import compare_broadphases  # noqa: E402 (from examples/, put on sys.path by conftest.py)


def test_compare_broadphases_writes_a_png(tmp_path, capsys):
    png = tmp_path / "broadphases.png"
    status = compare_broadphases.main([str(png), "--frames", "8", "--subdivisions", "2",
                                       "--repeat", "1", "--threads", "1"])
    out = capsys.readouterr().out
    assert status == 0, out
    assert "every method found the same contacts as brute at every frame" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert png.stat().st_size > 10_000
