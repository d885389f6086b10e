"""The engines' leaderboard (verify.leaderboard) and its report section (verify.report.engines)."""
import json

from verify.leaderboard import CASES, engine_run, figure_png, merge_boards, words
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


def _coulomb_row(engine, setting, slides, sticks_at, slips_at=None, digits=1.6):
    return {"engine": engine, "version": "1", "adapter": engine.lower(), "case": "coin-coulomb-skid-1",
            "setting": setting, "wall_s": 2.0, "outcome": "ok",
            "score": {"min_digits": digits, "worst": "phidot at t = 0.97", "energy_rel_drift": 0.11,
                      "energy_rel_error": 3e-3, "slip_speed_error": 0.5, "contact_height": 1e-6,
                      "contact_velocity": 36.4, "components": {"theta": {"final_digits": 2.0}}},
            "friction": {"mu": "0.3", "velocity": ["36.35", "0.0"],
                         "run": {"slides": slides, "n_slides": len(slides), "sticks_at": sticks_at, "slips_at": slips_at},
                         "reference": {"phases": ["sliding", "rolling"], "n_slides": 1, "switch_times": [0.0764715],
                                       "slips_at": None, "sticks_at": 0.0764715}}}


def test_words_for_a_coulomb_run_say_where_it_sticks():
    # a skid: the stick against the reference's; friction takes energy, so the energy drift is no error here
    ok = _coulomb_row("Fake", "best", [[0.0, 0.0761]], 0.0761)
    assert words(ok) == "right to the eye; sticks at t = 0.0761 (reference 0.0765)"
    assert words(_coulomb_row("Fake", "default", [[0.0, None]], None)) == \
        "right to the eye; never sticks (the reference slides from 0 to 0.0765)"
    chatter = _coulomb_row("Fake", "default", [[0.0, 0.08], [0.1, 0.11], [0.2, 0.21]], 0.08)
    assert words(chatter).endswith("sticks at t = 0.0800 (reference 0.0765), then slides 2 more times")
    # rolls, slides, rolls: both ends of the slide
    slip = dict(ok, friction={"run": {"slides": [[0.0793, 0.0965]], "n_slides": 1, "slips_at": 0.0793, "sticks_at": 0.0965},
                              "reference": {"n_slides": 1, "slips_at": 0.078, "sticks_at": 0.0966}})
    assert words(slip).endswith("slides from 0.0793 to 0.0965 (reference 0.0780 to 0.0966)")
    never = dict(slip, friction=dict(slip["friction"], run={"slides": [], "n_slides": 0, "slips_at": None, "sticks_at": None}))
    assert words(never).endswith("never slides (the reference slides from 0.0780 to 0.0966)")
    unscored = dict(ok, score=None, outcome="error: score: unknown reference case")
    assert words(unscored).startswith("no score: error: score") and words(unscored).endswith("(reference 0.0765)")


def test_a_coulomb_case_renders_with_its_energy_error_and_slides():
    board = {"cases": [{"case": "coin-coulomb-skid-1", "t_end_run": None, "coulomb": {"mu": "0.3", "velocity": ["36.35", "0"]}}],
             "machine": "a CPU", "sources": {"commit": "abc"},
             "rows": [_coulomb_row("Fake", "best", [[0.0, 0.0761]], 0.0761)]}
    text = "\n".join(render_markdown(board))
    assert "Coulomb friction mu = 0.3, starts sliding" in text
    assert ("| Fake 1 | best | 1.60 (phidot at t = 0.97) | 2.00 | 3.0e-03 | 5.0e-01 | 1.0e-06 | 0.0000 to 0.0761 | 2 | "
            "right to the eye; sticks at t = 0.0761 (reference 0.0765) |") in text
    assert figure_png(board)[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_rerun_of_one_case_replaces_its_rows_and_keeps_the_others():
    old = {"cases": [{"case": "disk-standard-1", "t_end_run": None}, {"case": "coin-coulomb-skid-1", "t_end_run": None}],
           "sources": {"commit": "old"}, "machine": "m",
           "rows": [{"case": "disk-standard-1", "adapter": "fake", "setting": "best", "wall_s": 1},
                    {"case": "coin-coulomb-skid-1", "adapter": "fake", "setting": "best", "wall_s": 1},
                    {"case": "coin-coulomb-skid-1", "adapter": "other", "setting": "best", "wall_s": 1}]}
    new = {"cases": [{"case": "coin-coulomb-skid-1", "t_end_run": None}], "sources": {"commit": "new"}, "machine": "m",
           "rows": [{"case": "coin-coulomb-skid-1", "adapter": "fake", "setting": "best", "wall_s": 2}]}
    merged = merge_boards(old, new)
    assert [c["case"] for c in merged["cases"]] == ["disk-standard-1", "coin-coulomb-skid-1"]
    assert [(r["case"], r["adapter"], r["wall_s"]) for r in merged["rows"]] == [
        ("disk-standard-1", "fake", 1), ("coin-coulomb-skid-1", "other", 1), ("coin-coulomb-skid-1", "fake", 2)]
    assert merged["sources"]["commit"] == "new" and merged["rows"][0]["sources"]["commit"] == "old"


def test_the_board_holds_both_coulomb_cases_over_their_whole_second():
    assert ("coin-coulomb-slip-1", None) in CASES and ("coin-coulomb-skid-1", None) in CASES


def test_engines_refuses_a_case_that_is_not_on_the_board(capsys, tmp_path):
    from verify.cli import main

    code = main(["engines", "--case", "disk-fig2-circle", "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 2 and "--case 'disk-fig2-circle': not a case of the board" in err and "coin-coulomb-skid-1" in err
    assert not (tmp_path / "engines.json").exists()
