"""The batch road's front door (verify/engine/ensemble.py, verify/engine/lanes.py): lanes are independent,
parameters go by name, the events and guards are the single road's, one model resolution per chunk or
map, and no module outside the engine room (and the named exceptions) imports heyoka."""
from __future__ import annotations

import ast
import math
from pathlib import Path

import numpy as np
import pytest

from verify.engine import batch, ensemble as ensemble_module
from verify.engine.ensemble import ensemble
from verify.engine.single import solve

ROOT = Path(__file__).resolve().parents[1]
WIDTH = 4
T_END = 2.0
GRID = np.linspace(0.0, T_END, 201)
#: Disk starts (theta, thetadot, phidot, psidot) and the event solve stops each at (None: none in 2 s); the
#: contact cases are tests/test_contact_event.py's.
STARTS = [((1.2, 0.0, 1.0, 4.0), None), ((1.5, -5.0, 0.0, 0.0), "contact_lost"), ((1.0, 0.0, 0.0, 0.0), "lies_flat"),
          ((2.0, 5.0, 0.0, 0.0), "contact_lost"), ((0.8, 1.0, 2.0, 6.0), None), ((1.4, -0.5, -1.0, 9.0), None)]


def _disk():
    return ensemble("disk", "full", WIDTH, 2 * T_END + 1)


def _inputs(ens, starts, values=None):
    """States and lane parameters of ``starts``, padded to whole batches."""
    n = len(starts)
    pad = batch.pad_lanes(n, WIDTH)
    states = np.zeros((8, n))
    for j, (th, thd, phd, psd) in enumerate(starts):
        states[[0, 3, 4, 5], j] = th, thd, phd, psd
    values = dict(values or {"k": 0.25, "g": 980.0})
    values.setdefault("theta_max", float(ens.model.domain.theta_max))
    return np.ascontiguousarray(states[:, pad]), ens.parameters(len(pad), values)


def _run(ens, states, pars, threads=1):
    (batches, messages), = ens.propagate(states, pars, GRID, threads, max_delta_t=ens.step_cap([9.0], 980.0))
    assert not messages
    return (np.concatenate([b.output for b in batches], axis=2), np.concatenate([b.local.pars for b in batches], axis=1))


def test_a_lane_gets_the_bits_it_gets_alone_in_a_batch_of_its_width():
    """Lanes do not interact (each has its own steps and events): a lane run alone, in a batch of copies
    of itself, gives the very bits it gave among other partners, whether it froze on an event or not."""
    ens = _disk()
    states, pars = _inputs(ens, [s for s, _ in STARTS])
    out, final = _run(ens, states, pars, threads=2)
    reasons = ens.record(final, "reason")
    assert (reasons > 0).any() and (reasons == 0).any()  # frozen and running lanes are both compared
    for k in range(len(STARTS)):
        one, warned = ens.alone(GRID, states[:, k], pars[:, k], max_delta_t=ens.step_cap([9.0], 980.0))
        assert not warned and ens.failure(one, 0, warned) is None
        assert one.output[:, :, 0].tobytes() == out[:, :, k].tobytes()
        assert one.local.pars[:, 0].tobytes() == final[:, k].tobytes()


def test_parameters_go_by_name_whatever_the_order_of_the_mapping():
    """The lane parameters are laid out by name: permuting the mapping changes no bit of a run.  Negative
    control: the same values laid out by the mapping's order (k and g swapped) give another run."""
    ens = _disk()
    starts = [s for s, _ in STARTS[:3]]
    values = {"k": 0.25, "g": 980.0, "theta_max": math.pi, "alive": 1.0}
    permuted = dict(reversed(list(values.items())))
    a, b = ens.parameters(4, values), ens.parameters(4, permuted)
    assert a.tobytes() == b.tobytes()
    out_a, _ = _run(ens, _inputs(ens, starts, values)[0], a)
    out_b, _ = _run(ens, _inputs(ens, starts, permuted)[0], b)
    assert out_a.tobytes() == out_b.tobytes()
    by_order = a.copy()
    by_order[: 2] = np.array(list(permuted.values())[2:])[:, None]  # g where k belongs and k where g does
    out_c, _ = _run(ens, _inputs(ens, starts)[0], by_order)
    assert out_c.tobytes() != out_a.tobytes()
    columns = ens.model_columns({"g": 980.0, "k": np.array([0.25, 0.5])})
    assert columns.tolist() == [[0.25, 0.5], [980.0, 980.0]]


@pytest.mark.parametrize("bad,message", [({"k": 0.25}, "no value for the lane parameter 'g'"),
                                         ({"k": 0.25, "g": 980.0, "mass": 1.0}, "'mass' is not a lane parameter")])
def test_a_missing_or_unknown_lane_parameter_is_named(bad, message):
    ens = _disk()
    with pytest.raises(KeyError, match=message):
        ens.parameters(4, {**bad, "theta_max": math.pi} if "g" in bad else bad)


def test_events_fire_as_in_the_single_road():
    """Each lane stops at the event solve stops the same start at, at the same time to the flow's
    conditioning: batch lanes and solve integrate the same equations with different steps, so states
    agree to ~eps sqrt(steps) |Phi| (1e-16 x 30 x 1e3 by t = 2 s) and an event time to that over |N'|
    or |thetadot| (order 1 to 100 here): 1e-9 s leaves a margin of ~300."""
    ens = _disk()
    states, pars = _inputs(ens, [s for s, _ in STARTS])
    _, final = _run(ens, states, pars)
    for k, ((th, thd, phd, psd), event) in enumerate(STARTS):
        sol = solve("disk", T_END, {"theta": repr(th), "thetadot": repr(thd), "phidot": repr(phd), "psidot": repr(psd)})
        reason = int(ens.record(final, "reason")[k])
        assert (ens.event_name(reason) if reason else None) == event
        assert sol.outcome == ("ok" if event is None else f"event:{event}")
        if event is not None:
            assert abs(float(ens.record(final, "t_stop")[k]) - float(sol.t_events[event])) < 1e-9
            assert ens.record(final, "alive")[k] == 0.0


def test_a_lane_that_breaks_a_guard_is_reported_failed(monkeypatch):
    """Negative control of the guards: with the events' freezing switched off (as if heyoka had missed
    them) the lanes that should have stopped run on past the domain or the contact, and the guard on
    their samples names them failed; the lanes that never reach an event are kept."""
    ens = ensemble("disk", "full", WIDTH, 2 * T_END + 1.5)  # its own cooldown: its own template
    starts = [s for s, _ in STARTS]
    states, pars = _inputs(ens, starts)
    n = len(starts)

    def guarded():
        out, final = _run(ens, states, pars)
        model_pars = ens.model_columns({"k": 0.25, "g": 980.0}, n)
        reason = ens.record(final, "reason")[:n]
        samples = np.ascontiguousarray(np.transpose(out[:, :, :n], (1, 2, 0)))  # (states, lanes, grid)
        return ens.guard(GRID, samples, model_pars, reason != 0, ens.record(final, "t_stop")[:n])

    assert guarded() == [None] * n  # the events froze them: nothing to flag
    monkeypatch.setattr(batch.Freeze, "__call__", lambda self, ta, d_sgn, lane: True)
    flagged = guarded()
    for (_, event), failure in zip(STARTS, flagged):
        if event is None:
            assert failure is None
        else:
            assert failure is not None and failure[0] in ("failed:event_detection", "failed:non_finite")


def test_the_step_cap_reads_the_models_own_g(tmp_path):
    """sqrt(g) of the model's g parameter: a sweep's [params] g, else the model's default (no fallback)."""
    from verify.sweep import parse
    from verify.sweep.engine import fastest_rate

    text = ("[sweep]\nname = \"g\"\nmodel = \"disk\"\nt_end = 1\nsamples = 11\nchunk = 4\nstore = \"{s}\"\n{p}"
            "[start]\ntheta = 1.2\n\n[[axis]]\nname = \"psidot\"\nfrom = 1\nto = 2\ncount = 2\n\n"
            "[record]\nquantities = [\"max_theta\"]\n")
    default = parse(text.format(s=tmp_path / "a.sqlite", p=""))
    low_g = parse(text.format(s=tmp_path / "b.sqlite", p="[params]\ng = 1\n\n"))
    assert fastest_rate(default) == math.sqrt(980.0)
    assert fastest_rate(low_g) == 2.0  # the psidot axis, not sqrt(980) nor sqrt(1)


def test_one_model_resolution_per_chunk(tmp_path, monkeypatch):
    """The sweep resolves its model once (the ensemble's), not once per helper; its modules and the
    maps' hold no get_model of their own."""
    from verify.studies import map_runs, maps
    from verify.sweep import engine, parse, spec

    calls = []
    real = ensemble_module.get_model
    monkeypatch.setattr(ensemble_module, "get_model", lambda name, *a: calls.append(name) or real(name, *a))
    ensemble_module.clear()
    ensemble_module.resolve.cache_clear()
    try:
        sweep = parse(f"[sweep]\nname = \"one\"\nmodel = \"body:hoop\"\nt_end = 0.5\nsamples = 11\nchunk = 4\n"
                      f"store = \"{tmp_path / 'one.sqlite'}\"\n[start]\nphidot = 1.0\npsidot = 4.0\n[[axis]]\n"
                      "name = \"theta\"\nfrom = 0.6\nto = 1.2\ncount = 6\n[record]\nquantities = [\"max_theta\"]\n")
        rows = engine.run_chunk(sweep, 0, 1, WIDTH) + engine.run_chunk(sweep, 1, 1, WIDTH)
    finally:
        monkeypatch.undo()
        ensemble_module.clear()
        ensemble_module.resolve.cache_clear()
    assert [r["outcome"] for r in rows] == ["ok"] * 6
    assert calls == ["body:hoop"]
    for module in (engine, spec, map_runs, maps):
        assert not hasattr(module, "get_model"), module.__name__


def test_a_body_file_has_no_stability_map_and_says_why():
    from verify.studies.maps import stability_map

    with pytest.raises(ValueError, match="a body file has no steady-motion study"):
        stability_map("body:hoop", "diameter-spin")


#: Modules that may import heyoka: the engine room, the benchmarks' bare baselines, the precisions' types
#: and the provenance's versions.
HEYOKA_ALLOWED = ("verify/engine/", "verify/bench/", "verify/precision.py", "verify/provenance.py")


def _imports_heyoka(path: Path) -> bool:
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import) and any(a.name.split(".")[0] == "heyoka" for a in node.names):
            return True
        if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "heyoka" and not node.level:
            return True
    return False


def test_no_heyoka_outside_the_engine_room():
    found = [str(p.relative_to(ROOT)) for p in sorted((ROOT / "verify").rglob("*.py")) if _imports_heyoka(p)]
    assert found, "the scan found no import at all: it would pass whatever the tree holds"
    assert [f for f in found if not f.startswith(HEYOKA_ALLOWED)] == []


def test_a_bare_lane_system_is_the_yardstick_not_a_route():
    """compile_lanes(bare=True): the same equations without the alive factor, only the events asked for,
    parameters only as far as the system reads them; a choice of events is refused for the suite's lanes."""
    from verify.engine.lanes import compile_lanes

    model = _disk().model
    bare = compile_lanes(model, "full", WIDTH, 5.0, bare=True, events=("contact_lost",))
    assert bare.events == ("contact_lost",) and bare.layout.names == ("k", "g")
    alive = f"p{_disk().lanes.layout['alive']}"
    assert all(alive in str(rhs) for _, rhs in _disk().lanes.template.sys)  # the suite's lanes freeze
    assert not any(alive in str(rhs) for _, rhs in bare.template.sys)
    with pytest.raises(ValueError, match="a choice of events is for a bare baseline"):
        compile_lanes(model, "full", WIDTH, 5.0, events=("contact_lost",))
