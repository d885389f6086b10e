"""``python -m verify animate``: a run, a figure's panels or a saved run into GIF/HTML, and its bad input."""
import pytest
from PIL import Image

from verify.cli import main

SMALL = ["--width", "96", "--max-seconds", "1", "--fps", "10"]


def _main(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_a_figure_side_by_side(capsys, tmp_path):
    out = tmp_path / "fig5.gif"
    code, text, err = _main(capsys, "animate", "--figure", "5", "--out", str(out), *SMALL)
    assert code == 0, err
    with Image.open(out) as im:
        assert im.size[0] == 2 * 96 and im.n_frames >= 2  # two panels, one clock
    assert "2 panel(s)" in text


def test_a_saved_run_and_a_model_run(capsys, tmp_path):
    run = tmp_path / "run.csv"
    assert _main(capsys, "trajectory", "disk", "--t-end", "0.5", "--output", str(run))[0] == 0
    code, _, err = _main(capsys, "animate", str(run), "--out", str(tmp_path / "run.html"), *SMALL)
    assert code == 0, err
    html = (tmp_path / "run.html").read_text()
    assert "<img" in html or "data:image" in html
    assert "http://" not in html and "https://" not in html
    code, _, err = _main(capsys, "animate", "hoop", "--t-end", "0.5", "--out", str(tmp_path / "h.gif"), *SMALL)
    assert code == 0, err


@pytest.mark.parametrize("argv, message", [
    (["disk", "--out", "{d}/x.avi"], "unknown extension '.avi'"),
    (["disk", "--out", "{d}/missing/x.gif"], "does not exist"),
    (["--figure", "7", "--out", "{d}/x.gif"], "--figure 7 has no run to animate"),
    (["--figure", "five", "--out", "{d}/x.gif"], "--figure 'five' is not a figure number"),
    (["--figure", "2", "--side", "lhs", "--out", "{d}/x.gif"], "Fig. 2 has one panel"),
    (["--figure", "5", "--side", "top", "--out", "{d}/x.gif"], "--side 'top'"),
    (["disk", "--side", "lhs", "--out", "{d}/x.gif"], "--side is for --figure"),
    (["disk", "--speed", "-1", "--out", "{d}/x.gif"], "--speed"),
    (["disk", "--fps", "0", "--out", "{d}/x.gif"], "--fps"),
    (["disk", "--width", "10", "--out", "{d}/x.gif"], "--width"),
    (["{d}/none.csv", "--out", "{d}/x.gif"], "no run file"),
    (["--start", "nope", "--out", "{d}/x.gif"], "unknown start 'nope'"),
    (["effective", "--t-end", "0.1", "--out", "{d}/x.gif"], "cannot animate model 'effective'"),
])
def test_bad_input_is_one_line_exit_2_and_nothing_written(capsys, tmp_path, argv, message):
    argv = [a.replace("{d}", str(tmp_path)) for a in argv]
    code, out, err = _main(capsys, "animate", *argv)
    assert code == 2 and len(err.strip().splitlines()) == 1 and message in err, err
    assert list(tmp_path.iterdir()) == []
