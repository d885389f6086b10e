"""The engines' leaderboard (verify.leaderboard) and its report section (verify.report.engines)."""
import json

from verify.leaderboard import engine_run, figure_png, words
from verify.report.engines import render_markdown

FAKE = '''
def run_case(case, setting="default", t_end=None):
    if setting == "broken":
        raise RuntimeError("the solver diverged")
    if setting == "absent":
        import engine_that_is_not_installed  # noqa: F401
    return {"engine": "Fake", "version": "0.1", "case": case, "setting": setting, "wall_s": 0.5, "outcome": "ok",
            "score": {"min_digits": 4.2, "worst": "psi at t = 1", "partial": False, "energy_rel_drift": 1e-5,
                      "contact_height": 1e-6, "contact_velocity": 1e-5,
                      "components": {"theta": {"final_digits": 5.0}}}, "_columns": object()}
'''


def test_an_adapter_runs_in_its_own_process_and_its_failures_are_named(tmp_path):
    path = tmp_path / "fake_adapter.py"
    path.write_text(FAKE)
    ok = engine_run("fake", path, "disk-standard-1", "best", None)
    assert ok["score"]["min_digits"] == 4.2 and "_columns" not in ok and words(ok) == "good to 3 digits"
    broken = engine_run("fake", path, "disk-standard-1", "broken", None)
    assert broken["outcome"] == "error: RuntimeError: the solver diverged" and words(broken).startswith("no score")
    absent = engine_run("fake", path, "disk-standard-1", "absent", None)
    assert absent["outcome"].startswith("not installed") and words(absent) == "not installed here"


def test_words_for_a_run():
    def rec(digits, outcome="ok", drift=1e-9, partial=False):
        return {"outcome": outcome, "score": {"min_digits": digits, "energy_rel_drift": drift, "partial": partial}}

    assert words(rec(12.8)) == "reference quality"
    assert words(rec(-0.5, drift=0.6)) == "no digit right; energy drifts 60 %"
    assert words(rec(2.0, outcome="fell")) == "falls over (wrong)"
    assert words(rec(6.1, partial=True)) == "accurate (partial)"


def test_the_section_renders_a_board_and_says_how_to_make_one():
    board = {"cases": [{"case": "disk-standard-1", "t_end_run": None}], "machine": "a CPU", "sources": {"commit": "abc"},
             "rows": [{"engine": "Fake", "version": "0.1", "adapter": "fake", "case": "disk-standard-1",
                       "setting": "best", "wall_s": 0.5, "outcome": "ok", "words": "good to 3 digits",
                       "score": {"min_digits": 4.2, "worst": "psi at t = 1", "energy_rel_drift": 1e-5,
                                 "contact_height": 1e-6, "contact_velocity": 1e-5,
                                 "components": {"theta": {"final_digits": 5.0}}}}]}
    text = "\n".join(render_markdown(board))
    assert "| Fake 0.1 | best | 4.20 (psi at t = 1) | 5.00 | 1.0e-05 | 1.0e-06 / 1.0e-05 | 0.5 | good to 3 digits |" in text
    assert "make engines" in "\n".join(render_markdown(None))
    assert figure_png(board)[:8] == b"\x89PNG\r\n\x1a\n"
    json.dumps(board)
