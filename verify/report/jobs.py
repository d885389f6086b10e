"""The report's jobs: every computation behind a number or figure of the report, as a registry.

A :class:`Job` names a function of this module (so a worker process can run it by name), its
JSON-ready arguments and the modules it starts from (which, with their imports and data files,
make its cache key: :mod:`.dependencies`).  Each job function returns a :class:`JobOutput`:
JSON-ready ``data`` for results.json, the figures it draws (:class:`~.figures.Image`), and wall
times, which go to timing.json only (results.json must be the same bytes on every run).

The jobs are as fine as the work allows, so both cores stay busy and a change recomputes
little: one per claim module, threshold case, stability map, conservation model, retrograde
mechanism and quad reference case.
"""
from __future__ import annotations

import importlib
import time
from dataclasses import dataclass, field
from typing import Any

#: Reference-check precisions; quad is one job per case (about 7 s each), the others one job each.
REFERENCE_PRECISIONS = ("double", "long", "quad")


@dataclass(frozen=True)
class Job:
    """One unit of the report's computation.

    ``name`` is unique and path-like (``claims/disk``, ``reference/quad/disk-fig3-lhs``);
    ``function`` a function of this module (or ``package.module:name``) called as ``function(*args)``; ``modules`` the
    modules whose import closure the result depends on; ``files`` further data files it reads.
    """

    name: str
    function: str
    args: tuple = ()
    modules: tuple = ()
    files: tuple = ()


@dataclass
class JobOutput:
    data: Any
    images: list = field(default_factory=list)
    timing: dict = field(default_factory=dict)


def registry() -> list:
    """Every job of the report, in the order the report presents their results."""
    from ..claims import SECTION_MODULES  # lazy: main process only; the workers import this module
    from ..reference.proved import proved_directory  # lazy: main process only; the workers import this module
    from ..reference.store import DIRECTORY, read_index  # lazy: main process only; the workers import this module
    from ..studies.conservation import conservation_models  # lazy: main process only; the workers import this module
    from ..studies.retrograde import MECHANISMS  # lazy: main process only; the workers import this module
    from ..studies.summary import MAPS, THRESHOLD_CASES  # lazy: main process only; the workers import this module

    from ..claims.base import PAPER_FILE  # lazy: main process only; the workers import this module

    jobs = [Job(f"claims/{m}", "claims_job", (m,), (f"verify.claims.{m}", "verify.report.claim_records",
                                                   "verify.report.figures"), (str(PAPER_FILE),)) for m in SECTION_MODULES]
    jobs += [Job(f"conservation/{m}", "conservation_job", (m,), ("verify.studies.conservation",))
             for m in conservation_models()]
    jobs += [Job(f"thresholds/{_case_name(*case)}", "threshold_job", case, ("verify.studies.summary",))
             for case in THRESHOLD_CASES]
    jobs += [Job(f"studies/{n}", f"{n}_job", (), ("verify.studies.summary",)) for n in ("captions", "spindown", "precision")]
    jobs += [Job(f"maps/{model}-{motion}", "map_job", (model, motion),
                 ("verify.studies.summary", "verify.report.study_figures")) for model, motion in MAPS]
    jobs.append(Job("dissipation", "dissipation_job", (), ("verify.studies.dissipation", "verify.report.study_figures")))
    jobs += [Job(f"retrograde/{m}", "retrograde_job", (m,), ("verify.studies.retrograde", "verify.report.retrograde"))
             for m in MECHANISMS]
    jobs += friction_jobs()
    jobs.append(Job("bodies", "bodies_job", (), ("verify.studies.bodies",),
                    tuple(str(p) for p in sorted(_bodies_directory().glob("*.toml")))))
    jobs.append(Job("bodies/thresholds", "body_thresholds_job", (), ("verify.studies.body_thresholds",),
                    tuple(str(p) for p in sorted(_bodies_directory().glob("*.toml")))))
    jobs.append(Job("tippe-top", "tippe_top_job", (), ("verify.studies.tippe.report",),
                    tuple(str(p) for p in _tippe_files())))
    index = read_index()
    index_file = str(DIRECTORY / "index.json")
    for precision in REFERENCE_PRECISIONS:
        groups = [[e] for e in index["cases"]] if precision == "quad" else [index["cases"]]
        for group in groups:
            label = group[0]["name"] if len(group) == 1 else "all"
            proofs = [str(p) for e in group for p in sorted(proved_directory().glob(f"{e['name']}.*bit.json"))]
            jobs.append(Job(f"reference/{precision}/{label}", "reference_job", (precision, [e["name"] for e in group]),
                            ("verify.reference",), (index_file, *(str(DIRECTORY / e["file"]) for e in group), *proofs)))
    return jobs


def _bodies_directory():
    from models.bodies import DIRECTORY as bodies  # lazy: main process only; the workers import this module

    return bodies


def friction_jobs() -> list:
    """The friction section's jobs: one per paper figure with runs, the reference cases, the steady
    families, and per dissipation law the slip on the quasi-steady drift and in the damped run (one job:
    the run's slip event is switched on near the drift's slip times)."""
    from models.dissipative import LAW_NAMES  # lazy: main process only; the workers import this module
    from .figure_friction import figure_numbers  # lazy: main process only; the workers import this module

    study = ("verify.studies.friction",)
    jobs = [Job(f"friction/figures/fig-{n}", "friction_figure_job", (n,), ("verify.report.figure_friction",))
            for n in figure_numbers()]
    jobs += [Job("friction/reference", "friction_reference_job", (), study),
             Job("friction/steady", "friction_steady_job", (), study)]
    jobs += [Job(f"friction/slip/{law}", "friction_slip_job", (law,), study) for law in LAW_NAMES]
    jobs += [Job("friction/coulomb", "coulomb_examples_job", (), ("verify.studies.coulomb_examples",))]
    return jobs


def _case_name(model: str, motion: str, params: dict) -> str:
    from models import ring as ring_body  # lazy: main process only; the workers import this module

    if model.startswith("ring"):
        tag = ring_body.parameter_set_name(params) or "custom"
    else:
        tag = "-".join(f"{k}{v}" for k, v in sorted(params.items())) or "defaults"
    return f"{model}-{motion}-{tag}"


def function_of(job: Job):
    """The job's function (``function``: a name in this module, or ``package.module:name``)."""
    if ":" in job.function:
        module, _, name = job.function.partition(":")
        return getattr(importlib.import_module(module), name)
    return globals()[job.function]


def run(job: Job) -> JobOutput:
    """Run one job in this process."""
    return function_of(job)(*job.args)


# --- the job functions -----------------------------------------------------------------------

def claims_job(module: str) -> JobOutput:
    """Evaluate every claim of ``verify.claims.<module>``: their records and their figures."""
    from .claim_records import claim_record  # lazy: a worker loads only its job's modules
    from .figures import render  # lazy: a worker loads only its job's modules

    claims = importlib.import_module(f"verify.claims.{module}").claims()
    records, images, timing = [], [], {}
    for claim in claims:
        t0 = time.monotonic()
        ev = claim.evaluate()
        figs = [render(fig) for fig in ev.figures]
        records.append(claim_record(claim, ev, figs))
        images += figs
        timing[claim.id] = round(time.monotonic() - t0, 2)
    return JobOutput(records, images, {"claims": timing})


def conservation_job(model: str) -> JobOutput:
    from ..studies.conservation import conservation_rows  # lazy: a worker loads only its job's modules

    return JobOutput(conservation_rows(models=(model,)))


def threshold_job(model: str, motion: str, params: dict) -> JobOutput:
    from ..studies.summary import threshold_case_rows  # lazy: a worker loads only its job's modules

    return JobOutput(threshold_case_rows(model, motion, params))


def captions_job() -> JobOutput:
    from ..studies.summary import caption_rows  # lazy: a worker loads only its job's modules

    return JobOutput(caption_rows())


def spindown_job() -> JobOutput:
    from ..studies.summary import spindown_rows  # lazy: a worker loads only its job's modules

    return JobOutput(spindown_rows())


def precision_job() -> JobOutput:
    from ..studies.summary import precision_rows  # lazy: a worker loads only its job's modules

    return JobOutput(precision_rows())


def map_job(model: str, motion: str) -> JobOutput:
    from ..studies.summary import map_row  # lazy: a worker loads only its job's modules
    from .study_figures import render_map  # lazy: a worker loads only its job's modules

    row, smap, timing = map_row(model, motion)
    return JobOutput(row, [render_map(smap)], timing)


def dissipation_job() -> JobOutput:
    from ..studies.dissipation import dissipation_study, to_record  # lazy: a worker loads only its job's modules
    from .study_figures import render_dissipation  # lazy: a worker loads only its job's modules

    laws = dissipation_study()
    return JobOutput([to_record(s) for s in laws], [render_dissipation(laws)],
                     {"laws": {s.law: round(s.run.wall_seconds, 2) for s in laws}})


def retrograde_job(mechanism: str) -> JobOutput:
    from ..studies.retrograde import run_study  # lazy: a worker loads only its job's modules
    from .retrograde import figures  # lazy: a worker loads only its job's modules

    study = run_study(mechanisms=(mechanism,))
    summary = study.summaries[mechanism]
    seconds = summary.pop("seconds")  # wall time: timing.json only
    return JobOutput(summary, list(figures(mechanism, *study.sweeps[mechanism]).values()), {"sweep_seconds": seconds})


def reference_job(precision: str, names: list) -> JobOutput:
    from ..reference import check_set  # lazy: a worker loads only its job's modules

    return JobOutput([c.to_record() for c in check_set(precision, names)])



def friction_figure_job(figure: int) -> JobOutput:
    from .figure_friction import figure_rows  # lazy: a worker loads only its job's modules

    return JobOutput(figure_rows(figure))


def friction_reference_job() -> JobOutput:
    from ..studies.friction import reference_rows  # lazy: a worker loads only its job's modules

    return JobOutput(reference_rows())


def friction_steady_job() -> JobOutput:
    from ..studies.friction import steady_rows  # lazy: a worker loads only its job's modules

    return JobOutput(steady_rows())


def coulomb_examples_job() -> JobOutput:
    from ..studies.coulomb_examples import examples  # lazy: a worker loads only its job's modules

    return JobOutput(examples())


def _tippe_files() -> list:
    from models.bodies import DIRECTORY  # lazy: a worker loads only its job's modules

    return sorted(DIRECTORY.glob("tippe-top*.toml"))


def bodies_job() -> JobOutput:
    from ..studies.bodies import rows  # lazy: a worker loads only its job's modules

    return JobOutput(rows())


def body_thresholds_job() -> JobOutput:
    """The shipped bodies' steady motions and thresholds, each checked by the nonlinear equations and, for the
    paper's bodies, by the built-in model's threshold (:mod:`verify.studies.body_thresholds`, ~60 s); a
    disagreement fails the job."""
    from ..studies.body_thresholds import failures, rows  # lazy: a worker loads only its job's modules

    table = rows()
    bad = failures(table)
    if bad:
        raise RuntimeError("body thresholds: " + "; ".join(bad))
    return JobOutput(table)


def tippe_top_job() -> JobOutput:
    """The tippe top under the smooth law and exact Coulomb friction (:mod:`verify.studies.tippe`, ~80 s)."""
    from ..studies.tippe.report import job_data  # lazy: a worker loads only its job's modules

    return JobOutput(job_data())


def friction_slip_job(law: str) -> JobOutput:
    from ..studies.friction import slip_runs, transported_slip  # lazy: a worker loads only its job's modules

    drift = transported_slip(law)
    return JobOutput({"drift": drift, "run": slip_runs(law, drift)})
